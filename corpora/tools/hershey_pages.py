#!/usr/bin/env python3
"""Writes a pen-plotter job (G-code, coordinates in steps) that plots the
same page of text once per Hershey font, every page at the same place (the
plotter is given a new sheet between pages): glyphs that two fonts share
(many Hershey fonts share their digits, punctuation or whole alphabets)
recur at the same coordinates, pages apart. Usage:

    hershey_pages.py SCALE FONT.jhf [FONT.jhf ...] > job.gcode

SCALE is the number of motor steps per Hershey unit. The font reader is
hershey_gcode.py's, and so is the
drawing of a glyph.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hershey_gcode import draw_glyph, read_jhf  # noqa: E402

PAGE = [
    "The quick brown fox jumps over the lazy dog.",
    "Sphinx of black quartz, judge my vow!",
    "Pack my box with five dozen liquor jugs (1234567890).",
    "\"How vexingly quick daft zebras jump\" -- 12:45, 3/8 + 7% = ?",
    "#include <stdio.h> int main() { return a[i] * b_j ^ 2; }",
    "ZEPHYRS BLOW, VEXING DAFT JIM; WALTZ, NYMPH, FOR QUICK JIGS VEX BUD.",
]


def main():
    scale = int(sys.argv[1])
    out = sys.stdout
    out.write('; the same page of text in %d Hershey fonts, %d steps per font unit\n' %
              (len(sys.argv) - 2, scale))
    out.write('G90\n')
    for path in sys.argv[2:]:
        glyphs = list(read_jhf(path))  # ASCII 32..127 in order
        out.write('; page: font %s\n' % path.rsplit('/', 1)[-1])
        y0 = 0
        for line in PAGE:
            x0 = 0
            for ch in line:
                k = ord(ch) - 32
                if k < 0 or k >= len(glyphs):
                    continue
                left, right, strokes = glyphs[k]
                draw_glyph(out, x0, y0, scale, left, strokes)
                x0 += (right - left) * scale
            y0 -= 40 * scale
        out.write('G0 X0 Y0\n')


if __name__ == '__main__':
    main()
