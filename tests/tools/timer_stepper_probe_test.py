"""corpora/tools/timer_stepper_probe.py on logs written by a small segment
generator of this test (trapezoid moves cut into 10 ms segments with the dt
remainder carried, levels and periods by Grbl's threshold rule, interrupts
by the probe's own interrupt model): the probe must fit every move, choose
integer periods that regenerate the log tick for tick, and find the
segments that were written (up to two a cut that the ticks leave open). A log with one step moved by a tick must not be
reproduced.

Usage: timer_stepper_probe_test.py SOURCE_DIR"""
import json
import math
import os
import subprocess
import sys
import tempfile

SOURCE = sys.argv[1]
PROBE = os.path.join(SOURCE, 'corpora', 'tools', 'timer_stepper_probe.py')
sys.path.insert(0, os.path.dirname(PROBE))
import timer_stepper_probe as probe  # noqa: E402

CPU, SEG, CT = 16e6, 160000, 640
MODEL = probe.Model(CT, [2000, 4000, 8000], SEG)


def move_segments(E, v0, v1, vmax, acc):
    """Grbl-like segments (cycles per step, leading steps) of a move of E
    steps from speed v0 to v1 (steps/s), cruise vmax, acceleration acc."""
    d_acc = (vmax * vmax - v0 * v0) / (2 * acc); d_dec = (vmax * vmax - v1 * v1) / (2 * acc)
    if d_acc + d_dec > E:
        vmax = math.sqrt((2 * acc * E + v0 * v0 + v1 * v1) / 2)
        d_acc = (vmax * vmax - v0 * v0) / (2 * acc); d_dec = E - d_acc
    t_acc = (vmax - v0) / acc; t_cru = (E - d_acc - d_dec) / vmax; t_dec = (vmax - v1) / acc

    def x(t):
        if t <= t_acc: return v0 * t + acc * t * t / 2
        if t <= t_acc + t_cru: return d_acc + vmax * (t - t_acc)
        u = min(t - t_acc - t_cru, t_dec)
        return E - d_dec + vmax * u - acc * u * u / 2
    end = t_acc + t_cru + t_dec
    out = []; t = 0.0; prev_rem = float(E); rem_time = 0.0
    while math.ceil(prev_rem) > 0:
        dt = 0.01
        while x(t + dt) - x(t) < 1.25 and t + dt < end: dt += 0.01
        dt = min(dt, end - t)
        rem = max(0.0, E - x(t + dt)) if t + dt < end else 0.0
        n = math.ceil(prev_rem) - math.ceil(rem)
        inv = (dt + rem_time) / (math.ceil(prev_rem) - rem)
        out.append((math.ceil(CPU * inv), n))
        rem_time = (math.ceil(rem) - rem) * inv
        prev_rem = rem; t += dt
    return out


def write_log(moves, speeds, path):
    segs, conc = [], []
    c = 5 * CT
    for b, (m, (v0, v1, vmax)) in enumerate(zip(moves, speeds)):
        E = max(abs(v) for v in m)
        for cps, n in move_segments(E, v0, v1, vmax, 20000.0):
            L = sum(1 for t in MODEL.thr if cps >= t)
            P = min(cps >> L, 0xffff) + 1
            segs.append((L, n << L, b, None)); conc.append((c, P)); c += (n << L) * P
    size = c // CT + 2
    log = probe.regenerate(MODEL, moves, segs, conc, size)
    first = next(i for i, v in enumerate(log) if v & 0x15)
    last = max(i for i, v in enumerate(log) if v & 0x15)
    with open(path, 'wb') as f:
        f.write(log[first:last + 1])
    return segs


def run(log, report):
    r = subprocess.run([sys.executable, PROBE, log, report], capture_output=True, text=True)
    return r.returncode, r.stdout


def found_moves(log, moves):
    """`stepzip segment --to json` of the log when it finds `moves` (each
    with the ticks of its first and last step): the moves' ends are where
    the log's position first reaches them."""
    d, evt, evm, dirch = probe.read_log(log, len(moves[0]))
    pos = [0] * len(moves[0]); ends = []; k = 0; dbits = 0; di = 0; want = [0] * len(moves[0])
    for m in moves:
        want = [want[a] + m[a] for a in range(len(m))]
        start = k
        while pos != want:
            while di < len(dirch) and dirch[di][0] <= evt[k]: dbits = dirch[di][1]; di += 1
            for a in range(len(pos)):
                if evm[k] >> a & 1: pos[a] += -1 if dbits >> a & 1 else 1
            k += 1
        ends.append((evt[start], evt[k - 1]))
    return {'chains': [{'moves': [{'delta': list(m), 'ticks': list(t)} for m, t in zip(moves, ends)]}]}


