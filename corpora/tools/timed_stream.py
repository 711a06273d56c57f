#!/usr/bin/env python3
"""Timed STEP/DIR streams from a trapezoid planner: a small motion controller
of this project's own, for test and corpus data.

A job (a seeded mix of polygons, circles drawn as short chords, spirals and
travel moves; with --axes 3 a Z lift between shapes) is planned as a
controller does it:

- per move a trapezoid speed profile with the acceleration limited per axis
  (the path acceleration is the smallest axis limit divided by that axis's
  share of the move), the nominal speed limited per axis the same way;
- junction speeds by the junction-deviation rule, then a backward and a
  forward pass over the whole job (unlimited look-ahead);
- with --scurve, S-shaped ramps instead: the speed follows a smoothstep
  (3u^2 - 2u^3) from one speed to the next, its peak acceleration the
  limit (the planner works with 2/3 of it, the mean acceleration of such a
  ramp, so ramps take 1.5 times as long as trapezoid ones);
- a segment generator that cuts the profile into constant-rate stepper
  segments of --segment-ms (a segment is stretched until it holds a step);
- a stepper interrupt at the segment's rate in CPU cycles, a Bresenham line
  per move over the axes (counters start at half the event count), with
  AMASS-like smoothing: below rate thresholds the interrupt runs 2, 4 or 8
  times faster and the Bresenham increments shrink accordingly;
- a move's DIR levels are set in the interrupt that starts it (an axis the
  move does not step is driven to 0), steps come from the next interrupt on;
  with --pipeline instead (as Grbl orders its interrupt) the interrupt that
  loads a move computes its first step event, and every step and the DIR
  levels leave with the next interrupt;
- --amass-levels 0 turns the smoothing off; --period-unit K rounds periods
  above K cycles down to a multiple of K (a timer prescaler of K).

Output: one byte per tick of --tick-us, bit 2i = axis i stepped in the tick,
bit 2i+1 = axis i DIR level (1 = negative) at the end of the tick; the
stream runs from the tick of the first step to the tick of the last step.
With --report FILE, a JSON list of the planned moves (steps, entry, nominal,
exit speed in steps/s of the leading axis, acceleration in steps/s^2 of the
leading axis) is written too; with --moves FILE, the same moves' signed
step counts, a line of one integer per axis each (the moves a reader of
the stream should find: tests/timed_moves_test.cpp). With --isr-log FILE
(not with --pipeline), the interrupt's true timing, a text line per tick
of the stream: the move's leading axis (its Bresenham major axis, the one that steps every 2^level
interrupts), the step-smoothing level, and how far the leading axis is
through its interval between two steps at the tick's end, in 1/2^24 of
the interval (interrupts since its last step plus the share of the next
one elapsed, over 2^level; -1 0 0 before the first interrupt). A model
of the stream can be measured against it: the slots of the interrupt
grid that each tick crosses, known exactly.

Usage: timed_stream.py [--axes 2|3] [--seed N] [--shapes N] [--steps-mm X]
                       [--rate MM_PER_MIN] [--accel MM_PER_S2] [--jd MM] [--scurve]
                       [--tick-us US] [--segment-ms MS] [--cpu-mhz MHZ]
                       [--amass-levels 0-3] [--pipeline] [--period-unit K]
                       [--report FILE] [--moves FILE] [--isr-log FILE] > out.steps
"""
import argparse
import json
import math
import random
import sys


