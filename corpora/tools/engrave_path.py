#!/usr/bin/env python3
"""Writes the tool path of an engraving job as absolute "x y z a" vertices in
motor steps: Hershey glyph strokes in X/Y, the tool lifted on Z between
strokes, and a rotary A axis that turns the work piece between text lines
(as on a ring or cylinder engraver). Usage:

    engrave_path.py SCALE FONT.jhf [FONT.jhf ...] > path.txt
"""
import sys

sys.path.insert(0, __file__.rsplit('/', 1)[0])
from hershey_gcode import read_jhf  # noqa: E402

LIFT = 60        # Z steps between cutting depth and travel height
A_PER_LINE = 90  # A steps per text line


def main():
    scale = int(sys.argv[1])
    width = 1600 * scale // 10
    a = 0
    z_up, z_down = 0, -LIFT
    print('# engraving tool path: x y z a (steps)')
    print(0, 0, z_up, a)
    x0 = 0
    for path in sys.argv[2:]:
        for left, right, strokes in read_jhf(path):
            if x0 + (right - left) * scale > width:
                x0 = 0
                a += A_PER_LINE
            for stroke in strokes:
                pts = [(x0 + (x - left) * scale, -y * scale) for x, y in stroke]
                print(pts[0][0], pts[0][1], z_up, a)
                print(pts[0][0], pts[0][1], z_down, a)
                for x, y in pts[1:]:
                    print(x, y, z_down, a)
                print(pts[-1][0], pts[-1][1], z_up, a)
            x0 += (right - left) * scale


if __name__ == '__main__':
    main()
