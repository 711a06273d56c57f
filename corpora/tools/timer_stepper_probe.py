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
period is one of the periods that fit), a move's first segment 18 bits; per
move the step counts as signed Elias-gamma codes.

With --restart the moves are those `stepzip segment --format timed --to
json` found in the log (JOB is that JSON): a move that does not fit is
passed over and the fit starts afresh at the next move's first step, with
its timing unknown; the probe then reports how many moves it fitted whole
and how many of the log's steps they hold (a coder that finds the moves in
the log would fit these; docs/benchmarks.md "Timed streams: the moves of a
log").

Usage: timer_stepper_probe.py LOG JOB.nc|REPORT.json [--steps-mm 100]
         [--cycles-per-tick 640] [--thresholds 2000,4000,8000]
         [--segment-cycles 160000] [--segments OUT.json]
       timer_stepper_probe.py LOG MOVES.json --restart [...]
"""
import argparse
import bisect
import json
import math
import struct
import sys

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
    pos = [0, 0]; moves = []
    for line in text.split('\n'):
        if not line.startswith(('G0 ', 'G1 ')): continue
        tgt = list(pos)
        for w in line.split()[1:]:
            tgt['XY'.index(w[0])] = lround(f32(read_float(w[1:]) * f32(float(steps_mm))))
        dd = (tgt[0] - pos[0], tgt[1] - pos[1])
        if any(dd): moves.append(dd)
        pos = tgt
    return moves


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


def cost(segs, conc, moves):
    """Estimated bits: segments (step count, period) by their place in the
    move (first, second, later), moves (step counts)."""
    seg_bits = [0, 0, 0]; hist = []; misses = []
    for (L, N, b, p), (c, P) in zip(segs, conc):
        same = [r for bb, r in hist[-2:] if bb == b] if hist and hist[-1][0] == b else []
        if not same:
            seg_bits[0] += 19
        else:
            rate = 2 * same[-1] - same[0] if len(same) == 2 else same[-1]
            q = (round(1 / rate) >> L) if rate > 0 else P
            r = 0 if p.plo <= q <= p.phi else (q - p.phi if q > p.phi else q - p.plo)
            seg_bits[min(len(same), 2)] += 1 + gamma(r); misses.append(abs(r))
        hist.append((b, 1.0 / (P << L)))
    move_bits = sum(gamma(v) for m in moves for v in m)
    misses.sort()
    return seg_bits, move_bits, misses


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


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('log'); ap.add_argument('job')
    ap.add_argument('--steps-mm', type=int, default=100)
    ap.add_argument('--cycles-per-tick', type=int, default=640)
    ap.add_argument('--thresholds', default='2000,4000,8000')
    ap.add_argument('--segment-cycles', type=int, default=160000)
    ap.add_argument('--segments', help='write the fitted segments (level, interrupts, move, c, P) as JSON')
    ap.add_argument('--restart', action='store_true',
                    help="JOB is stepzip segment's JSON; pass over moves that do not fit")
    a = ap.parse_args()
    model = Model(a.cycles_per_tick, [int(v) for v in a.thresholds.split(',')], a.segment_cycles)
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
    if a.segments:
        json.dump([[L, N, b, c, P] for (L, N, b, _), (c, P) in zip(segs, conc)], open(a.segments, 'w'))
    return 0 if not bad else 2


if __name__ == '__main__':
    sys.exit(main())
