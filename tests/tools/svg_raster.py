#!/usr/bin/env python3
"""Draws chains over rsvg-convert's raster of the SVG they were stepped from.

The SVG must map user units to pixels one to one (viewBox "0 0 W H" and
width W, height H); `stepzip interpolate` maps a user point (x, y) to the
step (x, -y), so a chain point (X, Y) lies at pixel (floor(X), floor(-Y)).
Checks, with D pixels of slack (Chebyshev):
- every chain point has a painted pixel (alpha >= 128) within D;
- every painted pixel has a chain point within D.
Prints "points P ink I misses A/B" and exits 1 on any miss.
Usage: svg_raster.py PICTURE.png CHAINS.fc D
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from svg_check import decode_png, read_chains  # noqa: E402


def main():
    png, chains_path, d = sys.argv[1], sys.argv[2], int(sys.argv[3])
    width, height, pixel = decode_png(png)
    ink = {(x, y) for y in range(height) for x in range(width) if pixel(x, y)[3] >= 128}
    points = set()
    for pts, _ in read_chains(chains_path):
        for (x, y) in pts:
            points.add((math.floor(x), math.floor(-y)))

    def near(p, s):
        return any((p[0] + dx, p[1] + dy) in s
                   for dx in range(-d - 1, d + 1) for dy in range(-d - 1, d + 1)
                   if max(abs(dx + 0.5), abs(dy + 0.5)) <= d + 0.5)

    lost_points = [p for p in points if not near(p, ink)]
    lost_ink = [p for p in ink if not near(p, points)]
    print(f"points {len(points)} ink {len(ink)} misses {len(lost_points)}/{len(lost_ink)}")
    if not points or not ink or lost_points or lost_ink:
        if lost_points:
            print("chain points far from ink:", sorted(lost_points)[:10])
        if lost_ink:
            print("ink far from the chains:", sorted(lost_ink)[:10])
        sys.exit(1)


if __name__ == "__main__":
    main()