def job(rng, shapes, axes):
    """The path in mm: a list of (target point, feed mm/min or None for travel)."""
    moves = []
    pos = [0.0] * axes
    for k in range(shapes):
        cx, cy = rng.uniform(5, 115), rng.uniform(5, 75)
        kind = k % 4
        pts = []
        if kind == 0:  # regular polygon
            n, r, a0 = rng.randint(3, 8), rng.uniform(2, 12), rng.uniform(0, math.pi)
            pts = [(cx + r * math.cos(a0 + 2 * math.pi * i / n), cy + r * math.sin(a0 + 2 * math.pi * i / n))
                   for i in range(n + 1)]
        elif kind == 1:  # circle as chords
            n, r = rng.randint(24, 72), rng.uniform(3, 15)
            pts = [(cx + r * math.cos(2 * math.pi * i / n), cy + r * math.sin(2 * math.pi * i / n))
                   for i in range(n + 1)]
        elif kind == 2:  # spiral
            n, r = rng.randint(40, 90), rng.uniform(4, 14)
            pts = [(cx + r * i / n * math.cos(0.3 * i), cy + r * i / n * math.sin(0.3 * i)) for i in range(n)]
        else:  # a zig-zag hatch
            n, w, h = rng.randint(3, 9), rng.uniform(5, 20), rng.uniform(0.5, 2)
            for i in range(n):
                y = cy + i * h
                pts += [(cx, y), (cx + w, y)] if i % 2 == 0 else [(cx + w, y), (cx, y)]
        feed = rng.choice([600, 1200, 1800, 2400])
        if axes == 3:
            moves.append(([pos[0], pos[1], 2.0], None))  # lift
            moves.append(([pts[0][0], pts[0][1], 2.0], None))
            moves.append(([pts[0][0], pts[0][1], 0.0], feed / 2))  # plunge
            for p in pts[1:]:
                moves.append(([p[0], p[1], 0.0], feed))
            pos = [pts[-1][0], pts[-1][1], 0.0]
        else:
            moves.append(([pts[0][0], pts[0][1]], None))
            for p in pts[1:]:
                moves.append(([p[0], p[1]], feed))
            pos = [pts[-1][0], pts[-1][1]]
    moves.append(([0.0] * axes, None))
    return moves


def plan(moves, a):
    """Move blocks in steps with trapezoid speeds in mm/s along the path."""
    spm, rate, acc = a.steps_mm, a.rate, a.accel
    blocks = []
    cur = [0] * a.axes
    prev_unit = None
    for target, feed in moves:
        tgt = [round(t * spm[i]) for i, t in enumerate(target)]
        d = [tgt[i] - cur[i] for i in range(a.axes)]
        if not any(d):
            continue
        mm = [d[i] / spm[i] for i in range(a.axes)]
        length = math.sqrt(sum(v * v for v in mm))
        unit = [v / length for v in mm]
        nominal = min(rate[i] / 60 / abs(unit[i]) for i in range(a.axes) if unit[i] != 0)
        if feed is not None:
            nominal = min(nominal, feed / 60)
        accel = min(acc[i] / abs(unit[i]) for i in range(a.axes) if unit[i] != 0)
        if a.scurve:
            accel /= 1.5  # the mean acceleration of a smoothstep ramp whose peak is the limit
        vj = 0.0
        if prev_unit is not None:
            cos_t = -sum(prev_unit[i] * unit[i] for i in range(a.axes))
            if cos_t < 0.999999:
                cos_t = max(cos_t, -0.999999)
                sin_half = math.sqrt(0.5 * (1 - cos_t))
                vj = math.sqrt(accel * a.jd * sin_half / (1 - sin_half))
        blocks.append(dict(d=d, length=length, nominal=nominal, accel=accel, vj_max=vj, scurve=a.scurve))
        prev_unit = unit
        cur = tgt
    # Entry speeds: junction limit, reachable backward from a stop, then forward.
    n = len(blocks)
    for i, b in enumerate(blocks):
        b['entry'] = min(b['vj_max'], b['nominal'], blocks[i - 1]['nominal'] if i else 0.0)
    nxt = 0.0
    for b in reversed(blocks):
        b['entry'] = min(b['entry'], math.sqrt(nxt * nxt + 2 * b['accel'] * b['length']))
        nxt = b['entry']
    v = 0.0
    for i, b in enumerate(blocks):
        b['entry'] = v
        nxt = blocks[i + 1]['entry'] if i + 1 < n else 0.0
        b['exit'] = min(nxt, math.sqrt(v * v + 2 * b['accel'] * b['length']))
        v = b['exit']
    for b in blocks:
        v0, v1, A, L = b['entry'], b['exit'], b['accel'], b['length']
        acc_d = (b['nominal'] ** 2 - v0 * v0) / (2 * A)
        dec_d = (b['nominal'] ** 2 - v1 * v1) / (2 * A)
        if acc_d + dec_d > L:  # triangle: the peak speed where the ramps meet
            acc_d = max(0.0, min(L, (L + (v1 * v1 - v0 * v0) / (2 * A)) / 2))
            b['cruise'] = math.sqrt(v0 * v0 + 2 * A * acc_d)
            dec_d = L - acc_d
        else:
            b['cruise'] = b['nominal']
        b['acc_d'], b['dec_d'] = acc_d, dec_d
    return blocks


