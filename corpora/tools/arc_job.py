#!/usr/bin/env python3
"""A G-code job of random lines and arcs, in whole steps: MOVES moves per
path, PATHS paths (each starts with a G0 jump); lines of 20 to 200 steps in
any direction, arcs (G2/G3 with integer I J) of radius 15 to 150 steps
turning 60 to 300 degrees either way. Stepped by `stepzip interpolate
--arc-method M`, it is the job of docs/benchmarks.md "Arcs".
Usage: arc_job.py PATHS MOVES SEED > job.gcode"""
import math
import random
import sys

paths, moves, seed = int(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3])
rng = random.Random(seed)
print('; random lines and arcs: %d paths of %d moves, seed %d' % (paths, moves, seed))
print('G21 G90 G17')
arcs = 0
for p in range(paths):
    x, y = rng.randrange(-2000, 2000), rng.randrange(-2000, 2000)
    print('G0 X%d Y%d' % (x, y))
    for i in range(moves):
        if rng.random() < 0.5:
            length, a = 20 + 180 * rng.random(), 2 * math.pi * rng.random()
            x, y = x + round(length * math.cos(a)), y + round(length * math.sin(a))
            print('G1 X%d Y%d' % (x, y))
        else:
            r, a = 15 + 135 * rng.random(), 2 * math.pi * rng.random()
            cx, cy = x + round(r * math.cos(a)), y + round(r * math.sin(a))
            ccw = rng.random() < 0.5
            sweep = math.radians(60 + 240 * rng.random()) * (1 if ccw else -1)
            sx, sy = x - cx, y - cy
            ex = cx + round(sx * math.cos(sweep) - sy * math.sin(sweep))
            ey = cy + round(sx * math.sin(sweep) + sy * math.cos(sweep))
            print('G%d X%d Y%d I%d J%d' % (3 if ccw else 2, ex, ey, cx - x, cy - y))
            x, y = ex, ey
            arcs += 1
print('; %d arcs' % arcs)
