#!/usr/bin/env python3
"""Counts what an HP-GL file draws: pen-down vertices and pen-down paths.

Reads the instructions stepzip and hp2xx both understand (IN, PU, PD, PA, PR;
labels and device-control escapes are skipped) and prints
"vertices PATHS_SEGMENTS paths N": a vertex is one coordinate pair the pen
moves to while down and that differs from where it is.
Usage: hpgl_count.py FILE
"""
import re
import sys


def strip_escapes(text):
    # HP RS-232 device-control sequences: ESC . letter [parameters] ':'
    return re.sub(r"\x1b\.[A-Za-z@][^:]*:?|\x1b\.[A-Za-z@]", "", text)


def count(text):
    text = strip_escapes(text)
    pen_down = False
    absolute = True
    x = y = 0
    vertices = 0
    paths = 0
    in_path = False
    i = 0
    n = len(text)
    while i < n:
        c = text[i]
        if not c.isalpha():
            i += 1
            continue
        mnemonic = text[i:i + 2].upper()
        i += 2
        if mnemonic == "LB":  # label: text up to ETX (0x03)
            end = text.find("\x03", i)
            i = n if end < 0 else end + 1
            continue
        j = i
        while j < n and not text[j].isalpha() and text[j] != ";":
            j += 1
        params = [p for p in re.split(r"[,\s]+", text[i:j].strip()) if p]
        i = j
        if mnemonic == "IN":
            pen_down, absolute, x, y = False, True, 0, 0
            in_path = False
            continue
        if mnemonic not in ("PU", "PD", "PA", "PR"):
            continue
        if mnemonic == "PU":
            pen_down = False
            in_path = False
        elif mnemonic == "PD":
            pen_down = True
        elif mnemonic == "PA":
            absolute = True
        elif mnemonic == "PR":
            absolute = False
        values = [float(p) for p in params]
        for k in range(0, len(values) - 1, 2):
            nx, ny = values[k], values[k + 1]
            if not absolute:
                nx, ny = x + nx, y + ny
            if pen_down and (nx, ny) != (x, y):
                vertices += 1
                if not in_path:
                    paths += 1
                    in_path = True
            x, y = nx, ny
    return vertices, paths


def main():
    with open(sys.argv[1], encoding="latin-1") as f:
        vertices, paths = count(f.read())
    print(f"vertices {vertices} paths {paths}")


if __name__ == "__main__":
    main()
