#!/usr/bin/env python3
"""Probe: how much of a timed STEP/DIR log a model of Grbl's stepper interrupt
reproduces tick for tick (a measurement prototype, not the codec).

Model (Grbl 1.1's segment generator and Timer1 interrupt with AMASS):
- a stepper segment has a step rate in CPU cycles per step, cps; its
  smoothing level L is decided by thresholds (--thresholds, cycles per step
  at which levels 1, 2, 3 begin: L = number of thresholds <= cps); the
  timer's compare value is cps >> L, the interrupt period P one cycle more
  (the timer counts 0..compare), at most 65536;
- a segment runs N = n << L interrupts for n steps of the move's leading
  axis; the Bresenham increments are a move's step counts << (3 - L)
  against its leading count << 3, counters starting at half of that at the
  move's first segment and carried across its segments;
- the interrupt that loads a segment (at cycle c) computes its first step
  event; every step leaves one interrupt later: the step of interrupt i
  (1..N) at cycle c + i*P; the next segment is loaded at c + N*P; a move's
  DIR levels leave with its second interrupt, c + P;
- segments last one --segment-cycles period (10 ms), the dt remainder of
  the partial step carried to the next one (so n*cps lies within one cps
  of it), several periods while under 1.25 steps in one, and the move's
  last segment ends with the move.

The moves' step counts come from the job (G-code read in single
precision with --steps-mm, or the --report JSON of timed_stream.py); the
timing is fitted: per segment L, n and P such that every step tick and DIR
change matches, each segment's feasible (c, P) a polygon whose end c + N*P
is passed on as an interval, with depth-first backtracking. Then integer
(c, P) are chosen per segment (a backward pass of the starts from which the
rest fits, a forward choice), the whole stream is regenerated from them and
compared tick for tick, and the cost of coding the segments is estimated:
per segment the step count n as one bit among the 10 ms rule's candidates,
the period as a signed Elias-gamma residual against a prediction carrying
the move's rate change from its previous two segments (0 when the predicted
period is one of the periods that fit), a move's first segment 19 bits; per
move the step counts as signed Elias-gamma codes.

With --restart the moves are those `stepzip segment --format timed --to
json` found in the log (JOB is that JSON): a move that does not fit is
passed over and the fit starts afresh at the next move's first step, with
its timing unknown; the probe then reports how many moves it fitted whole
and how many of the log's steps they hold (a coder that finds the moves in
the log would fit these; docs/benchmarks.md "Timed streams: the moves of a
log").

With --planner (JOB the G-code) the probe also runs Grbl 1.1's planner and
segment generator over the job (planner.c; stepper.c st_prep_buffer), in
single precision with a PC build's double intermediates (--planner-avr: the
AVR's, all single), and reports the predicted period of every fitted
segment against its fitted range, the cost with each period coded against
the prediction, and the log regenerated from the prediction alone.

Usage: timer_stepper_probe.py LOG JOB.nc|REPORT.json [--steps-mm 100]
         [--cycles-per-tick 640] [--thresholds 2000,4000,8000]
         [--segment-cycles 160000] [--segments OUT.json]
         [--planner [--planner-avr] [--planner-blocks 16]]
       timer_stepper_probe.py LOG MOVES.json --restart [...]
"""
import argparse
import bisect
import copy
import json
import math
import os
import struct
import subprocess
import sys
import time

LMAX = 3
PMAX = 65536  # the 16-bit compare value + 1


def f32(x):
    return struct.unpack('f', struct.pack('f', x))[0]


def read_float(text):
    """A decimal as a single-precision g-code reader makes it: the digits as
    an integer, then scaled by 0.01 and 0.1 (double constants, the result
    stored as single)."""
    neg = text.startswith('-'); text = text.lstrip('+-')
    whole, _, frac = text.partition('.')
    v = f32(float(int(whole + frac))); e = -len(frac)
    if v != 0:
        while e <= -2: v = f32(v * 0.01); e += 2
        if e < 0: v = f32(v * 0.1)
    return -v if neg else v


def lround(x):
    return int(math.floor(x + 0.5)) if x >= 0 else -int(math.floor(-x + 0.5))


def read_moves(path, steps_mm):
    """The moves' signed step counts: from a timed_stream.py report or a
    2-axis G-code job (G0/G1 X.. Y.., absolute mm)."""
    text = open(path).read()
    if path.endswith('.json'):
        doc = json.loads(text)
        if isinstance(doc, dict):  # stepzip segment --to json
            return [tuple(m['delta']) for m in doc['chains'][0]['moves']]
        return [tuple(b['steps']) for b in doc]
    return read_job(path, steps_mm, Arith(False))[0]


def read_log(path, axes):
    """Step ticks with their axis masks, and the DIR changes (tick, bits)."""
    d = open(path, 'rb').read()
    evt, evm, dirch = [], [], []
    prev = 0
    for t, b in enumerate(d):
        m = sum(((b >> (2 * a)) & 1) << a for a in range(axes))
        if m: evt.append(t); evm.append(m)
        db = sum(((b >> (2 * a + 1)) & 1) << a for a in range(axes))
        if db != prev: dirch.append((t, db)); prev = db
    return d, evt, evm, dirch


class Poly:
    """Feasible (c, P): c in [clo, chi], P in [plo, phi], lo_j <= c + i_j P <= hi_j."""
    def __init__(s, clo, chi, plo, phi):
        s.clo, s.chi, s.plo, s.phi = clo, chi, plo, phi
        s.cons = []

    def cmin(s, P):
        return max([s.clo] + [lo - i * P for i, lo, _ in s.cons])

    def cmax(s, P):
        return min([s.chi] + [hi - i * P for i, _, hi in s.cons])

    def add(s, i, lo, hi):
        """Adds a constraint and narrows [plo, phi]; False if nothing fits."""
        s.cons.append((i, lo, hi))
        g = lambda P: s.cmax(P) - s.cmin(P)  # concave in P
        a, b = s.plo, s.phi
        while b - a > 2:
            m1 = a + (b - a) // 3; m2 = b - (b - a) // 3
            if g(m1) < g(m2): a = m1
            else: b = m2
        best = max(range(a, b + 1), key=g)
        if g(best) < 0: return False
        lo, hi = s.plo, best
        while lo < hi:
            m = (lo + hi) // 2
            if g(m) >= 0: hi = m
            else: lo = m + 1
        s.plo = lo
        lo, hi = best, s.phi
        while lo < hi:
            m = (lo + hi + 1) // 2
            if g(m) >= 0: lo = m
            else: hi = m - 1
        s.phi = lo
        return True

    def end_range(s, N):
        """[min, max] of c + N P over the feasible set."""
        def least(f, a, b):  # f convex on the integers a..b
            while b - a > 2:
                m1 = a + (b - a) // 3; m2 = b - (b - a) // 3
                if f(m1) <= f(m2): b = m2
                else: a = m1
            return min(f(P) for P in range(a, b + 1))
        return (least(lambda P: s.cmin(P) + N * P, s.plo, s.phi),
                -least(lambda P: -(s.cmax(P) + N * P), s.plo, s.phi))

    def copy(s):
        p = Poly(s.clo, s.chi, s.plo, s.phi); p.cons = list(s.cons); return p


