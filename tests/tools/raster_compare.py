#!/usr/bin/env python3
"""Compares two drawings rendered to PBM (by hp2xx): how much of each one's
ink lies within D pixels of the other's.

Prints "recall R precision P": R = share of the black pixels of A within D
pixels (Chebyshev) of a black pixel of B, P = the same from B to A; exits 1
when either is below MIN (default 0.97), or when the pictures differ in size.
Usage: raster_compare.py A.pbm B.pbm [D [MIN]]
Also: raster_compare.py --bbox FILE.hpgl prints "xmin xmax ymin ymax" of the
PU/PD coordinate pairs of an HP-GL file that stepzip wrote (absolute only).
"""
import re
import sys


def read_pbm(path):
    with open(path, "rb") as f:
        data = f.read()
    tokens = []
    pos = 0
    while len(tokens) < 3:
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b"#":
            while data[pos:pos + 1] not in (b"\n", b""):
                pos += 1
            continue
        start = pos
        while not data[pos:pos + 1].isspace():
            pos += 1
        tokens.append(data[start:pos])
    pos += 1
    magic, width, height = tokens[0], int(tokens[1]), int(tokens[2])
    if magic != b"P4":
        sys.exit(f"{path}: not a binary PBM")
    stride = (width + 7) // 8
    black = set()
    for y in range(height):
        row = data[pos + y * stride:pos + (y + 1) * stride]
        for bx, byte in enumerate(row):
            if byte:
                for bit in range(8):
                    if byte & (0x80 >> bit):
                        x = bx * 8 + bit
                        if x < width:
                            black.add((x, y))
    return width, height, black


def near_share(a, b, d):
    if not a:
        return 1.0
    hits = 0
    for (x, y) in a:
        found = False
        for dy in range(-d, d + 1):
            for dx in range(-d, d + 1):
                if (x + dx, y + dy) in b:
                    found = True
                    break
            if found:
                break
        hits += found
    return hits / len(a)


def bbox(path):
    text = open(path, encoding="latin-1").read()
    xs, ys = [], []
    for m in re.finditer(r"P[UD]([-0-9,]*)", text):
        nums = [int(v) for v in m.group(1).split(",") if v]
        xs += nums[0::2]
        ys += nums[1::2]
    print(min(xs), max(xs), min(ys), max(ys))


def main():
    if sys.argv[1] == "--bbox":
        bbox(sys.argv[2])
        return
    d = int(sys.argv[3]) if len(sys.argv) > 3 else 2
    least = float(sys.argv[4]) if len(sys.argv) > 4 else 0.97
    wa, ha, a = read_pbm(sys.argv[1])
    wb, hb, b = read_pbm(sys.argv[2])
    if (wa, ha) != (wb, hb):
        print(f"sizes differ: {wa}x{ha} and {wb}x{hb}")
        sys.exit(1)
    if not a or not b:
        print(f"empty picture: {len(a)} and {len(b)} black pixels")
        sys.exit(1)
    r, p = near_share(a, b, d), near_share(b, a, d)
    print(f"recall {r:.4f} precision {p:.4f} ({len(a)} and {len(b)} black pixels)")
    sys.exit(0 if r >= least and p >= least else 1)


if __name__ == "__main__":
    main()
