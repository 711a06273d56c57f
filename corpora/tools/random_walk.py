#!/usr/bin/env python3
"""Random-walk chains, the worst case for reverse interpolation: every step
independent and uniform over the 8 (or 4) Freeman directions.
Usage: random_walk.py 8|4 STEPS SEED > walk.fc"""
import random
import sys

conn, n, seed = int(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3])
rng = random.Random(seed)
codes = '01234567' if conn == 8 else '0246'
print('# random walk, %d-connected, %d steps, seed %d' % (conn, n, seed))
line = []
for i in range(n):
    line.append(rng.choice(codes))
print('0 0 ' + ''.join(line))
