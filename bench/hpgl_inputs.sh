#!/bin/sh
# HP-GL text inputs for the CM raw block (docs/benchmarks.md "CM raw block"):
# tune.hpgl, the file its parameters were chosen on (plots other than
# corpora/tools/gnuplot_plots.gp's), and speed.hpgl (4.6 MB), twenty
# variants of it at other sizes and sample counts plus
# corpora/plotter/gnuplot.hpgl, for throughput.
# Usage: bench/hpgl_inputs.sh DIR   (needs gnuplot; Debian gnuplot-nox 5.4.4)
set -eu
dir=${1:?usage: hpgl_inputs.sh DIR}
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$dir"
cd "$dir"
cat > tune.gp <<'GP'
set terminal hpgl 8
set output 'tune.hpgl'
set size 0.25,0.25
set samples 300
set isosamples 24
set grid
set title 'Tuning curves'
plot [0:15] sin(x)*exp(-x/10), cos(1.5*x)/(1+x/5), x/15
set title 'Spirals'
set polar
set size square
plot [0:6*pi] t/20, 0.3*sin(5*t)
unset polar
set size nosquare
set title 'Surface B'
set hidden3d
splot [-2:2][-2:2] cos(x*x+y*y)*exp(-(x*x+y*y)/4)
set title 'Bars'
set style fill empty
plot [0:40] floor(6*cos(x/5)+8) with steps, abs(4*sin(x/3)) with impulses
GP
gnuplot tune.gp
for s in 1 2 3 4 5 6 7 8; do
  sed "s/tune.hpgl/big$s.hpgl/; s/samples 300/samples $((200 + s * 50))/; s/isosamples 24/isosamples $((18 + s * 2))/; s/0.25,0.25/0.$((20 + s)),0.$((20 + s))/" tune.gp > b$s.gp
  gnuplot b$s.gp
done
for s in 9 10 11 12 13 14 15 16 17 18 19 20; do
  sed "s/tune.hpgl/big$s.hpgl/; s/samples 300/samples $((600 + s * 80))/; s/isosamples 24/isosamples $((20 + s * 2))/; s/0.25,0.25/0.$((20 + s)),0.$((20 + s))/" tune.gp > b$s.gp
  gnuplot b$s.gp
done
cat big*.hpgl "$root/corpora/plotter/gnuplot.hpgl" > speed.hpgl
rm -f b*.gp big*.hpgl
ls -l tune.hpgl speed.hpgl
