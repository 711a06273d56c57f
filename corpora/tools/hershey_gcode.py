#!/usr/bin/env python3
"""Writes a pen-plotter job (G-code, coordinates in steps) that draws a
specimen sheet of Hershey stroke fonts: every glyph of every font named, in
rows, as a plotter would be driven. Usage:

    hershey_gcode.py SCALE FONT.jhf [FONT.jhf ...] > job.gcode

SCALE is the number of motor steps per Hershey unit. Glyph coordinates in
.jhf files are letters offset from 'R'; " R" lifts the pen.
"""
import sys


def read_jhf(path):
    """Yields (left, right, strokes) per glyph; strokes are lists of (x, y)."""
    data = open(path, 'rb').read().decode('latin-1').replace('\r', '')
    lines = data.split('\n')
    i = 0
    while i < len(lines):
        line = lines[i]
        i += 1
        if len(line) < 8:
            continue
        count = int(line[5:8])
        body = line[8:]
        while len(body) < 2 * count and i < len(lines):
            body += lines[i]  # long glyphs continue on the next line
            i += 1
        left, right = ord(body[0]) - ord('R'), ord(body[1]) - ord('R')
        strokes, cur = [], []
        for k in range(1, count):
            a, b = body[2 * k], body[2 * k + 1]
            if a == ' ' and b == 'R':
                if cur:
                    strokes.append(cur)
                cur = []
            else:
                cur.append((ord(a) - ord('R'), ord(b) - ord('R')))
        if cur:
            strokes.append(cur)
        yield left, right, strokes


def draw_glyph(out, x0, y0, scale, left, strokes):
    """Writes a glyph's strokes as G0 to its first point and G1 through the
    rest, its left edge at x0 and its origin line at y0."""
    for stroke in strokes:
        # Hershey y grows downward
        pts = [(x0 + (x - left) * scale, y0 - y * scale) for x, y in stroke]
        out.write('G0 X%d Y%d\n' % pts[0])
        for p in pts[1:]:
            out.write('G1 X%d Y%d\n' % p)


def main():
    scale = int(sys.argv[1])
    page_width = 2400 * scale // 10
    out = sys.stdout
    out.write('; Hershey font specimen sheet, %d steps per font unit\n' % scale)
    out.write('G90\n')
    y0 = 0
    for path in sys.argv[2:]:
        out.write('; font %s\n' % path.rsplit('/', 1)[-1])
        x0 = 0
        for left, right, strokes in read_jhf(path):
            if x0 + (right - left) * scale > page_width:
                x0 = 0
                y0 -= 40 * scale
            draw_glyph(out, x0, y0, scale, left, strokes)
            x0 += (right - left) * scale
        y0 -= 48 * scale
    out.write('G0 X0 Y0\n')


if __name__ == '__main__':
    main()
