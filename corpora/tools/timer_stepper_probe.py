#!/usr/bin/env python3
"""Probe: how much of a timed STEP/DIR log a timer-interrupt stepper model
reproduces exactly (a measurement prototype, not the codec).

Model: the stepper interrupt fires every P CPU cycles, P constant within a
stepper segment of N interrupts (N a multiple of 2^L); with step-smoothing
level L (0..LMAX) the Bresenham increments are steps << (LMAX - L) against
a threshold of event_count << LMAX, counters starting at half of it and
carried across the segments of a planner block; the step computed in
interrupt i (1..N) leaves in tick floor((c + (i - 1 + DELTA)·P) / C_TICK),
c the cycle of the interrupt that loaded the segment, and the next segment
is loaded at c + N·P. The planner blocks' step counts are taken from the
g-code job (targets read and rounded to steps in single precision),
so only the timing is fitted: per segment L, P and N are searched so that
the regenerated steps match the log tick for tick, keeping the cycle c as
an interval of the values every match so far allows.

Per segment the candidates are ranked by how many steps they and the next
segment (of the same or the next block) match; when no candidate goes on,
the search backs up to earlier segments' other candidates. With THRESHOLDS
(cycles per step at which levels 1, 2, ... begin, e.g. 2000,4000,8000) a
segment's L must be the one its cycles per step select.

JOB is the g-code of a 2-axis job or the --report JSON of timed_stream.py
(its moves' steps, any axis count).

Usage: timer_stepper_probe.py LOG JOB.nc|REPORT.json [DELTA [C_TICK [LMAX [STEPS_MM [THRESHOLDS]]]]]
Prints the segments fitted (block, L, P, N, steps matched, width of the
cycle interval), then how far the fit reached.
"""
import sys, math, struct
f32=lambda x: struct.unpack('f',struct.pack('f',x))[0]
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
def lround(x): return int(math.floor(x+0.5)) if x>=0 else -int(math.floor(-x+0.5))
d = open(sys.argv[1], 'rb').read(); nc = open(sys.argv[2]).read().split('\n')
arg = lambda i, v: int(sys.argv[i]) if len(sys.argv) > i else v
DELTA = arg(3, 1); CT = arg(4, 640); LMAX = arg(5, 3); SPM = arg(6, 100)
pos = [0, 0]; blocks = []
if sys.argv[2].endswith('.json'):  # a timed_stream.py --report: the moves' steps
    import json
    blocks = [b['steps'] for b in json.loads('\n'.join(nc))]
    nc = []
for line in nc:
    if not line.startswith(('G0 ', 'G1 ')): continue
    tgt = list(pos)
    for w in line.split()[1:]:
        tgt['XY'.index(w[0])] = lround(f32(read_float(w[1:]) * f32(float(SPM))))
    dd = [tgt[0]-pos[0], tgt[1]-pos[1]]
    if any(dd): blocks.append(dd)
    pos = tgt
evt=[]; evm=[]
for t, b in enumerate(d):
    m = (b & 1) | ((b >> 1) & 2) | ((b >> 2) & 4)  # the STEP bits 0, 2, 4 of axes 0, 1, 2
    if m: evt.append(t); evm.append(m)
NA = len(blocks[0])
def gen(cnt, S, E, L, u_left, limit):
    """interrupt indices with masks: list of (i, mask, cnt_after, u_after)"""
    inc=[s<<(LMAX-L) for s in S]; thr=E<<LMAX; cnt=list(cnt); du=1<<(LMAX-L); i=0; out=[]
    while u_left >= du and len(out) < limit:
        i+=1; u_left-=du; mask=0
        for a in range(NA):
            cnt[a]+=inc[a]
            if cnt[a]>thr: cnt[a]-=thr; mask|=1<<a
        if mask: out.append((i, mask, tuple(cnt), u_left))
    return out, i, tuple(cnt), u_left