class Model:
    def __init__(s, ct, thresholds, seg):
        s.ct, s.thr, s.seg = ct, thresholds, seg

    def p_range(s, L):
        """Periods (compare value + 1) the threshold rule allows at level L."""
        lo = 1 if L == 0 else (s.thr[L - 1] >> L) + 1
        hi = s.thr[0] if L == 0 else (PMAX if L == LMAX else s.thr[L] >> L)
        return lo, hi

    def walk(s, S, E, cnt, L, poly, evt, evm, k, R):
        """Interrupts at level L from counters cnt against the observed step
        ticks from index k: the candidate ends (n, polygon, counters, k) for
        n = 1.. leading steps while everything matches."""
        inc = [v << (LMAX - L) for v in S]; thr = E << LMAX
        cnt = list(cnt); i = 0; n = 0; out = []
        while n < R:
            for _ in range(1 << L):
                i += 1; mask = 0
                for a in range(len(S)):
                    cnt[a] += inc[a]
                    if cnt[a] > thr: cnt[a] -= thr; mask |= 1 << a
                if mask:
                    if k >= len(evt) or evm[k] != mask: return out
                    t = evt[k]
                    if not poly.add(i, s.ct * t, s.ct * t + s.ct - 1): return out
                    k += 1
            n += 1
            out.append((n, poly.copy(), tuple(cnt), k))
            lo = ((poly.plo - 1) << L) - 1; hi = poly.phi << L
            kmax = 1 if hi < s.seg * 5 // 8 else 40  # stretched only below 1.25 steps a period
            if n * lo > s.seg * kmax + 2 * hi: break
        return out

    def rule(s, n, L, poly, R, first, cps_prev):
        """Whether n steps at this rate fill whole segment periods (the dt
        remainder carried: within one step's time), or end the move."""
        if n == R: return True
        lo = ((poly.plo - 1) << L) - 1; hi = poly.phi << L
        up = 0 if first else cps_prev
        for kk in range(1, 40):
            if n * hi >= s.seg * kk - hi and n * lo <= s.seg * kk + up: return True
            if s.seg * kk - hi > n * hi: break
        return False