def main():
    moves = [(900, 350), (-120, 260), (0, -700), (40, -15), (-820, -595)]
    speeds = [(0, 900, 4000), (900, 0, 3000), (0, 0, 5000), (0, 300, 2000), (300, 0, 4500)]
    with tempfile.TemporaryDirectory() as tmp:
        log = os.path.join(tmp, 'log.steps'); report = os.path.join(tmp, 'moves.json')
        segs = write_log(moves, speeds, log)
        with open(report, 'w') as f:
            json.dump([{'steps': list(m)} for m in moves], f)
        rc, out = run(log, report)
        print(out)
        assert rc == 0, 'the probe does not reproduce the log'
        assert 'moves fitted %d of %d' % (len(moves), len(moves)) in out
        assert 'ticks regenerated differently 0 ' in out
        # the segments written, up to a few that the ticks leave open (a cut at a
        # rate that does not change)
        got = next(line for line in out.split('\n') if line.startswith('segments '))
        n = int(got.split()[1])
        assert abs(n - len(segs)) <= 2, (n, len(segs))
        levels = eval(got.split(' levels ')[1])
        for L in range(4):
            want = sum(1 for s in segs if s[0] == L)
            assert abs(levels[L] - want) <= 2, (L, levels[L], want)
        # one step a tick later: the model cannot make it
        data = bytearray(open(log, 'rb').read())
        t = next(i for i in range(len(data) // 2, len(data)) if data[i] & 1 and not data[i + 1] & 1)
        data[t] &= ~1; data[t + 1] |= 1
        open(log, 'wb').write(bytes(data))
        rc, out = run(log, report)
        print(out)
        assert rc != 0 and 'moves fitted %d of' % len(moves) not in out
        # --restart on the moves found in a log: all of them; with the third
        # move (straight down) cut in two, its first half fits (a move may end
        # anywhere), the second does not, and the fit starts again after it
        segs = write_log(moves, speeds, log)
        total = sum(1 for v in open(log, 'rb').read() if v & 0x15)
        cut = moves[:2] + [(0, -350), (0, -350)] + moves[3:]
        for given, fitted in ((moves, len(moves)), (cut, len(moves))):
            with open(report, 'w') as f:
                json.dump(found_moves(log, given), f)
            r = subprocess.run([sys.executable, PROBE, log, report, '--restart'], capture_output=True, text=True)
            print(r.stdout)
            assert r.returncode == 0
            restarts = len(given) - fitted
            assert 'moves fitted whole %d of %d (restarts %d)' % (fitted, len(given), restarts) in r.stdout, r.stdout
            if fitted == len(given):
                assert 'step events in them %d of %d' % (total, total) in r.stdout, r.stdout
    planner_reproduces_grbl()
    print('ok')


def planner_reproduces_grbl():
    """--planner's model of Grbl 1.1 (planner, segment generator, interrupt)
    on the real stream's first 15 moves (corpora/timed/grbl-start.*, cut from
    ../shared/corpora-timed): from the job and one start cycle it writes the
    stream's 74 568 ticks as Grbl did; with the junction deviation 0.011 mm
    for 0.010 or the acceleration 201 mm/s^2 for 200 it does not."""
    job = os.path.join(SOURCE, 'corpora', 'timed', 'grbl-start.nc')
    log = os.path.join(SOURCE, 'corpora', 'timed', 'grbl-start.steps')
    ar = probe.Arith(False)
    moves, flags, settings = probe.read_job(job, 100, ar)
    assert len(moves) == 30, len(moves)
    data, evt, evm, _ = probe.read_log(log, 2)

    def reproduces(settings):
        pred, replans = probe.simulate_grbl(moves, flags, settings, ar)
        pred = [seg for seg in pred if seg[0] < 15]
        c0, k = probe.planner_start(MODEL, moves, pred, evt, evm)
        if k < len(evt):
            return False, k
        out = probe.planner_log(MODEL, moves, pred, c0, len(data))
        return bytes(out) == data, sum(1 for a, b in zip(out, data) if a != b)

    ok, k = reproduces(settings)
    assert ok, ('the planner model does not write grbl-start.steps', k)
    for key, value in (('jdev', probe.f32(0.011)), ('accel', [probe.f32(201 * 3600.0)] * 2)):
        ok, k = reproduces(dict(settings, **{key: value}))
        assert not ok, ('reproduced with', key, value)


if __name__ == '__main__':
    main()
