#!/usr/bin/env python3
"""Writes one freeman chain of N steps to stdout, streaming: "0 0 " then runs of
1-40 equal random Freeman digits (seed 1), then a newline. For the memory
test in docs/benchmarks.md: bench/long_chain.py 100000000 | stepzip compress -c - > big.stz"""
import sys, random
n = int(sys.argv[1]); random.seed(1)
parts = []
while sum(len(p) for p in parts) < 1 << 20:
    parts.append(random.choice("01234567") * random.randint(1, 40))
chunk = "".join(parts)[: 1 << 20].encode()
out = sys.stdout.buffer
out.write(b"0 0 ")
left = n
while left > 0:
    k = min(left, len(chunk)); out.write(chunk[:k]); left -= k
out.write(b"\n")
