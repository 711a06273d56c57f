#!/usr/bin/env python3
"""Probe: a timed 2-axis STEP/DIR log taken apart into its path and its timing
(a measurement prototype, not the codec; docs/benchmarks.md "Timed streams:
path and timing apart").

Measures, for a log of one byte per tick (bit 0 X STEP, 1 X DIR, 2 Y STEP,
3 Y DIR):
- path: writes the log with its idle ticks dropped (--path OUT), the order of
  the step events without their times, to be compressed by stepzip as a
  steps log;
- timing by gaps: the cost of the ticks between step events under adaptive
  order-k models of the gaps (frequency counts per context, an escape to an
  order-0 count for a gap unseen in the context), with and without the
  events' axis masks as context;
- moves: greedy maximal digital straight segments over the step events, the
  leading axis's steps as abscissa and each following-axis step counted
  after the leading step before it (free phase, Debled-Rennesson's
  recognition), against the moves of the job (--job, G0/G1 XY in mm at
  --steps-mm, as timer_stepper_probe.py reads them);
- AMASS: a move simulated with the Bresenham counters that
  timer_stepper_probe.py models (increments (s << 3) >> L against
  (leading << 3), counters from half), its level L constant or changing every
  8 leading steps, and whether its events stay one such segment.

Usage: timed_split_probe.py LOG [--job JOB.nc] [--steps-mm 100] [--path OUT]
"""
import argparse
import collections
import importlib.util
import math
import os


def events(log):
    """The ticks that step, with their bytes."""
    return [(t, b) for t, b in enumerate(log) if b & 5]


def gap_cost(gaps, masks, order, with_mask):
    """Bits of the gaps under an adaptive order-`order` model."""
    ctx_counts = collections.defaultdict(collections.Counter)
    ctx_total = collections.Counter()
    zero = collections.Counter()
    zero_total = 0
    alphabet = len(set(gaps))
    bits = 0.0
    for i, g in enumerate(gaps):
        ctx = tuple(gaps[max(0, i - order):i])
        if with_mask:
            ctx += (masks[i], masks[i - 1] if i else -1)
        c, n = ctx_counts[ctx], ctx_total[ctx]
        if c[g]:
            p = c[g] / (n + 1)
        else:
            p = 1 / (n + 1) * (zero[g] + 0.5) / (zero_total + 0.5 * alphabet)
        bits -= math.log2(p)
        c[g] += 1
        ctx_total[ctx] += 1
        zero[g] += 1
        zero_total += 1
    return bits / 8


def unit(b):
    """(dx, dy) of a log byte (DIR high = negative)."""
    dx = (-1 if b & 2 else 1) if b & 1 else 0
    dy = (-1 if b & 8 else 1) if b & 4 else 0
    return dx, dy


def dss_length(steps, i, lead):
    """Events from i that form one digital straight segment with `lead` as
    the leading axis: a leading step closes the point (leading steps, the
    following axis's steps so far); at most one following step between two
    leading steps; signs constant."""
    fol = 1 - lead
    if steps[i][lead] == 0:
        return 0
    a, b, mu = 0, 1, 0
    uf = ul = lf = ll = (0, 0)
    x = y = pending = 0
    sign_lead = sign_fol = 0
    ok = i
    for j in range(i, len(steps)):
        d = steps[j]
        if d[lead]:
            if sign_lead == 0:
                sign_lead = d[lead]
            elif d[lead] != sign_lead:
                break
            nx, ny = x + 1, y + pending
            r = a * nx - b * ny
            if mu <= r < mu + b:
                if r == mu:
                    ul = (nx, ny)
                if r == mu + b - 1:
                    ll = (nx, ny)
            elif r == mu - 1:
                lf, ul = ll, (nx, ny)
                a, b = ny - uf[1], nx - uf[0]
                mu = a * nx - b * ny
            elif r == mu + b:
                uf, ll = ul, (nx, ny)
                a, b = ny - lf[1], nx - lf[0]
                mu = a * nx - b * ny - b + 1
            else:
                break
            x, y, pending = nx, ny, 0
            ok = j + 1
        if d[fol]:
            if sign_fol == 0:
                sign_fol = d[fol]
            elif d[fol] != sign_fol:
                break
            pending += 1
            if pending > 1:
                break
    return ok - i