def fit(model, moves, evt, evm, dirch, limit=3000, k0=0, dptr0=0, dcur0=0):
    """The deepest fit found: (step events matched, segments). It starts at
    step event k0, the next DIR change dirch[dptr0], DIR levels dcur0."""
    NA = len(moves[0])
    dirbits = [sum(1 << a for a in range(NA) if m[a] < 0) for m in moves]

    def start(b):
        E = max(abs(v) for v in moves[b])
        return tuple([(E << LMAX) >> 1] * NA), E

    def cands(st):
        b, cnt, R, k, clo, chi, cps_prev, first, dptr, dcur = st
        S = [abs(v) for v in moves[b]]; E = max(S)
        out = []; dcon = None; nd = dptr; ndcur = dcur
        if first and dirbits[b] != dcur:
            if dptr >= len(dirch) or dirch[dptr][1] != dirbits[b]: return []
            dcon = dirch[dptr][0]; nd = dptr + 1; ndcur = dirbits[b]
        for L in range(LMAX + 1):
            poly = Poly(clo, chi, *model.p_range(L))
            if dcon is not None and not poly.add(1, model.ct * dcon, model.ct * dcon + model.ct - 1):
                continue
            for n, p, cnt2, k2 in model.walk(S, E, cnt, L, poly, evt, evm, k, R):
                if not model.rule(n, L, p, R, first, cps_prev): continue
                e = p.end_range(n << L); cps = p.phi << L
                if n == R:
                    c2, E2 = start(b + 1) if b + 1 < len(moves) else ((), 0)
                    nst = (b + 1, c2, E2, k2, e[0], e[1], cps, True, nd, ndcur)
                else:
                    nst = (b, cnt2, R - n, k2, e[0], e[1], cps, False, nd, ndcur)
                mid = ((p.plo + p.phi) // 2) << L
                score = 0 if n == R and n * mid <= model.seg + cps_prev else \
                    min(abs(n * mid - model.seg * kk) for kk in range(1, 40))
                out.append((score, (L, n << L, b, p), nst))
        out.sort(key=lambda x: x[0])
        return [x[1:] for x in out]

    c0, E0 = start(0)
    stack = [[(0, c0, E0, k0, -(1 << 40), 1 << 40, 0, True, dptr0, dcur0), None, None, 0]]
    best = (k0, []); bt = 0
    while stack:
        fr = stack[-1]; st = fr[0]
        if st[0] >= len(moves):
            best = (st[3], [f[1] for f in stack[1:]]); break
        if fr[2] is None: fr[2] = cands(st)
        if fr[3] >= len(fr[2]):
            stack.pop(); bt += 1
            if bt > limit: break
            continue
        seg, nst = fr[2][fr[3]]; fr[3] += 1
        stack.append([nst, seg, None, 0])
        if nst[3] > best[0]:
            best = (nst[3], [f[1] for f in stack[1:]]); bt = 0
    return best


def concrete(segs):
    """Integer (c, P) per segment: a backward pass of the starts from which
    the rest fits (intervals), then a forward choice that looks one segment
    ahead. Returns the choices
    and the number of segments where the rest had to start afresh."""
    def periods(p):
        step = (p.phi - p.plo) // 40000 + 1
        return range(p.plo, p.phi + 1, step)
    back = [None] * (len(segs) + 1); back[-1] = (-(1 << 62), 1 << 62); breaks = 0
    for j in range(len(segs) - 1, -1, -1):
        L, N, b, p = segs[j]; A, B = back[j + 1]
        for attempt in (0, 1):
            lo = hi = None
            for P in periods(p):
                x, y = p.cmin(P), p.cmax(P)
                if attempt == 0: x, y = max(x, A - N * P), min(y, B - N * P)
                if x <= y:
                    lo = x if lo is None else min(lo, x); hi = y if hi is None else max(hi, y)
            if lo is not None: break
            breaks += 1
        back[j] = (lo, hi)
    def fits(j, c):
        """The periods of segment j that start at c and end where the rest fits."""
        L, N, b, p = segs[j]; A, B = back[j + 1]
        return [P for P in periods(p) if p.cmin(P) <= c <= p.cmax(P) and A <= c + N * P <= B]
    out = []; c = (back[0][0] + back[0][1]) // 2
    for j, (L, N, b, p) in enumerate(segs):
        A, B = back[j + 1]; mid = (A + B) // 2
        ok = sorted(fits(j, c), key=lambda P: abs(c + N * P - mid))
        # one segment of look-ahead: the intervals are wider than the integer starts
        got = next((P for P in ok[:64] if j + 1 == len(segs) or fits(j + 1, c + N * P)), None)
        if got is None and ok: got = ok[0]
        if got is None:
            got = next((P for P in periods(p) if p.cmin(P) <= c <= p.cmax(P)), p.plo)
        out.append((c, got)); c += N * got
        if not A <= c <= B: c = mid
    return out, breaks


def regenerate(model, moves, segs, conc, size):
    """The log the model writes from the segments' (L, N, move, c, P)."""
    NA = len(moves[0]); out = bytearray(size); dirs = []; prev = -1; cnt = None
    for (L, N, b, _), (c, P) in zip(segs, conc):
        S = [abs(v) for v in moves[b]]; E = max(S); thr = E << LMAX
        if b != prev:
            cnt = [thr >> 1] * NA; prev = b
            dirs.append((c + P, sum(1 << a for a in range(NA) if moves[b][a] < 0)))
        inc = [v << (LMAX - L) for v in S]
        for i in range(1, N + 1):
            for a in range(NA):
                cnt[a] += inc[a]
                if cnt[a] > thr:
                    cnt[a] -= thr
                    t = (c + i * P) // model.ct
                    if 0 <= t < size: out[t] |= 1 << (2 * a)
    dirs.sort(); di = 0; cur = 0
    for t in range(size):
        while di < len(dirs) and dirs[di][0] // model.ct <= t: cur = dirs[di][1]; di += 1
        for a in range(NA): out[t] |= ((cur >> a) & 1) << (2 * a + 1)
    return out


def gamma(v):
    """Bits of a signed Elias-gamma code."""
    return 2 * int(math.log2(2 * abs(v) + (1 if v < 0 else 0) + 1)) + 1


def cost(segs, conc, moves, pred=None):
    """Estimated bits: segments (step count, period) by their place in the
    move (first, second, later), moves (step counts). With pred (--planner:
    the planner's cycles per step for every segment) every period, a move's
    first too, is coded against the prediction, and a move pays a bit for
    G0/G1."""
    seg_bits = [0, 0, 0]; hist = []; misses = []
    for j, ((L, N, b, p), (c, P)) in enumerate(zip(segs, conc)):
        same = [r for bb, r in hist[-2:] if bb == b] if hist and hist[-1][0] == b else []
        if pred is not None:
            r = planner_miss(pred[j], L, p)
            seg_bits[min(len(same), 2)] += 1 + gamma(r); misses.append(abs(r))
        elif not same:
            seg_bits[0] += 19
        else:
            rate = 2 * same[-1] - same[0] if len(same) == 2 else same[-1]
            q = (round(1 / rate) >> L) if rate > 0 else P
            r = 0 if p.plo <= q <= p.phi else (q - p.phi if q > p.phi else q - p.plo)
            seg_bits[min(len(same), 2)] += 1 + gamma(r); misses.append(abs(r))
        hist.append((b, 1.0 / (P << L)))
    move_bits = sum(gamma(v) for m in moves for v in m) + (len(moves) if pred is not None else 0)
    misses.sort()
    return seg_bits, move_bits, misses


# --planner: Grbl 1.1's look-ahead planner (planner.c) and segment generator
# (stepper.c st_prep_buffer), re-implemented to predict every segment's step
# count and cycles per step from the job alone.

BLOCK_BUFFER_SIZE = 16   # planner ring: holds 15 blocks
SEGMENT_BUFFER_SIZE = 6  # segment ring: holds 5 segments
RAMP_ACCEL, RAMP_CRUISE, RAMP_DECEL, RAMP_DECEL_OVERRIDE = range(4)


class Arith:
    """How the build evaluates a C expression with a double constant (0.5*x,
    2.0*x, 1.0-x, DT_SEGMENT): in double on a PC build such as grbl-sim, in
    single on the AVR, where double is float. Float variables are single
    either way (f32 on every store); d() rounds a 'double' intermediate."""
    def __init__(s, avr):
        s.avr = avr
        s.d = f32 if avr else (lambda x: x)

    def read_float(s, text):
        if not s.avr: return read_float(text)
        neg = text.startswith('-'); text = text.lstrip('+-')  # the constants 0.01, 0.1 in single
        whole, _, frac = text.partition('.')
        v = f32(float(int(whole + frac))); e = -len(frac)
        if v != 0:
            while e <= -2: v = f32(v * f32(0.01)); e += 2
            if e < 0: v = f32(v * f32(0.1))
        return -v if neg else v


def read_job(path, steps_mm, ar):
    """A 2-axis G-code job (G0/G1 X.. Y.., absolute mm): the moves' signed
    step counts (the targets rounded to steps in single precision, as Grbl
    does), per move whether it is G0 and its feed (mm/min), and the X, Y
    settings of the job's $ lines (Grbl's DEFAULTS_GENERIC otherwise)."""
    st = {'100': '250', '101': '250', '110': '500', '111': '500', '120': '10', '121': '10', '11': '0.010'}
    pos = [0, 0]; feed = 0.0; rapid = True; moves = []; flags = []
    for line in open(path).read().split('\n'):
        if line.startswith('$') and '=' in line:
            k, v = line[1:].split('=', 1); st[k] = v; continue
        tgt = list(pos); motion = False
        for w in line.split():
            if w in ('G0', 'G1'): rapid = w == 'G0'; motion = True
            elif w[0] == 'F': feed = ar.read_float(w[1:])
            elif w[0] in 'XY':
                tgt['XY'.index(w[0])] = lround(f32(read_float(w[1:]) * f32(float(steps_mm))))
                motion = True
        dd = (tgt[0] - pos[0], tgt[1] - pos[1])
        if motion and any(dd): moves.append(dd); flags.append((rapid, feed))
        pos = tgt
    v = lambda k: ar.read_float(st[k])
    settings = dict(steps_mm=[v('100'), v('101')], max_rate=[v('110'), v('111')],
                    accel=[f32(f32(v(k) * 60) * 60) for k in ('120', '121')],  # mm/min²
                    jdev=v('11'))
    return moves, flags, settings


class Block:
    """A planner block. The segment generator shrinks mm as it goes."""
    pass


class Planner:
    """The ring of blocks with plan_buffer_line and planner_recalculate."""
    def __init__(s, ar, settings, size=BLOCK_BUFFER_SIZE):
        s.ar, s.size = ar, size
        s.spm, s.max_rate, s.accel, s.jdev = (settings[k] for k in ('steps_mm', 'max_rate', 'accel', 'jdev'))
        s.buf = [None] * size; s.tail = s.head = s.planned = 0
        s.prev_unit = None; s.prev_nominal = 0.0
        s.on_tail = lambda: None  # st_update_plan_block_parameters

    def nxt(s, i): return 0 if i + 1 == s.size else i + 1
    def prv(s, i): return (i or s.size) - 1
    def full(s): return s.tail == s.nxt(s.head)
    def current(s): return None if s.head == s.tail else s.buf[s.tail]

    def exit_speed_sqr(s):
        """The entry speed² of the block after the executing one (0 if none)."""
        i = s.nxt(s.tail)
        return 0.0 if i == s.head else s.buf[i].entry_sqr

    def discard(s):
        if s.head != s.tail:
            i = s.nxt(s.tail)
            if s.tail == s.planned: s.planned = i
            s.tail = i

    def unit_vector(s, v):
        """Normalises v in place, returns its length."""
        m = 0.0
        for x in v:
            if x != 0: m = f32(m + f32(x * x))
        m = f32(math.sqrt(m)); inv = f32(s.ar.d(1.0 / m))
        v[:] = [f32(x * inv) for x in v]
        return m

    @staticmethod
    def limit(maxv, unit):
        """The largest value along unit that keeps every axis within maxv."""
        lim = f32(1e38)
        for m, u in zip(maxv, unit):
            if u != 0: lim = min(lim, abs(f32(m / u)))
        return lim

    def nominal(s, b):
        """plan_compute_profile_nominal_speed, overrides at 100 %."""
        d = s.ar.d
        if b.rapid: v = f32(d(b.rapid_rate * d(0.01 * 100)))
        else:
            v = f32(d(b.feed * d(0.01 * 100)))
            if v > b.rapid_rate: v = b.rapid_rate
        return v if v > 1.0 else 1.0  # MINIMUM_FEED_RATE

    def add(s, k, delta, rapid, feed):
        """plan_buffer_line of move k (signed steps)."""
        d = s.ar.d; b = Block(); b.k = k
        b.events = max(abs(v) for v in delta)
        unit = [f32(v / m) for v, m in zip(delta, s.spm)]  # mm from the steps
        b.mm = s.unit_vector(unit)
        b.accel = s.limit(s.accel, unit); b.rapid_rate = s.limit(s.max_rate, unit)
        b.rapid, b.feed = rapid, feed
        if s.head == s.tail:  # empty buffer: from rest
            b.entry_sqr = 0.0; max_junction = 0.0
        else:  # junction deviation: the centripetal speed of the corner
            cos = 0.0
            for p, u in zip(s.prev_unit, unit): cos = f32(cos - f32(p * u))
            if cos > d(0.999999): max_junction = 0.0  # reversal: MINIMUM_JUNCTION_SPEED
            elif cos < d(-0.999999): max_junction = f32(1e38)  # straight on
            else:
                ju = [f32(u - p) for p, u in zip(s.prev_unit, unit)]
                s.unit_vector(ju)
                ja = s.limit(s.accel, ju)
                sin_d2 = f32(d(math.sqrt(d(0.5 * d(1.0 - cos)))))
                max_junction = f32(max(0.0, d(f32(f32(ja * s.jdev) * sin_d2) / d(1.0 - sin_d2))))
        nom = s.nominal(b)
        slower = s.prev_nominal if nom > s.prev_nominal else nom
        b.max_entry_sqr = min(f32(slower * slower), max_junction)
        s.prev_nominal = nom; s.prev_unit = unit
        s.buf[s.head] = b; s.head = s.nxt(s.head)
        s.recalculate()

    def recalculate(s):
        """planner_recalculate: a reverse pass from the newest block (exit 0)
        down to the planned pointer, then a forward pass that moves it on."""
        i = s.prv(s.head)
        if i == s.planned: return
        cur = s.buf[i]
        cur.entry_sqr = min(cur.max_entry_sqr, f32(f32(2 * cur.accel) * cur.mm))
        i = s.prv(i)
        if i == s.planned:
            if i == s.tail: s.on_tail()
        else:
            while i != s.planned:
                nx = cur; cur = s.buf[i]; i = s.prv(i)
                if i == s.tail: s.on_tail()
                if cur.entry_sqr != cur.max_entry_sqr:
                    e = f32(nx.entry_sqr + f32(f32(2 * cur.accel) * cur.mm))
                    cur.entry_sqr = e if e < cur.max_entry_sqr else cur.max_entry_sqr
        nx = s.buf[s.planned]; i = s.nxt(s.planned)
        while i != s.head:
            cur = nx; nx = s.buf[i]
            if cur.entry_sqr < nx.entry_sqr:
                e = f32(cur.entry_sqr + f32(f32(2 * cur.accel) * cur.mm))
                if e < nx.entry_sqr: nx.entry_sqr = e; s.planned = i
            if nx.entry_sqr == nx.max_entry_sqr: s.planned = i
            i = s.nxt(i)


class SegmentGenerator:
    """st_prep_buffer, one segment a call: (move, steps, cycles per step)."""
    def __init__(s, ar, planner, ticks_per_s=100, f_cpu=16000000):
        s.ar, s.pl = ar, planner
        s.dt_expr = ar.d(1.0 / ar.d(ticks_per_s * 60.0))  # DT_SEGMENT (min)
        s.dt_segment = f32(s.dt_expr)
        s.cycles_per_min = f32(float(f_cpu * 60))         # TICKS_PER_MICROSECOND*1000000*60
        s.block = None; s.recalc = False; s.replans = 0
        s.cur = s.exit = s.vmax = s.acc_until = s.dec_after = 0.0
        s.steps_rem = s.dt_rem = s.step_per_mm = s.req_mm = 0.0
        planner.on_tail = s.replanned

    def replanned(s):
        """st_update_plan_block_parameters: the planner changed the block being
        cut; its rest is re-profiled from the current speed."""
        if s.block is not None:
            s.recalc = True; s.replans += 1
            s.block.entry_sqr = f32(s.cur * s.cur)
            s.block = None

    def profile(s, b):
        """The block's ramps, as distances from its end: accelerate until
        acc_until, cruise at vmax, decelerate after dec_after to the next
        block's entry speed."""
        d = s.ar.d
        inv_2a = f32(d(0.5 / b.accel))
        s.ramp = RAMP_ACCEL; s.acc_until = b.mm
        exit_sqr = s.pl.exit_speed_sqr(); s.exit = f32(math.sqrt(exit_sqr))
        nom = s.pl.nominal(b); nom_sqr = f32(nom * nom)
        inter = f32(d(0.5 * f32(b.mm + f32(inv_2a * f32(b.entry_sqr - exit_sqr)))))
        if b.entry_sqr > nom_sqr:  # only after a re-plan that lowered the speed
            s.acc_until = f32(b.mm - f32(inv_2a * f32(b.entry_sqr - nom_sqr)))
            if s.acc_until <= 0:
                raise NotImplementedError('deceleration-only override')
            s.dec_after = f32(inv_2a * f32(nom_sqr - exit_sqr))
            s.vmax = nom; s.ramp = RAMP_DECEL_OVERRIDE
        elif inter > 0:
            if inter < b.mm:  # trapezoid or triangle
                s.dec_after = f32(inv_2a * f32(nom_sqr - exit_sqr))
                if s.dec_after < inter:
                    s.vmax = nom
                    if b.entry_sqr == nom_sqr: s.ramp = RAMP_CRUISE
                    else: s.acc_until = f32(s.acc_until - f32(inv_2a * f32(nom_sqr - b.entry_sqr)))
                else:
                    s.acc_until = s.dec_after = inter
                    s.vmax = f32(d(math.sqrt(d(d(d(2.0 * b.accel) * inter) + exit_sqr))))
            else:
                s.ramp = RAMP_DECEL
        else:  # acceleration only
            s.acc_until = 0.0; s.vmax = s.exit

    def segment(s):
        d = s.ar.d
        if s.block is None:
            b = s.pl.current()
            if b is None: return None
            s.block = b
            if s.recalc: s.recalc = False  # keep the block's step data
            else:
                s.steps_rem = float(b.events)
                s.step_per_mm = f32(s.steps_rem / b.mm)
                s.req_mm = f32(d(1.25 / s.step_per_mm))  # REQ_MM_INCREMENT_SCALAR steps
                s.dt_rem = 0.0
                s.cur = f32(math.sqrt(b.entry_sqr))
            s.profile(b)
        b = s.block
        # the distance of one DT_SEGMENT through the ramps (more while under 1.25 steps)
        dt_max = s.dt_segment; dt = 0.0; tv = dt_max
        mm = b.mm; min_mm = max(0.0, f32(mm - s.req_mm))
        while True:
            if s.ramp == RAMP_DECEL_OVERRIDE:
                sv = f32(b.accel * tv)
                if f32(s.cur - s.vmax) <= sv:
                    mm = s.acc_until
                    tv = f32(d(d(2.0 * f32(b.mm - mm)) / f32(s.cur + s.vmax)))
                    s.ramp = RAMP_CRUISE; s.cur = s.vmax
                else:
                    mm = f32(d(mm - d(tv * d(s.cur - d(0.5 * sv)))))
                    s.cur = f32(s.cur - sv)
            elif s.ramp == RAMP_ACCEL:
                sv = f32(b.accel * tv)
                mm = f32(d(mm - d(tv * d(s.cur + d(0.5 * sv)))))
                if mm < s.acc_until:  # end of the acceleration
                    mm = s.acc_until
                    tv = f32(d(d(2.0 * f32(b.mm - mm)) / f32(s.cur + s.vmax)))
                    s.ramp = RAMP_DECEL if mm == s.dec_after else RAMP_CRUISE
                    s.cur = s.vmax
                else:
                    s.cur = f32(s.cur + sv)
            elif s.ramp == RAMP_CRUISE:
                mv = f32(mm - f32(s.vmax * tv))
                if mv < s.dec_after:  # end of the cruise
                    tv = f32(f32(mm - s.dec_after) / s.vmax)
                    mm = s.dec_after; s.ramp = RAMP_DECEL
                else:
                    mm = mv
            else:
                sv = f32(b.accel * tv); done = False
                if s.cur > sv:
                    mv = f32(d(mm - d(tv * d(s.cur - d(0.5 * sv)))))
                    if mv > 0: mm = mv; s.cur = f32(s.cur - sv); done = True
                if not done:  # end of the block
                    tv = f32(d(d(2.0 * mm) / f32(s.cur + s.exit)))
                    mm = 0.0; s.cur = s.exit
            dt = f32(dt + tv)
            if dt < dt_max: tv = f32(dt_max - dt)  # a ramp ended inside the segment
            elif mm > min_mm:
                dt_max = f32(d(dt_max + s.dt_expr)); tv = f32(dt_max - dt)
            else: break
            if not mm > 0: break
        # whole steps: the remaining distance in steps rounded up; the partial
        # step's time goes to the next segment (dt_remainder)
        dist = f32(s.step_per_mm * mm)
        n_rem = float(math.ceil(dist)); last = float(math.ceil(s.steps_rem))
        dt = f32(dt + s.dt_rem)
        inv_rate = f32(dt / f32(last - dist))
        cycles = math.ceil(f32(s.cycles_per_min * inv_rate))
        b.mm = mm; s.steps_rem = n_rem
        s.dt_rem = f32(f32(n_rem - dist) * inv_rate)
        if mm == 0:
            s.block = None; s.pl.discard()
        return b.k, int(last - n_rem), cycles


def simulate_grbl(moves, flags, settings, ar, blocks=BLOCK_BUFFER_SIZE):
    """Every segment Grbl cuts from the job, (move, steps, cycles per step),
    and how many times the block being cut was re-planned. The foreground is
    infinitely fast: the cycle starts with the planner full, the interrupt
    frees one segment slot at a time, the generator refills it at once, and
    the parser hands the planner a move whenever a block is freed."""
    run = GrblRun(settings, ar, blocks); out = []
    while (seg := run.next(moves, flags)) is not None: out.append(seg)
    return out, run.gen.replans


def amass(model, cycles):
    """The AMASS level and the timer period (compare value + 1) of a rate."""
    L = sum(1 for x in model.thr if cycles >= x)
    return L, min(cycles >> L, PMAX - 1) + 1


def planner_miss(cycles, L, p):
    """The predicted period at level L against a fitted range: 0 inside."""
    q = min(cycles >> L, PMAX - 1) + 1
    return 0 if p.plo <= q <= p.phi else (q - p.phi if q > p.phi else q - p.plo)


def cover(segs, pred):
    """For every fitted segment the predicted segment that holds its first
    step, and whether the two are the same steps of the move."""
    starts = {}; pos = {}
    for j, (b, n, _) in enumerate(pred):
        starts.setdefault(b, []).append((pos.get(b, 0), j)); pos[b] = pos.get(b, 0) + n
    out = []; pos = {}
    for L, N, b, _ in segs:
        s0 = pos.get(b, 0); pos[b] = s0 + (N >> L)
        i = bisect.bisect_right(starts[b], (s0, 1 << 62)) - 1
        p0, j = starts[b][i]
        out.append((j, p0 == s0 and pred[j][1] == N >> L))
    return out


def planner_start(model, moves, pred, evt, evm):
    """Runs the predicted segments from cycle 0 against the log's step ticks:
    the start cycles that put every step event into its tick. Returns
    (start cycle, events in their ticks); on a mismatch a start that fits
    the events before it."""
    m = Matcher()
    for seg in pred:
        if not m.feed(model, moves, seg, evt, evm): break
    return (m.lo + m.hi) // 2, m.kk


def planner_log(model, moves, pred, c0, size):
    """The log (size ticks) that the predicted segments write when the
    first interrupt is at cycle c0."""
    ss = []; cc = []; c = c0
    for b, n, cycles in pred:
        L, P = amass(model, cycles)
        ss.append((L, n << L, b, None)); cc.append((c, P)); c += (n << L) * P
    return regenerate(model, moves, ss, cc, size)


def planner_probe(a, model, moves, segs, conc, d, evt, evm):
    """--planner: the planner's prediction against the fitted segments, the
    cost of coding the periods against it, and the log regenerated from the
    prediction alone."""
    ar = Arith(a.planner_avr)
    if a.job.endswith('.json'): raise SystemExit('--planner: JOB must be the G-code job')
    _, flags, settings = read_job(a.job, a.steps_mm, ar)
    pred, replans = simulate_grbl(moves, flags, settings, ar, a.planner_blocks)
    at = cover(segs, pred)
    print('planner: Grbl segments', len(pred), '(blocks re-planned while cut: %d);' % replans,
          'fitted segments that are one of them', sum(s for _, s in at), 'of', len(segs))
    rows = {name: [0, 0, 0] for name in ('segments', 'in range', 'within 1', 'P exact', 'P within 1', 'level agrees')}
    res = [[], [], []]; prev = None; place = 0
    for ((L, N, b, p), (c, P)), (j, _) in zip(zip(segs, conc), at):
        place = 0 if b != prev else min(place + 1, 2); prev = b
        cycles = pred[j][2]; r = planner_miss(cycles, L, p); q = min(cycles >> L, PMAX - 1) + 1
        for name, ok in (('segments', True), ('in range', r == 0), ('within 1', abs(r) <= 1), ('P exact', q == P),
                         ('P within 1', abs(q - P) <= 1), ('level agrees', amass(model, cycles)[0] == L)):
            rows[name][place] += ok
        res[place].append(abs(r))
    print('  fitted segments (first, second, later of a move)')
    for name, v in rows.items(): print('  %-13s' % name, *v)
    for place, name in enumerate(('first', 'second', 'later')):
        m = sorted(res[place])
        if m: print('  miss (cycles outside the fitted range), %s: median %d p90 %d max %d'
                    % (name, m[len(m) // 2], m[len(m) * 9 // 10], m[-1]))
    parts, mb, misses = cost(segs, conc, moves, [pred[j][2] for j, _ in at])
    sb = sum(parts)
    print('planner estimated bits: segments', sb, '(%.2f a segment; first, second, later segments of a move:' % (sb / len(segs)),
          *parts, end='); ')
    print('moves with G0/G1', mb, 'total bytes', (sb + mb + 7) // 8)
    # the log from the prediction alone: one start cycle, no fitted data
    c0, k = planner_start(model, moves, pred, evt, evm)
    out = planner_log(model, moves, pred, c0, len(d))
    bad = sum(1 for t in range(len(d)) if d[t] != out[t])
    mb = sum(gamma(v) for m in moves for v in m) + len(moves)
    print('planner alone: start cycle', c0, 'puts', k, 'of', len(evt), 'step events in their ticks; ticks regenerated differently',
          bad, 'of', len(d), '; estimated bits: moves with G0/G1', mb, 'start', gamma(c0), 'total bytes', (mb + gamma(c0) + 7) // 8)


def fit_restarting(model, moves, doc, evt, evm, dirch):
    """--restart: fit from each move that the fit before could not pass."""
    found = doc['chains'][0]['moves']
    first = [bisect.bisect_left(evt, m['ticks'][0]) for m in found] + [len(evt)]
    dticks = [t for t, _ in dirch]
    b = fitted = held = restarts = 0
    while b < len(moves):
        k0 = first[b]
        dptr = bisect.bisect_right(dticks, found[b - 1]['ticks'][1]) if b > 0 else 0
        k, _ = fit(model, moves[b:], evt, evm, dirch, k0=k0, dptr0=dptr, dcur0=dirch[dptr - 1][1] if dptr > 0 else 0)
        stop = len(moves) if k >= len(evt) else bisect.bisect_right(first, k) - 1  # the move of the first step not fitted
        fitted += stop - b
        held += first[stop] - k0
        restarts += stop < len(moves)
        b = max(stop + 1, b + 1)
    print('moves fitted whole', fitted, 'of', len(moves), '(restarts', restarts, end=')\n')
    print('step events in them', held, 'of', len(evt))
    return 0


# --recover: the job (settings, moves, G0/G1 and feed per move, start cycle)
# out of the log alone, judged by regenerating the log with the model above.

STEPS_MM = (100, 80, 250, 1)      # one per float class: x 2^k regenerates alike
JDEV = ('0.010', '0.005', '0.020', '0.001', '0.002', '0.050', '0.100', '0.015', '0.008', '0.003', '0.030')


def round_near(x, rel=0.04, most=9):
    """Decimals a user would type near x, nearest first: 1 or 2 significant
    digits, or 3 ending in 0 or 5."""
    out = set()
    e = 10 ** math.floor(math.log10(x))
    for step in (e, e / 2, e / 10, e / 20):
        for q in range(int(x * (1 - rel) / step), int(x * (1 + rel) / step) + 2):
            v = round(q * step, 6)
            if v > 0 and abs(v - x) <= rel * x: out.add(v)
    return sorted(out, key=lambda v: abs(v - x))[:most]


def dec(v):
    s = ('%.6f' % v).rstrip('0').rstrip('.')
    return s if '.' in s or len(s) else '0'


class LogSteps:
    """The log's step events with per-axis prefix counts, for moves cut at
    event boundaries."""
    def __init__(s, d, evt, evm, dirch, NA):
        s.d, s.evt, s.evm, s.dirch, s.NA = d, evt, evm, dirch, NA
        s.pc = [[0] * (len(evt) + 1) for _ in range(NA)]
        s.axt = [[t for t, m in zip(evt, evm) if (m >> a) & 1] for a in range(NA)]
        for a in range(NA):
            pa = s.pc[a]; c = 0
            for i, m in enumerate(evm):
                c += (m >> a) & 1; pa[i + 1] = c

    def move(s, i0, i1):
        """The signed step counts of events [i0, i1): signs from the DIR
        level at the axis's first step (None if an axis turns inside)."""
        out = []
        for a in range(s.NA):
            n = s.pc[a][i1] - s.pc[a][i0]
            if n:
                j = i0
                while not (s.evm[j] >> a) & 1: j += 1
                if (s.d[s.evt[j]] >> (2 * a + 1)) & 1: n = -n
            out.append(n)
        return tuple(out)

    def forced(s):
        """Event indices where a DIR change forces a move boundary."""
        return sorted({bisect.bisect_left(s.evt, t) for t, _ in s.dirch} - {0, len(s.evt)})


class GrblRun:
    """Grbl's cycle as simulate_grbl describes it, one segment a call
    (simulate_grbl runs it to the end); its state can be deep-copied."""
    def __init__(s, settings, ar, blocks=BLOCK_BUFFER_SIZE):
        s.pl = Planner(ar, settings, blocks); s.gen = SegmentGenerator(ar, s.pl)
        s.k = 0; s.queued = 0; s.started = False; s.pending = []

    def _fill(s):
        while s.queued < SEGMENT_BUFFER_SIZE - 1:
            seg = s.gen.segment()
            if seg is None: return
            s.pending.append(seg); s.queued += 1

    def _top(s, moves, flags):
        while s.k < len(moves) and not s.pl.full():
            s.pl.add(s.k, moves[s.k], *flags[s.k]); s.k += 1

    def next(s, moves, flags):
        while not s.pending:
            if not s.started: s._top(moves, flags); s._fill(); s._top(moves, flags); s.started = True
            elif s.queued: s.queued -= 1; s._fill(); s._top(moves, flags)
            else: return None
        return s.pending.pop(0)


class Matcher:
    """The predicted segments against the log's step events, a segment a
    call: the start cycles that put every event in its tick (planner_start
    feeds it to the first mismatch)."""
    def __init__(s):
        s.c = 0; s.lo, s.hi = -(1 << 62), 1 << 62; s.kk = 0; s.prev = -1; s.cnt = None
        s.na = [0, 0]; s.soft = None  # steps per axis; soft: (c0, axis ticks) to sum the tick errors

    def soft_feed(s, model, moves, seg):
        """Soft mode: the ticks of each axis's steps against the log's,
        summed (capped at 64 ticks a step), no stop at a difference."""
        b, n, cycles = seg; c0, axt = s.soft
        L, P = amass(model, cycles); NA = len(moves[b])
        S = [abs(v) for v in moves[b]]; thr = max(S) << LMAX
        if b != s.prev: s.cnt = [thr >> 1] * NA; s.prev = b
        inc = [v << (LMAX - L) for v in S]; cnt = s.cnt; ct = model.ct; err = 0
        for i in range(1, (n << L) + 1):
            for a in range(NA):
                cnt[a] += inc[a]
                if cnt[a] > thr:
                    cnt[a] -= thr; j = s.na[a]; s.na[a] += 1
                    t = (c0 + s.c + i * P) // ct
                    err += min(64, abs(t - axt[a][j])) if j < len(axt[a]) else 64
        s.c += (n << L) * P
        return err

    def feed(s, model, moves, seg, evt, evm):
        b, n, cycles = seg
        L, P = amass(model, cycles); NA = len(moves[b])
        S = [abs(v) for v in moves[b]]; thr = max(S) << LMAX
        if b != s.prev: s.cnt = [thr >> 1] * NA; s.prev = b
        inc = [v << (LMAX - L) for v in S]; cnt = s.cnt; ct = model.ct; ne = len(evt)
        for i in range(1, (n << L) + 1):
            mask = 0
            for a in range(NA):
                cnt[a] += inc[a]
                if cnt[a] > thr: cnt[a] -= thr; mask |= 1 << a
            if not mask: continue
            if s.kk >= ne or evm[s.kk] != mask: return False
            t0 = ct * evt[s.kk] - (s.c + i * P)
            lo = max(s.lo, t0); hi = min(s.hi, t0 + ct - 1)
            if lo > hi: return False
            s.lo, s.hi = lo, hi; s.kk += 1
            for a in range(NA): s.na[a] += (mask >> a) & 1
        s.c += (n << L) * P
        return True


class Judge:
    """A job (settings, move boundaries in events, G0/G1 per move, feed)
    run through the model against the log, with snapshots at every move's
    first segment to resume from after a local change."""
    def __init__(s, model, ar, ls, settings, bounds, rapid, feed):
        s.model, s.ar, s.ls = model, ar, ls
        s.settings, s.bounds, s.rapid, s.feed = settings, list(bounds), list(rapid), feed
        s.snaps = []; s.evals = 0
        s.rebuild()

    def rebuild(s):
        s.moves = [s.ls.move(s.bounds[i], s.bounds[i + 1]) for i in range(len(s.bounds) - 1)]
        s.flags = [(r, s.feed) for r in s.rapid]

    def run(s, upto=None, snap=None, record=False, moves=None, flags=None):
        """Events matched from the start (resuming from snap), stopping
        once a segment of move upto comes; and whether all matched."""
        moves = moves or s.moves; flags = flags or s.flags
        s.evals += 1
        if snap is None: run, m = GrblRun(s.settings, s.ar), Matcher()
        else: run, m = copy.deepcopy(snap[2])
        evt, evm = s.ls.evt, s.ls.evm
        while True:
            seg = run.next(moves, flags)
            if seg is None: return m.kk, m.kk == len(evt), m
            if seg[0] != m.prev:
                if upto is not None and seg[0] >= upto: return m.kk, False, m
                if record:  # the state before this segment was taken
                    sn = copy.deepcopy((run, m)); sn[0].pending.insert(0, seg)
                    s.snaps.append((seg[0], run.k, sn))
            if not m.feed(s.model, moves, seg, evt, evm): return m.kk, False, m

    def soft(s, snap, moves, flags, first, upto):
        """The summed tick error of the steps of moves first..upto-1 (from
        snap, the start cycle the middle of the range that snap allows)."""
        s.evals += 1
        run, m = copy.deepcopy(snap[2])
        m.soft = ((m.lo + m.hi) // 2, s.ls.axt); err = 0
        while True:
            seg = run.next(moves, flags)
            if seg is None or seg[0] >= upto: return err
            e = m.soft_feed(s.model, moves, seg)
            if seg[0] >= first: err += e

    def snap_for(s, j):
        """The latest snapshot whose planner has not read move j yet."""
        best = None
        for sn in s.snaps:
            if sn[1] <= j: best = sn
            else: break
        return best

    def drop(s, j):
        s.snaps = [sn for sn in s.snaps if sn[1] <= j]


def initial_job(chain, ls, feed_steps):
    """Move boundaries from stepzip segment's moves (their first steps) and
    the DIR changes; G0 where the cruise is above the G1 feed."""
    first = sorted({bisect.bisect_left(ls.evt, m['ticks'][0]) for m in chain['moves']} | set(ls.forced()) | {0})
    first = [f for f in first if f < len(ls.evt)]
    bounds = first + [len(ls.evt)]
    cruise = {}
    for m in chain['moves']: cruise[bisect.bisect_left(ls.evt, m['ticks'][0])] = m['cruise']
    rapid = [cruise.get(b, 0) > feed_steps * 1.03 for b in bounds[:-1]]
    return bounds, rapid


def settings_for(ar, spm, rate, accel, jdev):
    v = ar.read_float
    return dict(steps_mm=[v(dec(spm))] * 2, max_rate=[v(dec(rate))] * 2,
                accel=[f32(f32(v(dec(accel)) * 60) * 60)] * 2, jdev=v(jdev))


def recover(a, model):
    t0 = time.process_time()
    ar = Arith(a.planner_avr)
    d, evt, evm, dirch = read_log(a.log, 2)
    ls = LogSteps(d, evt, evm, dirch, 2)
    if a.job and a.job.endswith('.json'): chain = json.load(open(a.job))['chains'][0]
    else:
        exe = a.stepzip or os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'build', 'stepzip')
        out = subprocess.run([exe, 'segment', a.log, '--format', 'timed', '--tick-us', str(a.tick_us), '--to', 'json', '-c'],
                             check=True, capture_output=True).stdout
        chain = json.loads(out)['chains'][0]
    rate_s = max(x['max_rate'] for x in chain['axes'])      # steps/s
    acc_s = max(x['acceleration'] for x in chain['axes'])   # steps/s²
    # the G1 feed: the commonest cruise (path steps/s, 0.5 % bins) under the
    # rate limit, long moves counting most (short ones never reach it)
    hist = {}
    for m in chain['moves']:
        if m['cruise'] < 0.97 * rate_s:
            key = round(math.log(m['cruise']) / 0.005); hist[key] = hist.get(key, 0) + m['length'] ** 2
    feed_s = math.exp(max(hist, key=hist.get) * 0.005) if hist else rate_s
    print('recover: stepzip moves', len(chain['moves']), 'axis rate %.1f steps/s, acceleration %.1f steps/s², G1 cruise %.1f steps/s'
          % (rate_s, acc_s, feed_s))
    H = a.recover_moves  # moves judged in the settings search
    bounds, rapid = initial_job(chain, ls, feed_s)
    found = None
    for spm in STEPS_MM:
        cur, sc = search_settings(model, ar, ls, bounds, rapid, spm, rate_s, acc_s, feed_s, H, None)
        print('  steps/mm %s: $110/$111 %s $120/$121 %s $11 %s G1 F%s: %d events of the first %d moves matched'
              % (spm, dec(cur['rate']), dec(cur['accel']), cur['jdev'], dec(cur['feed']), sc, H))
        if found is None or sc > found[0]: found = (sc, spm, cur)
    _, spm, cur = found
    J = judge_for(model, ar, ls, bounds, rapid, spm, cur)
    print('  initial job: moves', len(J.moves), 'G0', sum(J.rapid))
    t1 = time.process_time(); edits = {}
    # fix the first H moves, settle the settings on them, then fix the rest
    K, done = fix(J, m0=0, limit=bounds[min(H, len(bounds) - 1)], edits=edits, verbose=a.verbose)
    cur, sc = search_settings(model, ar, ls, J.bounds, J.rapid, spm, rate_s, acc_s, feed_s, len(J.moves), cur)
    print('  settings again on the fixed moves: $110/$111 %s $120/$121 %s $11 %s G1 F%s: %d events'
          % (dec(cur['rate']), dec(cur['accel']), cur['jdev'], dec(cur['feed']), sc))
    J = judge_for(model, ar, ls, J.bounds, J.rapid, spm, cur)
    settings = J.settings
    K, done = fix(J, m0=0, limit=None, edits=edits, verbose=a.verbose)
    t2 = time.process_time()
    print('  edits', edits, 'judge runs', J.evals, '; events matched', K, 'of', len(evt))
    # the whole log from the recovered job alone
    run = GrblRun(settings, ar); pred = []
    while True:
        seg = run.next(J.moves, J.flags)
        if seg is None: break
        pred.append(seg)
    c0, k = planner_start(model, J.moves, pred, evt, evm)
    out = planner_log(model, J.moves, pred, c0, len(d))
    bad = [t for t in range(len(d)) if d[t] != out[t]]
    print('  regenerated: start cycle', c0, '; ticks regenerated differently', len(bad), 'of', len(d),
          '(first at tick %d)' % bad[0] if bad else '(byte-exact)')
    mb = sum(gamma(v) for mv in J.moves for v in mv)
    gb = len(J.moves)  # G0/G1: one bit a move (an entropy coder needs fewer)
    p0 = sum(J.rapid) / len(J.rapid); hb = -len(J.rapid) * sum(q * math.log2(q) for q in (p0, 1 - p0) if q > 0)
    sb = 6 * 8  # steps/mm, $110/$111, $120/$121, $11, F: a byte each and a header byte
    print('  job: moves', len(J.moves), 'G0', sum(J.rapid), 'G1 feed', dec(cur['feed']), '; estimated bits: step counts', mb,
          'G0/G1', gb, '(%.0f by entropy)' % hb, 'settings', sb, 'start', gamma(c0),
          'total bytes', (mb + gb + sb + gamma(c0) + 7) // 8)
    print('  CPU s: settings %.1f, moves %.1f, regeneration %.1f' % (t1 - t0, t2 - t1, time.process_time() - t2))
    if a.out_job:
        write_job(a.out_job, spm, cur, J)
    return 0 if not bad else 2


def judge_for(model, ar, ls, bounds, rapid, spm, cur):
    return Judge(model, ar, ls, settings_for(ar, spm, cur['rate'], cur['accel'], cur['jdev']),
                 bounds, rapid, ar.read_float(dec(cur['feed'])))


def search_settings(model, ar, ls, bounds, rapid, spm, rate_s, acc_s, feed_s, H, cur):
    """Coordinate descent over round decimals near the estimates: the
    settings under which the model matches the most events of the first H
    moves."""
    grids = dict(rate=round_near(rate_s * 60 / spm), accel=round_near(acc_s / spm), jdev=JDEV,
                 feed=round_near(feed_s * 60 / spm))
    if cur is None: cur = {k: v[0] for k, v in grids.items()}

    def score(c):
        return judge_for(model, ar, ls, bounds, rapid, spm, c).run(upto=H)[0]
    sc = score(cur)
    for _ in range(2):
        better = False
        for key in ('rate', 'accel', 'jdev', 'feed'):
            for v in grids[key]:
                if v == cur[key]: continue
                c2 = dict(cur, **{key: v}); s2 = score(c2)
                if s2 > sc: sc, cur, better = s2, c2, True
        if not better: break
    return cur, sc


def fix(J, m0, limit, edits, verbose):
    """The judge loop: run to the first event that does not match, try the
    local changes there, keep the one that matches furthest, repeat; stop
    at event limit or when no change helps. Returns (events matched, all)."""
    J.snaps = []
    K, done, _ = J.run(record=True, upto=None if limit is None else bisect.bisect_right(J.bounds, limit))
    while not done and (limit is None or K < limit):
        m = bisect.bisect_right(J.bounds, K) - 1
        bestk, bestc = K, None
        for name, aff, bounds, rapid, top in edit_candidates(J, m, K):
            moves = [J.ls.move(bounds[i], bounds[i + 1]) for i in range(len(bounds) - 1)]
            flags = [(r, J.feed) for r in rapid]
            k2, full, _ = J.run(upto=top, snap=J.snap_for(aff), moves=moves, flags=flags)
            whole = full or k2 >= bounds[min(top, len(bounds) - 1)]  # matches up to the horizon
            # a split must prove itself: both its parts match, or all up to the horizon
            if k2 > bestk and (whole or not name.startswith('split') or k2 >= bounds[m + 2]):
                bestk, bestc = k2, (name, aff, bounds, rapid)
            if whole: break
        if bestc is None:
            bestc = soft_fix(J, m, K, verbose)
        if bestc is None:
            print('  stuck at event', K, 'tick', J.ls.evt[K], 'in move', m, 'of', len(J.moves)); break
        name, aff, J.bounds, J.rapid = bestc[:4]
        edits[name.split()[0]] = edits.get(name.split()[0], 0) + 1
        if verbose: print('   ', K, 'move', m, name, '->', bestc[4] if len(bestc) > 4 else bestk)
        J.rebuild(); J.drop(aff)
        K, done, _ = J.run(snap=J.snap_for(aff), record=True,
                           upto=None if limit is None else bisect.bisect_right(J.bounds, limit))
    return K, done


def soft_fix(J, m, K, verbose, W=8):
    """No single change gets past event K of move m: several moves in the
    look-ahead are cut wrong. Descend on the summed tick error of moves
    m-1..m+4 over changes of moves m..m+W (boundary shifts, merges, G0/G1)
    until the events match past K; returns the change or None."""
    B, R = list(J.bounds), list(J.rapid)
    snap = J.snap_for(m)
    if snap is None: return None

    def job(b, r):
        return [J.ls.move(b[i], b[i + 1]) for i in range(len(b) - 1)], [(x, J.feed) for x in r]
    err = J.soft(snap, *job(B, R), m - 1, m + 5)
    for _ in range(12):
        best = None
        for j in range(m, min(m + W, len(R))):
            cands = [(B, R[:j] + [not R[j]] + R[j + 1:])]
            if j > 0:
                for delta in (1, -1, 2, -2, 3, -3, 4, -4):
                    if B[j - 1] < B[j] + delta < B[j + 1]:
                        cands.append((B[:j] + [B[j] + delta] + B[j + 1:], R))
                cands.append((B[:j] + B[j + 1:], R[:j] + R[j + 1:]))
            for b, r in cands:
                mv, fl = job(b, r)
                e = J.soft(snap, mv, fl, m - 1, m + 5)
                if e < err and (best is None or e < best[0]): best = (e, b, r)
        if best is None: return None
        err, B, R = best
        mv, fl = job(B, R)
        k2, full, _ = J.run(upto=min(m + 6, len(R)), snap=snap, moves=mv, flags=fl)
        if verbose: print('      soft: error', err, 'events', k2)
        if k2 > K: return ('soft', snap[1], B, R, k2)
    return None


def write_job(path, spm, cur, J):
    """The recovered job as G-code (steps as mm at the recovered steps/mm)."""
    lines = ['$100=%s' % dec(spm), '$101=%s' % dec(spm), '$110=%s' % dec(cur['rate']), '$111=%s' % dec(cur['rate']),
             '$120=%s' % dec(cur['accel']), '$121=%s' % dec(cur['accel']), '$11=%s' % cur['jdev'],
             'G21 G90 G94 G17', 'F%s' % dec(cur['feed'])]
    pos = [0, 0]
    for mv, r in zip(J.moves, J.rapid):
        pos = [p + v for p, v in zip(pos, mv)]
        lines.append('%s X%s Y%s' % ('G0' if r else 'G1', dec(pos[0] / spm), dec(pos[1] / spm)))
    open(path, 'w').write('\n'.join(lines) + '\n')


def edit_candidates(J, m, K):
    """Local changes near the move m holding the first event K that does
    not match, simplest first: (name, first move changed, bounds, G0 flags,
    horizon move)."""
    B, R = J.bounds, J.rapid; n = len(R); H = 6; out = []
    for j in (m, m + 1, m - 1, m + 2, m - 2, m + 3):
        if 0 <= j < n:
            r = list(R); r[j] = not r[j]
            out.append(('flip %d' % j, j, B, r, m + H))
    for delta in (1, -1, 2, -2, 3, -3, 4, -4, 6, -6, 8, -8):
        for j in (m + 1, m):
            if 0 < j < n and B[j - 1] < B[j] + delta < B[j + 1]:
                b = list(B); b[j] += delta
                out.append(('shift %d %+d' % (j, delta), j - 1, b, R, m + H))
    for j in (m + 1, m):
        if 0 < j < n:
            out.append(('merge %d' % j, j - 1, B[:j] + B[j + 1:], R[:j] + R[j + 1:], m + H - 1))
    lo, hi = B[m], B[m + 1]
    for w in range(0, hi - lo):
        for e in (K - w, K + w) if w else (K,):
            if lo < e < hi:
                for f0, f in ((R[m], R[m]), (R[m], not R[m]), (not R[m], R[m]), (not R[m], not R[m])):
                    out.append(('split %d' % m, m, B[:m + 1] + [e] + B[m + 1:], R[:m] + [f0, f] + R[m + 1:], m + H + 1))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('log'); ap.add_argument('job', nargs='?')
    ap.add_argument('--steps-mm', type=int, default=100)
    ap.add_argument('--cycles-per-tick', type=int, default=640)
    ap.add_argument('--thresholds', default='2000,4000,8000')
    ap.add_argument('--segment-cycles', type=int, default=160000)
    ap.add_argument('--segments', help='write the fitted segments (level, interrupts, move, c, P) as JSON')
    ap.add_argument('--restart', action='store_true',
                    help="JOB is stepzip segment's JSON; pass over moves that do not fit")
    ap.add_argument('--planner', action='store_true',
                    help="predict every segment with Grbl 1.1's planner and segment generator (JOB: the G-code)")
    ap.add_argument('--planner-avr', action='store_true',
                    help="with --planner: AVR arithmetic (double is float) instead of a PC build's")
    ap.add_argument('--planner-blocks', type=int, default=BLOCK_BUFFER_SIZE,
                    help='with --planner: planner ring size (it holds one block less)')
    ap.add_argument('--recover', action='store_true',
                    help='recover the job (settings, moves, G0/G1, feed) from LOG alone and regenerate LOG from it '
                         '(JOB, optional: stepzip segment JSON of LOG)')
    ap.add_argument('--out-job', help='with --recover: write the recovered job as G-code')
    ap.add_argument('--stepzip', help='with --recover: the stepzip binary (default: build/stepzip of this tree)')
    ap.add_argument('--tick-us', type=int, default=40, help="with --recover: the log's tick")
    ap.add_argument('--recover-moves', type=int, default=30, help='with --recover: moves judged in the settings search')
    ap.add_argument('--verbose', action='store_true', help='with --recover: every change made to the job')
    a = ap.parse_args()
    if a.job is None and not a.recover: ap.error('JOB is required without --recover')
    model = Model(a.cycles_per_tick, [int(v) for v in a.thresholds.split(',')], a.segment_cycles)
    if a.recover:
        return recover(a, model)
    moves = read_moves(a.job, a.steps_mm)
    d, evt, evm, dirch = read_log(a.log, len(moves[0]))
    if a.restart:
        return fit_restarting(model, moves, json.load(open(a.job)), evt, evm, dirch)
    k, segs = fit(model, moves, evt, evm, dirch)
    last = segs[-1][2] if segs else -1
    print('moves fitted', last + 1 if k == len(evt) else last, 'of', len(moves))
    print('step ticks matched', k, 'of', len(evt))
    print('segments', len(segs), 'levels', {L: sum(1 for s in segs if s[0] == L) for L in range(LMAX + 1)})
    if k < len(evt): return 1
    conc, breaks = concrete(segs)
    out = regenerate(model, moves, segs, conc, len(d))
    bad = [t for t in range(len(d)) if d[t] != out[t]]
    print('integer periods chosen; chain restarts', breaks)
    print('ticks regenerated differently', len(bad), 'of', len(d))
    parts, mb, misses = cost(segs, conc, moves)
    sb = sum(parts)
    print('estimated bits: segments', sb, '(%.2f a segment; first, second, later segments of a move:' % (sb / len(segs)),
          *parts, end='); ')
    print('moves', mb, 'total bytes', (sb + mb + 7) // 8)
    if misses:
        print('period residuals (timer cycles): median', misses[len(misses) // 2],
              'p90', misses[len(misses) * 9 // 10], 'zero', sum(1 for m in misses if m == 0))
    if a.planner:
        planner_probe(a, model, moves, segs, conc, d, evt, evm)
    if a.segments:
        json.dump([[L, N, b, c, P] for (L, N, b, _), (c, P) in zip(segs, conc)], open(a.segments, 'w'))
    return 0 if not bad else 2


if __name__ == '__main__':
    sys.exit(main())