def boxwalk(clo, chi, plo, phi, evs, k):
    m=0
    for (i, mask, _, _) in evs:
        if k+m >= len(evt) or evm[k+m] != mask: break
        t=evt[k+m]; j=i-1+DELTA
        if j == 0:
            lo_c, hi_c = max(clo, CT*t), min(chi, CT*t+CT-1)
            if lo_c > hi_c: break
            clo, chi = lo_c, hi_c
        else:
            lo = -((chi - CT*t)//j); hi = (CT*t+CT-1-clo)//j
            if max(plo, lo) > min(phi, hi): break
            plo, phi = max(plo, lo), min(phi, hi)
        m+=1
    return m, plo, phi
def cwalk(clo, chi, P, evs, k):
    res=[]; m=0
    for (i, mask, cnt, ul) in evs:
        if k+m >= len(evt) or evm[k+m] != mask: break
        t=evt[k+m]; j=i-1+DELTA
        lo, hi = CT*t - j*P, CT*t+CT-1 - j*P
        clo, chi = max(clo, lo), min(chi, hi)
        if clo > chi: break
        m+=1; res.append((m, clo, chi, i, cnt, ul))
    return res
LIM = 300
def quick(clo, chi, cnt, S, E, k, u_left):
    best=0
    for L in range(LMAX+1):
        evs = gen(cnt, S, E, L, u_left, 80)[0]
        best=max(best, boxwalk(clo, chi, 1, 1<<22, evs, k)[0])
    return best

THR = [int(v) for v in sys.argv[7].split(',')] if len(sys.argv) > 7 else None
def rule_ok(L, P):
    if THR is None: return True
    lo, hi = P << L, (P << L) + (1 << L) - 1  # the cycles per step P was shifted from
    tl = THR[L - 1] if L > 0 else 0
    th = THR[L] if L < len(THR) else 1 << 62
    return lo < th and hi >= tl
AMASS = {}  # level -> [min, max] cycles per step seen where the level was the only fit
def seg_step(S, E, k, cint, cnt, u_left, nxt=None):
    cand=[]
    for L in range(LMAX+1):
        evs, _, _, _ = gen(cnt, S, E, L, u_left, LIM)
        if not evs: continue
        m0, plo, phi = boxwalk(cint[0], cint[1], 1, 1<<22, evs, k)
        if m0 == 0: continue
        if phi - plo > 64:
            mid=(plo+phi)//2; Ps=range(mid-32, mid+33)
        else: Ps=range(plo, phi+1)
        du=1<<(LMAX-L)
        for P in Ps:
            res = cwalk(cint[0], cint[1], P, evs, k)
            if not res: continue
            mmax=res[-1][0]
            inext = evs[mmax][0] if mmax < len(evs) else (evs[-1][0] + 1 if len(evs) == LIM else res[-1][3] + res[-1][5]//du + 1)
            top = min(inext-1, res[-1][3] + res[-1][5]//du)
            Ns=[n for n in range(top - top % (1<<L), 0, -(1<<L))][:4]
            for N in Ns:
                pre=[r for r in res if r[3] <= N]
                if not pre: continue
                m, clo, chi = pre[-1][0], pre[-1][1], pre[-1][2]
                ul = u_left - N*du
                if ul < 0: continue
                cn = pre[-1][4]; extra = N - pre[-1][3]
                inc=[s<<(LMAX-L) for s in S]; cn=list(cn)
                for _ in range(extra):
                    for a in range(NA): cn[a]+=inc[a]
                cn=tuple(cn)
                nc_ = (clo+N*P, chi+N*P)
                if k+m >= len(evt): sc = m
                elif ul == 0:
                    if nxt is None: sc = m
                    else:
                        S2=[abs(v) for v in nxt]; E2=max(S2)
                        sc = m + quick(nc_[0], nc_[1], tuple([(E2<<LMAX)>>1]*NA), S2, E2, k+m, E2<<LMAX)
                else: sc = m + quick(nc_[0], nc_[1], cn, S, E, k+m, ul)
                cand.append((sc, L, P, N, m, nc_, cn, ul))
    if not cand: return None
    top = max(x[0] for x in cand)
    best_only = [x for x in cand if x[0] == top]
    levels = sorted(set(x[1] for x in best_only))
    if len(levels) == 1:
        for x in best_only:
            r = AMASS.setdefault(x[1], [x[2] << x[1], x[2] << x[1]])
            r[0] = min(r[0], x[2] << x[1]); r[1] = max(r[1], x[2] << x[1])
    def off(x):  # distance of the cycles per step from the range seen at that level
        r = AMASS.get(x[1])
        if r is None: return 1 << 40
        cps = x[2] << x[1]
        return max(0, r[0] - cps, cps - r[1])
    groups = {}
    for x in cand:
        key = (x[1], x[3], x[4], x[6], x[7])
        if key in groups:
            g = groups[key]; g[5] = (min(g[5][0], x[5][0]), max(g[5][1], x[5][1]))
        else: groups[key] = list(x)
    vals = [x for x in groups.values() if rule_ok(x[1], x[2])]
    return sorted(vals, key=lambda x: (-x[0], off(x)))[:6]
def start_interval(S, E, k, cnt, u_left):
    cands=[]
    for L in range(LMAX+1):
        evs = gen(cnt, S, E, L, u_left, 400)[0]
        if len(evs) < 2 or evs[0][1] != evm[k] or evs[1][1] != evm[k+1]: continue
        di = evs[1][0]-evs[0][0]; dt = evt[k+1]-evt[k]
        for P in range(max(1,(dt-1)*CT//di), (dt+1)*CT//di+2):
            res = cwalk(-(1<<50), 1<<50, P, evs, k)
            if res: cands.append((res[-1][0], L, P, res[-1][1], res[-1][2]))
    mb = max(x[0] for x in cands)
    top=[x for x in cands if x[0] == mb]
    return (min(x[3] for x in top), max(x[4] for x in top))
def fresh(bi):
    S=[abs(v) for v in blocks[bi]]; E=max(S)
    return tuple([(E<<LMAX)>>1]*NA), E<<LMAX
cnt0, ul0 = fresh(0)
S0=[abs(v) for v in blocks[0]]
stack=[dict(bi=0, k=0, cint=start_interval(S0, max(S0), 0, cnt0, ul0), cnt=cnt0, ul=ul0, cands=None, idx=0, seg=None)]
best_k=0; best_stack=None; since=0; backtracks=0; shown=0
while stack:
    f=stack[-1]
    if f['k'] >= len(evt) or f['bi'] >= len(blocks): best_stack=list(stack); best_k=f['k']; break
    if f['cands'] is None:
        S=[abs(v) for v in blocks[f['bi']]]; E=max(S)
        nxt = blocks[f['bi']+1] if f['bi']+1 < len(blocks) else None
        f['cands'] = seg_step(S, E, f['k'], f['cint'], f['cnt'], f['ul'], nxt) or []
    if f['idx'] >= len(f['cands']) or since > 400:
        stack.pop(); backtracks += 1; since += 1
        if since > 400: break
        continue
    sc, L, P, N, m, nc_, cn, ul = f['cands'][f['idx']]; f['idx'] += 1
    seg=(f['bi'], L, P, N, m, nc_[1]-nc_[0])
    if ul == 0:
        c2, u2 = fresh(f['bi']+1) if f['bi']+1 < len(blocks) else ((), 0)
        nf=dict(bi=f['bi']+1, k=f['k']+m, cint=nc_, cnt=c2, ul=u2, cands=None, idx=0, seg=seg)
    else:
        nf=dict(bi=f['bi'], k=f['k']+m, cint=nc_, cnt=cn, ul=ul, cands=None, idx=0, seg=seg)
    stack.append(nf)
    if nf['k'] > best_k:
        best_k=nf['k']; best_stack=list(stack); since=0
        if nf['bi'] >= shown + 25:
            shown = nf['bi']
            print('block', shown, 'step ticks', best_k, 'segments', len(stack) - 1, file=sys.stderr, flush=True)
    else: since+=1
segs=[f['seg'] for f in best_stack[1:]]
print('levels', sorted(AMASS.items()), file=sys.stderr)
k=best_k
print('backtracks', backtracks, 'stopped at block', best_stack[-1]['bi'], 'tick', evt[k] if k < len(evt) else None, file=sys.stderr)
for x in segs: print(*x)
print('segments', len(segs), 'step ticks explained', k, 'of', len(evt))