def position(b, t):
    """Distance along the move at time t from its start, and the move's duration."""
    v0, vc, v1, A = b['entry'], b['cruise'], b['exit'], b['accel']
    t1 = (vc - v0) / A
    t3 = (vc - v1) / A
    cruise_d = b['length'] - b['acc_d'] - b['dec_d']
    t2 = cruise_d / vc if vc > 0 else 0.0
    total = t1 + t2 + t3
    if t <= t1:
        if b['scurve'] and t1 > 0:
            u = t / t1
            return v0 * t + (vc - v0) * t1 * (u ** 3 - u ** 4 / 2), total
        return v0 * t + 0.5 * A * t * t, total
    if t <= t1 + t2:
        return b['acc_d'] + vc * (t - t1), total
    if t < total:
        u = t - t1 - t2
        if b['scurve'] and t3 > 0:
            w = u / t3
            return b['acc_d'] + cruise_d + vc * u - (vc - v1) * t3 * (w ** 3 - w ** 4 / 2), total
        return b['acc_d'] + cruise_d + vc * u - 0.5 * A * u * u, total
    return b['length'], total


def run(blocks, a):
    cpu = a.cpu_mhz * 1e6
    tick_cycles = a.tick_us * a.cpu_mhz
    seg_s = a.segment_ms / 1000
    # Rate thresholds in cycles per step: level l runs the interrupt 2^l times per step.
    amass_limits = [cpu / 8000, cpu / 4000, cpu / 2000][:a.amass_levels]
    top = a.amass_levels  # the Bresenham counters' scale: steps << top
    events = []  # (cycle, step mask, dir levels)
    # --isr-log: per interrupt, (the cycle its steps leave, the move's leading
    # axis, level, interrupts since the leading axis's last step, period).
    isrs = []
    cycle = 0
    dirs = 0
    pending = 0  # --pipeline: the step mask computed in the last interrupt, output in the next
    out_dirs = 0  # --pipeline: the DIR levels the pins show (set at a load, output one interrupt later)
    for b in blocks:
        d = b['d']
        count = max(abs(v) for v in d)
        new_dirs = sum(1 << i for i in range(a.axes) if d[i] < 0)
        if a.pipeline:
            dirs = new_dirs  # output with the next interrupt's step bits
        else:
            events.append((cycle, 0, new_dirs))  # DIR set in the interrupt that loads the move
            dirs = new_dirs
        counters = [count << top >> 1] * a.axes
        major = max(range(a.axes), key=lambda i: abs(d[i]))
        since_major = 0
        done = 0
        t = 0.0
        total = position(b, 0.0)[1]
        while done < count:
            t_end = t + seg_s
            while True:
                s, _ = position(b, min(t_end, total))
                target = min(count, int(s / b['length'] * count + 1e-9)) if t_end < total else count
                if target > done or t_end >= total:
                    break
                t_end += seg_s
            n = max(1, target - done)
            period = max(1, int(round((min(t_end, total) - t) * cpu / n)))
            level = sum(1 for lim in amass_limits if period > lim)
            isr = period >> level
            if isr > a.period_unit:
                isr -= isr % a.period_unit  # a timer prescaler: the period in whole timer counts
            for _ in range(n << level):
                mask = 0
                for i in range(a.axes):
                    counters[i] += (abs(d[i]) << top) >> level
                    if counters[i] > (count << top):
                        counters[i] -= count << top
                        mask |= 1 << i
                if a.pipeline:
                    events.append((cycle, pending, out_dirs))
                    out_dirs, pending = dirs, mask
                    cycle += isr
                else:
                    cycle += isr
                    if mask:
                        events.append((cycle, mask, dirs))
                    if a.isr_log:
                        since_major = 0 if mask >> major & 1 else since_major + 1
                        isrs.append((cycle, major, level, since_major, isr))
            done += n
            t = min(t_end, total)
        if not a.pipeline:
            cycle += isr
    if a.pipeline:
        events.append((cycle, pending, out_dirs))
    # Bin into ticks, from the first step's tick to the last step's tick.
    steps = [e for e in events if e[1]]
    if a.pipeline:  # keep the interrupts that step or change DIR
        kept, level = [], 0
        for e in events:
            if e[1] or e[2] != level:
                kept.append(e)
            level = e[2]
        events = kept
    first = int(steps[0][0] // tick_cycles)
    last = int(steps[-1][0] // tick_cycles)
    out = bytearray(last - first + 1)
    level = 0
    ei = 0
    # DIR levels before the first step are those of the first move.
    for tick in range(first, last + 1):
        end = (tick + 1) * tick_cycles
        while ei < len(events) and events[ei][0] < end:
            c, mask, dl = events[ei]
            level = dl
            for i in range(a.axes):
                if mask >> i & 1:
                    if out[tick - first] >> (2 * i) & 1:
                        sys.exit('two steps of one axis in one tick: use a shorter --tick-us')
                    out[tick - first] |= 1 << (2 * i)
            ei += 1
        for i in range(a.axes):
            if level >> i & 1:
                out[tick - first] |= 2 << (2 * i)
    if a.isr_log:
        write_isr_log(a.isr_log, isrs, first, last, tick_cycles)
    return bytes(out)


def write_isr_log(path, isrs, first, last, tick_cycles):
    """Writes --isr-log: per tick from `first` to `last`, the last interrupt
    before the tick's end and how far the leading axis is through its interval
    there."""
    lines = []
    j = -1
    for tick in range(first, last + 1):
        end = (tick + 1) * tick_cycles
        while j + 1 < len(isrs) and isrs[j + 1][0] < end:
            j += 1
        if j < 0:
            lines.append('-1 0 0')
            continue
        cycle, major, level, since, period = isrs[j]
        share = (since + (end - cycle) / period) / (1 << level)
        lines.append('%d %d %d' % (major, level, int(share * (1 << 24))))
    with open(path, 'w') as f:
        f.write('\n'.join(lines) + '\n')


def main():
    p = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    p.add_argument('--axes', type=int, default=2, choices=[2, 3])
    p.add_argument('--seed', type=int, default=1)
    p.add_argument('--shapes', type=int, default=12)
    p.add_argument('--steps-mm', type=float, nargs='+', default=[80.0])
    p.add_argument('--rate', type=float, nargs='+', default=[6000.0], help='mm/min per axis')
    p.add_argument('--accel', type=float, nargs='+', default=[500.0], help='mm/s^2 per axis')
    p.add_argument('--jd', type=float, default=0.02, help='junction deviation, mm')
    p.add_argument('--tick-us', type=float, default=20.0)
    p.add_argument('--segment-ms', type=float, default=10.0)
    p.add_argument('--cpu-mhz', type=int, default=16)
    p.add_argument('--scurve', action='store_true', help='S-shaped (smoothstep) speed ramps')
    p.add_argument('--amass-levels', type=int, default=3, choices=[0, 1, 2, 3],
                   help='step-smoothing levels (0: off, the interrupt runs at the step rate)')
    p.add_argument('--pipeline', action='store_true',
                   help='steps and DIR leave in the interrupt after the one that computes them, '
                        'the first step event of a move computed in the interrupt that loads it')
    p.add_argument('--period-unit', type=int, default=1,
                   help='interrupt periods above this many cycles are a multiple of it (a timer prescaler)')
    p.add_argument('--report')
    p.add_argument('--moves', help="the planned moves' signed step counts, a line each")
    p.add_argument('--isr-log', help='per tick, the interrupt grid the stream was made on (see above)')
    a = p.parse_args()
    if a.isr_log and a.pipeline:
        p.error('--isr-log does not go with --pipeline')
    for name in ('steps_mm', 'rate', 'accel'):
        v = getattr(a, name)
        setattr(a, name, (v * a.axes)[:a.axes] if len(v) == 1 else v[:a.axes])
    rng = random.Random(a.seed)
    blocks = plan(job(rng, a.shapes, a.axes), a)
    data = run(blocks, a)
    sys.stdout.buffer.write(data)
    if a.report:
        rep = []
        for b in blocks:
            lead = max(range(a.axes), key=lambda i: abs(b['d'][i]))
            k = abs(b['d'][lead]) / b['length']  # lead-axis steps per mm of path
            peak = 1.5 if a.scurve else 1.0  # the planner's acceleration is the mean of an S ramp
            rep.append(dict(steps=b['d'], entry=b['entry'] * k, cruise=b['cruise'] * k,
                            exit=b['exit'] * k, accel=b['accel'] * k * peak))
        with open(a.report, 'w') as f:
            json.dump(rep, f, indent=0)
    if a.moves:
        with open(a.moves, 'w') as f:
            for b in blocks:
                f.write(' '.join(str(v) for v in b['d']) + '\n')


if __name__ == '__main__':
    main()