def greedy_segments(steps):
    out, i = [], 0
    while i < len(steps):
        n = max(dss_length(steps, i, 0), dss_length(steps, i, 1), 1)
        out.append((i, i + n))
        i += n
    return out


def amass_events(sx, sy, levels):
    """Step events of a move (sx, sy >= 0) through the AMASS counters, the
    level taken from `levels` per 8 leading steps."""
    lead_total = max(sx, sy)
    e = lead_total << 3
    cx = cy = e >> 1
    out, done, k = [], 0, 0
    while done < lead_total:
        lv = levels[min(k // 8, len(levels) - 1)]
        for _ in range(1 << lv):
            cx += (sx << 3) >> lv
            cy += (sy << 3) >> lv
            dx = dy = 0
            if cx > e:
                cx -= e
                dx = 1
            if cy > e:
                cy -= e
                dy = 1
            if dx or dy:
                out.append((dx, dy))
            if dx if sx >= sy else dy:
                done += 1
                if done == lead_total:
                    break
        k += 1
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('log')
    ap.add_argument('--job')
    ap.add_argument('--steps-mm', type=float, default=100)
    ap.add_argument('--path')
    args = ap.parse_args()
    log = open(args.log, 'rb').read()
    ev = events(log)
    print(f'ticks {len(log)}, step events {len(ev)}')
    if args.path:
        with open(args.path, 'wb') as f:
            f.write(bytes(b for _, b in ev))
        print(f'path (idle ticks dropped) written to {args.path}')
    gaps = [ev[0][0]] + [ev[i][0] - ev[i - 1][0] for i in range(1, len(ev))]
    masks = [b & 5 for _, b in ev]
    print(f'gaps: {len(set(gaps))} distinct values')
    for order in (0, 1, 2, 3, 4):
        print(f'  order {order}: {gap_cost(gaps, masks, order, False):.0f} bytes,'
              f' with the axis masks {gap_cost(gaps, masks, order, True):.0f}')
    steps = [unit(b) for _, b in ev]
    segs = greedy_segments(steps)
    print(f'greedy segments over the events: {len(segs)}')
    if args.job:
        here = os.path.dirname(os.path.abspath(__file__))
        spec = importlib.util.spec_from_file_location(
            'probe', os.path.join(here, 'timer_stepper_probe.py'))
        probe = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(probe)
        moves = probe.read_moves(args.job, args.steps_mm)
        # ends compared in unit steps (a two-axis event counts two)
        cum = [0]
        for s in steps:
            cum.append(cum[-1] + abs(s[0]) + abs(s[1]))
        seg_ends = {cum[j] for _, j in segs}
        move_ends, t = set(), 0
        for m in moves:
            t += abs(m[0]) + abs(m[1])
            move_ends.add(t)
        print(f'  job moves {len(moves)}, ends shared with the segments {len(move_ends & seg_ends)}')
        print('  first moves (unit steps):', [abs(a) + abs(b) for a, b in moves[:12]])
        print('  first segments (unit steps):', [cum[j] - cum[i] for i, j in segs[:12]])
    print('AMASS simulation (events of one move: one segment or where it breaks):')
    for move in ((100, 37), (144, 70), (55, 54)):
        for levels in ([0], [1], [3], [3, 3, 2, 2, 1, 0, 0, 1, 2, 3], [0, 1, 2, 3, 3, 2, 1, 0]):
            evs = amass_events(*move, levels)
            n = max(dss_length(evs, 0, 0), dss_length(evs, 0, 1))
            verdict = 'one segment' if n == len(evs) else f'breaks at event {n}'
            print(f'  move {move} levels {levels}: {len(evs)} events, {verdict}')


if __name__ == '__main__':
    main()
