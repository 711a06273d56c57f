#!/usr/bin/env python3
"""How many of a job's moves `stepzip segment --format timed --to json` found
in its log: the moves it reports, the planned moves' ends that are ends of
its moves to the step, and the planned moves found whole (both ends, nothing
between). Positions are counted from the path's start; a path that comes
back to a point counts that point once.

Usage: timed_moves_check.py MOVES.json PLANNED [--steps-mm 100]

MOVES.json: the JSON of `stepzip segment --format timed --tick-us US --to
json` (its first chain). PLANNED: a `timed_stream.py --moves` file (a line
of signed step counts per move), a `timed_stream.py --report` JSON, or a
two-axis G-code job (G0/G1 X.. Y.. in absolute mm, read as
timer_stepper_probe.py reads it, at --steps-mm).
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import timer_stepper_probe  # noqa: E402  (read_moves)


def planned_moves(path, steps_mm):
    if path.endswith('.moves'):
        return [tuple(int(v) for v in line.split()) for line in open(path) if line.strip()]
    return timer_stepper_probe.read_moves(path, steps_mm)


def ends(moves, axes):
    at = [0] * axes
    out = []
    for m in moves:
        at = [at[i] + m[i] for i in range(axes)]
        out.append(tuple(at))
    return out


def main():
    p = argparse.ArgumentParser(description='moves of a timed log against its job')
    p.add_argument('moves_json')
    p.add_argument('planned')
    p.add_argument('--steps-mm', type=float, default=100)
    a = p.parse_args()
    found = [tuple(m['delta']) for m in json.load(open(a.moves_json))['chains'][0]['moves']]
    axes = len(found[0]) if found else 2
    plan = planned_moves(a.planned, a.steps_mm)
    index = {e: k for k, e in enumerate(ends(found, axes))}
    hits = whole = 0
    prev = -1
    for e in ends(plan, axes):
        k = index.get(e)
        hits += k is not None
        whole += k is not None and prev is not None and k == prev + 1
        prev = k
    print(f'moves {len(found)} planned {len(plan)} ends found {hits} whole {whole}')


if __name__ == '__main__':
    main()
