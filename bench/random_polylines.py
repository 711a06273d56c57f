#!/usr/bin/env python3
"""G-code of random polylines, for bench inputs of several MB: COUNT
polylines of 3-12 vertices from random.Random(SEED), each vertex within
+-REACH of the one before on both axes, inside 0..SIZE.

Usage: bench/random_polylines.py COUNT SIZE REACH SEED > plot.gcode
then e.g. `stepzip interpolate --profile grbl plot.gcode > plot.fc`
(1500 8000 600 11: 3.79 MB of Freeman text, 3.79 M steps).
Only the Python 3 standard library is used."""
import random
import sys


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    count, size, reach, seed = (int(a) for a in sys.argv[1:])
    rng = random.Random(seed)
    out = []
    for _ in range(count):
        vertices = rng.randint(3, 12)
        x, y = rng.randint(0, size), rng.randint(0, size)
        out.append("G0 X%d Y%d" % (x, y))
        for _ in range(vertices - 1):
            x = max(0, min(size, x + rng.randint(-reach, reach)))
            y = max(0, min(size, y + rng.randint(-reach, reach)))
            out.append("G1 X%d Y%d" % (x, y))
    sys.stdout.write("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
