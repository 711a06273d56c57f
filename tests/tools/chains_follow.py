#!/usr/bin/env python3
"""Checks that vectors written by `stepzip segment` follow the chains they
came from: chain files A (the original) and B (the vectors interpolated
again), freeman format, the same number of chains; chain i of B starts and
ends where chain i of A does, and every corner of B (a point where its
direction changes) that is a segment end lies on chain i of A, in order.
Prints a one-line reason and exits 1 otherwise.
Usage: chains_follow.py A.fc B.fc VECTORS.hpgl
"""
import re
import sys

MOVES = [(1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1)]


def read_chains(path):
    chains = []
    with open(path) as f:
        for line in f:
            if not line.strip() or line.startswith("#"):
                continue
            x, y, codes = line.split()
            x, y = int(x), int(y)
            points = [(x, y)]
            for c in codes:
                dx, dy = MOVES[int(c)]
                x, y = x + dx, y + dy
                points.append((x, y))
            chains.append(points)
    return chains


def read_paths(path):
    """Pen-down paths of stepzip's own HP-GL: PU x,y; PD x,y,...; (absolute)."""
    with open(path) as f:
        text = f.read()
    paths = []
    for mnemonic, params in re.findall(r"(PU|PD)([-0-9,]*);", text):
        values = [int(v) for v in params.split(",") if v]
        pairs = list(zip(values[0::2], values[1::2]))
        if mnemonic == "PU":
            if pairs:
                paths.append([pairs[-1]])
        else:
            paths[-1].extend(pairs)
    return paths


def main():
    a, b = read_chains(sys.argv[1]), read_chains(sys.argv[2])
    paths = read_paths(sys.argv[3])
    if not (len(a) == len(b) == len(paths)):
        sys.exit(f"{len(a)} chains, {len(b)} read back, {len(paths)} paths")
    for i, (ca, cb, path) in enumerate(zip(a, b, paths), 1):
        if ca[0] != cb[0] or ca[-1] != cb[-1]:
            sys.exit(f"chain {i}: {ca[0]}..{ca[-1]} came back as {cb[0]}..{cb[-1]}")
        k = 0
        for vertex in path:
            while k < len(ca) and ca[k] != vertex:
                k += 1
            if k == len(ca):
                sys.exit(f"chain {i}: vertex {vertex} is not on the chain (in order)")


if __name__ == "__main__":
    main()
