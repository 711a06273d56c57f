#!/usr/bin/env python3
"""Checks a PNG that rsvg-convert rendered from `stepzip segment --to svg`
against the chains it shows, with the standard library only (zlib).

- the PNG has the SVG's width and height;
- every point of every chain is painted (alpha > 0) at the pixel the SVG's
  viewBox maps it to (x right, y up, margin from the viewBox);
- grid points at Chebyshev distance >= 2 steps from every chain point are
  background (alpha 0): nothing is drawn where the chain is not;
- points in the middle of an axis-parallel run carry the run colour (blue).
Usage: svg_check.py PICTURE.svg PICTURE.png CHAINS.fc
"""
import re
import struct
import sys
import zlib

MOVES = [(1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1)]


def decode_png(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit("not a PNG")
    pos, idat, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    width, height, depth, colour, _, _, interlace = header
    if depth != 8 or colour not in (2, 6) or interlace != 0:
        sys.exit(f"unexpected PNG layout: depth {depth} colour {colour} interlace {interlace}")
    bpp = 4 if colour == 6 else 3
    raw = zlib.decompress(idat)
    stride = width * bpp
    rows, prev, i = [], bytearray(stride), 0
    for _ in range(height):
        kind, line = raw[i], bytearray(raw[i + 1:i + 1 + stride])
        i += 1 + stride
        for k in range(stride):
            a = line[k - bpp] if k >= bpp else 0
            b = prev[k]
            c = prev[k - bpp] if k >= bpp else 0
            if kind == 1:
                line[k] = (line[k] + a) & 255
            elif kind == 2:
                line[k] = (line[k] + b) & 255
            elif kind == 3:
                line[k] = (line[k] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else b if pb <= pc else c
                line[k] = (line[k] + pred) & 255
        rows.append(line)
        prev = line

    def pixel(x, y):
        line = rows[y]
        px = line[x * bpp:(x + 1) * bpp]
        return tuple(px) if bpp == 4 else tuple(px) + (255,)

    return width, height, pixel


def read_chains(path):
    chains = []
    with open(path) as f:
        for line in f:
            if not line.strip() or line.startswith("#"):
                continue
            x, y, codes = line.split()
            x, y = int(x), int(y)
            points, runs = [(x, y)], []
            for k, c in enumerate(codes):
                dx, dy = MOVES[int(c)]
                x, y = x + dx, y + dy
                points.append((x, y))
            chains.append((points, codes))
    return chains


def segment_distance(p, a, b):
    (px, py), (ax, ay), (bx, by) = p, a, b
    dx, dy = bx - ax, by - ay
    t = 0.0 if dx == dy == 0 else max(0.0, min(1.0, ((px - ax) * dx + (py - ay) * dy) / (dx * dx + dy * dy)))
    return ((px - ax - t * dx) ** 2 + (py - ay - t * dy) ** 2) ** 0.5


COLOURS = {"#1f6fd1": 2, "#1e9e3a": 1, "#d1301f": 0}  # run, diagonal, slope: dominant channel


def main():
    svg_path, png_path, fc_path = sys.argv[1:4]
    svg = open(svg_path).read()
    m = re.search(r'viewBox="0 0 (\d+) (\d+)" width="(\d+)" height="(\d+)"', svg)
    if not m:
        sys.exit("no viewBox/width/height in the SVG")
    vw, vh, width, height = map(int, m.groups())
    w, h, pixel = decode_png(png_path)
    if (w, h) != (width, height):
        sys.exit(f"PNG is {w}x{h}, the SVG says {width}x{height}")
    chains = read_chains(fc_path)
    points = [p for ch, _ in chains for p in ch]
    xs, ys = [p[0] for p in points], [p[1] for p in points]
    min_x, max_x, min_y, max_y = min(xs), max(xs), min(ys), max(ys)
    margin = (vw - (max_x - min_x)) // 2
    sx, sy = width / vw, height / vh

    def to_view(x, y):
        return (x - min_x + margin, max_y - y + margin)

    def at_view(vx, vy):
        return pixel(min(int(vx * sx), width - 1), min(int(vy * sy), height - 1))

    def at(x, y):
        return at_view(*to_view(x, y))

    # the segments as drawn, in viewBox units
    lines = []
    for attrs in re.findall(r"<line ([^>]*)/>", svg):
        v = dict(re.findall(r'([\w-]+)="([^"]*)"', attrs))
        lines.append(((float(v["x1"]), float(v["y1"])), (float(v["x2"]), float(v["y2"])),
                      v["stroke"], "stroke-dasharray" in v))
    if not lines:
        sys.exit("the SVG draws no segment")

    for x, y in points:
        if at(x, y)[3] == 0:
            sys.exit(f"chain point ({x}, {y}) is not drawn")
    occupied = set(points)
    checked = 0
    for x in range(min_x - margin + 1, max_x + margin):
        for y in range(min_y - margin + 1, max_y + margin):
            if any((x + i, y + j) in occupied for i in range(-1, 2) for j in range(-1, 2)):
                continue
            v = to_view(x, y)
            if any(segment_distance(v, a, b) < 1.5 for a, b, _, _ in lines):
                continue
            checked += 1
            if at(x, y)[3] != 0:
                sys.exit(f"({x}, {y}) is 2 steps from the chains and segments but painted {at(x, y)}")
    coloured = 0
    for a, b, stroke, dashed in lines:
        length_px = ((b[0] - a[0]) ** 2 * sx * sx + (b[1] - a[1]) ** 2 * sy * sy) ** 0.5
        if dashed or length_px < 12 or stroke not in COLOURS:
            continue
        px = at_view((a[0] + b[0]) / 2, (a[1] + b[1]) / 2)
        channel = COLOURS[stroke]
        if px[3] == 0 or any(px[channel] <= px[k] for k in range(3) if k != channel):
            sys.exit(f"segment {a}-{b} should be {stroke} at its middle, found {px}")
        coloured += 1
    print(f"{width}x{height}: {len(points)} chain points drawn, {checked} background points "
          f"clear, {coloured} of {len(lines)} segments in their colour")


if __name__ == "__main__":
    main()
