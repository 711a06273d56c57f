# Plots written by gnuplot's hpgl terminal: the HP-GL a pen plotter receives.
# Run: gnuplot gnuplot_plots.gp (writes plots.hpgl in the current directory)
set terminal hpgl 8
set output 'plots.hpgl'
# a plot of about 2000 x 1500 plotter units: a few MB of steps in all
set size 0.2,0.2
set samples 400
set isosamples 30
set grid
set title 'Damped oscillations'
plot [0:20] exp(-x/8)*sin(2*x), exp(-x/5)*cos(3*x), besj0(x)
set title 'Polar roses'
set polar
set size square
plot [0:2*pi] sin(4*t), 0.5*cos(7*t)
unset polar
set size nosquare
set title 'Surface'
set hidden3d
splot [-3:3][-3:3] sin(x*y/2)*exp(-(x*x+y*y)/6)
set title 'Lissajous'
set parametric
plot [0:2*pi] sin(3*t), cos(4*t), sin(5*t)*0.8, cos(2*t)*0.8
unset parametric
set title 'Histogram and steps'
set style fill empty
plot [0:30] floor(8*sin(x/3)+10) with steps, floor(5*cos(x/4)+6) with impulses
