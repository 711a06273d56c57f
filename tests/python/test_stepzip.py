"""The Python package `stepzip`: round trips of bytes, bytearray, memoryview
and numpy buffers, the streaming Compressor/Decompressor, reverse and forward
interpolation on packed steps and (n, axes) move arrays, vectors in, the
streaming segmenter and its bound, the command line's defaults, the GIL
released in long calls, and errors as stepzip.Error that never repeat the
input. Standard-library unittest; CTest runs it with PYTHONPATH set to the
built package (python.unittest) and against a pip-installed copy
(python.pip_install)."""
import decimal
import io
import os
import random
import sys
import threading
import time
import unittest

import numpy as np

import stepzip

SOURCE = os.environ.get("STEPZIP_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))

MOVES = [(1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1)]


def random_codes(rng, n, four=False):
    """Line-like stretches (repeated two-code patterns) and random turns."""
    out = []
    while len(out) < n:
        base = rng.randrange(0, 8, 2 if four else 1)
        other = (base + (2 if four else 1) * rng.choice((1, -1))) % 8
        period = rng.randint(2, 7)
        for k in range(rng.randint(3, 40)):
            out.append(other if k % period == period - 1 else base)
    return "".join(str(c) for c in out[:n])


class CompressTest(unittest.TestCase):
    def test_round_trip_is_byte_exact(self):
        data = b"# comment\n0 0 0020020020\n5 -3 000100010001222233\n\n10 10 7\n"
        frame = stepzip.compress(data)
        self.assertEqual(stepzip.decompress(frame), data)
        for profile in ("eval4", "eval8", "grbl"):
            frame = stepzip.compress(b"0 0 0000222200002222\n", profile=profile, level=19)
            self.assertEqual(stepzip.decompress(frame), b"0 0 0000222200002222\n")

    def test_corpus_file(self):
        with open(os.path.join(SOURCE, "corpora", "plotter", "hershey-grbl.fc"), "rb") as f:
            data = f.read()
        frame = stepzip.compress(data, profile="grbl")
        self.assertLess(len(frame), len(data))
        self.assertEqual(stepzip.decompress(frame), data)

    def test_errors_carry_code_and_place(self):
        with self.assertRaises(stepzip.Error) as ctx:
            stepzip.compress(b"0 0 0129\n", format="freeman", source="bad.fc")
        self.assertEqual(ctx.exception.code, 20)  # Errc::syntax
        self.assertIn("bad.fc:1:", str(ctx.exception))
        with self.assertRaises(ValueError):  # stepzip.Error is a ValueError
            stepzip.decompress(b"not a frame")
        with self.assertRaises(stepzip.Error):
            stepzip.compress(b"0 0 00\n", profile="nonesuch")


class SegmentTest(unittest.TestCase):
    def test_spec_example_is_one_segment(self):
        steps = stepzip.freeman_to_steps("0020020020")
        self.assertEqual(steps.dtype, np.uint16)
        deltas, phases, profile = stepzip.segment(steps, "patent")
        self.assertEqual(profile, "patent")
        self.assertEqual(deltas.tolist(), [[7, 3]])
        self.assertEqual(phases.tolist(), [[3 - 7]])
        self.assertEqual(stepzip.steps_to_freeman(stepzip.expand(deltas, phases, "patent")),
                         "0020020020")

    def test_every_profile_round_trips(self):
        rng = random.Random(11)
        for profile in ("eval4", "eval8", "patent", "grbl", "marlin"):
            four = profile in ("eval4", "patent")
            for segmenter in ("greedy", "optimal"):
                codes = random_codes(rng, 300, four)
                steps = stepzip.freeman_to_steps(codes)
                deltas, phases, _ = stepzip.segment(steps, profile, segmenter=segmenter)
                self.assertEqual(deltas.shape[1], 2)
                self.assertEqual(int(np.abs(deltas).max(axis=1).sum() if not four
                                     else np.abs(deltas).sum()), len(codes))
                back = stepzip.expand(deltas, phases, profile)
                self.assertTrue(np.array_equal(back, steps), (profile, segmenter))

    def test_lists_are_accepted_and_bad_input_raises(self):
        deltas, _, _ = stepzip.segment([1, 1, 1], "eval8")
        self.assertEqual(deltas.tolist(), [[3, 0]])
        with self.assertRaises(stepzip.Error) as ctx:
            stepzip.segment(stepzip.freeman_to_steps("01"), "eval4")
        self.assertEqual(ctx.exception.code, 22)  # connectivity
        with self.assertRaises(stepzip.Error):
            stepzip.expand(np.array([[5, 2]]), np.array([[100]]), "eval8")


class InterpolateTest(unittest.TestCase):
    def test_gcode_spec_example(self):
        chains = stepzip.interpolate("G0 X0 Y0\nG1 X7 Y3\n", "patent")
        self.assertEqual(len(chains), 1)
        start, steps = chains[0]
        self.assertEqual(start, (0, 0))
        self.assertEqual(stepzip.steps_to_freeman(steps), "0020020020")

    def test_hpgl_lines_come_back_as_segments(self):
        with open(os.path.join(SOURCE, "corpora", "plotter", "gnuplot.hpgl"), encoding="latin-1") as f:
            chains = stepzip.interpolate(f.read(), "eval8")
        self.assertGreater(len(chains), 100)
        for start, steps in chains[:200]:
            deltas, phases, _ = stepzip.segment(steps, "eval8", segmenter="optimal")
            self.assertTrue(np.array_equal(stepzip.expand(deltas, phases, "eval8"), steps))

    def test_step_size(self):
        (start, steps), = stepzip.interpolate("G21\nG0 X1 Y1\nG1 X2 Y1.5\n", "eval8",
                                              step_size="0.5")
        self.assertEqual(start, (2, 2))
        self.assertEqual(stepzip.steps_to_freeman(steps), "01")  # (2, 1): eval8 at F0 = 0


class StreamingTest(unittest.TestCase):
    def test_bound_holds_and_output_is_exact(self):
        rng = random.Random(5)
        codes = random_codes(rng, 2000)
        steps = stepzip.freeman_to_steps(codes)
        for bound in (1, 5, 64):
            seg = stepzip.StreamingSegmenter("eval8", 2, bound)
            parts = []
            emitted = 0
            for i, s in enumerate(steps):
                d, p = seg.push_step(int(s))
                parts.append((d, p))
                emitted += int(np.abs(d).max(axis=1).sum()) if len(d) else 0
                self.assertLessEqual(seg.held, bound)
                self.assertEqual(emitted + seg.held, i + 1)
            parts.append(seg.finish())
            deltas = np.concatenate([d for d, _ in parts])
            phases = np.concatenate([p for _, p in parts])
            self.assertTrue(np.array_equal(stepzip.expand(deltas, phases, "eval8"), steps))

    def test_same_as_batch_greedy_without_forced_cuts(self):
        rng = random.Random(8)
        steps = stepzip.freeman_to_steps(random_codes(rng, 3000))
        seg = stepzip.StreamingSegmenter("grbl")
        parts = [seg.push(steps[i:i + 100]) for i in range(0, len(steps), 100)]
        self.assertEqual(seg.forced_cuts, 0)
        parts.append(seg.finish())
        deltas = np.concatenate([d for d, _ in parts])
        phases = np.concatenate([p for _, p in parts])
        bd, bp, _ = stepzip.segment(steps, "grbl")
        self.assertTrue(np.array_equal(deltas, bd))
        self.assertTrue(np.array_equal(phases, bp))

    def test_bad_arguments(self):
        with self.assertRaises(stepzip.Error):
            stepzip.StreamingSegmenter("eval4", 3)
        seg = stepzip.StreamingSegmenter("eval4")
        with self.assertRaises(stepzip.Error):
            seg.push_step(int(stepzip.freeman_to_steps("1")[0]))
        self.assertEqual(seg.held, 0)


def corpus(name):
    with open(os.path.join(SOURCE, "corpora", "plotter", name), "rb") as f:
        return f.read()


class BuffersTest(unittest.TestCase):
    def test_every_buffer_type_round_trips(self):
        data = corpus("hershey-grbl.fc")
        frame = stepzip.compress(data)
        for kind, buf in (("bytes", data), ("bytearray", bytearray(data)),
                          ("memoryview", memoryview(data)),
                          ("numpy", np.frombuffer(data, dtype=np.uint8)),
                          ("memoryview slice", memoryview(b"xx" + data)[2:])):
            with self.subTest(kind=kind):
                f = stepzip.compress(buf)
                self.assertEqual(f, frame)
                self.assertEqual(stepzip.decompress(bytearray(f)), data)
                self.assertEqual(stepzip.decompress(np.frombuffer(f, dtype=np.uint8)), data)

    def test_errors_do_not_repeat_the_input(self):
        secret = "0 0 " + "0123" * 5000 + "\n"
        with self.assertRaises(TypeError) as ctx:
            stepzip.compress(secret)  # a str is not bytes
        self.assertNotIn("0123", str(ctx.exception))
        self.assertLess(len(str(ctx.exception)), 200)
        with self.assertRaises(TypeError) as ctx:
            stepzip.compress(secret.encode(), level="high")
        self.assertNotIn("0123", str(ctx.exception))
        with self.assertRaises(TypeError) as ctx:
            stepzip.compress(memoryview(np.zeros((40, 40), np.uint8))[::2])  # not contiguous
        self.assertIn("contiguous", str(ctx.exception))
        with self.assertRaises(stepzip.Error) as ctx:
            stepzip.decompress(bytearray(b"\x00" * 50000))
        self.assertLess(len(str(ctx.exception)), 200)


class StreamObjectsTest(unittest.TestCase):
    def test_compressor_pieces_give_the_one_shot_frame(self):
        data = corpus("hershey-grbl.fc")
        c = stepzip.Compressor(level=3)
        parts = [c.compress(memoryview(data)[i:i + 1000]) for i in range(0, len(data), 1000)]
        parts.append(c.flush())
        self.assertEqual(b"".join(parts), stepzip.compress(data))
        # the object starts a new frame after flush()
        self.assertEqual(c.compress(data) + c.flush(), stepzip.compress(data))

    def test_decompressor_pieces_and_copy_stream(self):
        data = corpus("hershey-grbl.fc")
        frame = stepzip.compress(data, profile="grbl")
        d = stepzip.Decompressor()
        out = b"".join(d.decompress(frame[i:i + 77]) for i in range(0, len(frame), 77)) + d.flush()
        self.assertEqual(out, data)
        src, dst = io.BytesIO(frame), io.BytesIO()
        self.assertEqual(stepzip.Decompressor().copy_stream(src, dst, read_size=500),
                         (len(frame), len(data)))
        self.assertEqual(dst.getvalue(), data)
        src, dst = io.BytesIO(data), io.BytesIO()
        read, written = stepzip.Compressor().copy_stream(src, dst)
        self.assertEqual((read, written), (len(data), len(dst.getvalue())))
        self.assertEqual(stepzip.decompress(dst.getvalue()), data)

    def test_stream_errors(self):
        frame = bytearray(stepzip.compress(corpus("hershey-grbl.fc")))
        d = stepzip.Decompressor()
        with self.assertRaises(stepzip.Error):  # cut short: only flush() can tell
            d.decompress(frame[:len(frame) // 2])
            d.flush()
        frame[len(frame) // 2] ^= 0x10
        with self.assertRaises(stepzip.Error):
            d.decompress(frame)
            d.flush()
        frame[len(frame) // 2] ^= 0x10
        self.assertEqual(d.decompress(frame) + d.flush(), corpus("hershey-grbl.fc"))  # usable again
        c = stepzip.Compressor(format="freeman", source="bad.fc")
        with self.assertRaises(stepzip.Error) as ctx:
            c.compress(b"0 0 0011\n5 5 0182\n")
            c.flush()
        self.assertIn("bad.fc:2:", str(ctx.exception))


class MovesTest(unittest.TestCase):
    def test_moves_in_and_out(self):
        codes = random_codes(random.Random(3), 500)
        packed = stepzip.freeman_to_steps(codes)
        moves = stepzip.freeman_to_steps(codes, moves=True)
        self.assertEqual(moves.dtype, np.int8)
        self.assertEqual(moves.shape, (500, 2))
        self.assertEqual(moves.tolist()[:1], [list(MOVES[int(codes[0])])])
        self.assertTrue(np.array_equal(stepzip.from_moves(moves), packed))
        self.assertTrue(np.array_equal(stepzip.to_moves(packed), moves))
        seg = stepzip.segment(moves, "eval8")
        self.assertTrue(np.array_equal(seg.deltas, stepzip.segment(packed, "eval8").deltas))
        self.assertTrue(np.array_equal(stepzip.expand(seg, moves=True), moves))
        self.assertEqual(stepzip.steps_to_freeman(moves), codes)

    def test_three_axes(self):
        rng = random.Random(4)
        moves = np.array([[rng.choice((-1, 0, 1)) for _ in range(3)] for _ in range(400)], np.int8)
        moves[(moves == 0).all(axis=1), 0] = 1  # every row moves
        seg = stepzip.segment(moves)  # axes from the shape, profile auto
        self.assertEqual(seg.deltas.shape[1], 3)
        self.assertTrue(np.array_equal(stepzip.expand(seg, moves=True), moves))
        # other integer dtypes are accepted
        self.assertTrue(np.array_equal(stepzip.from_moves(moves.astype(np.int64)),
                                       stepzip.from_moves(moves)))

    def test_moves_through_a_steps_file(self):
        rng = random.Random(6)
        moves = np.array([[rng.choice((-1, 0, 1)) for _ in range(3)] for _ in range(3000)], np.int8)
        moves[(moves == 0).all(axis=1), 2] = -1
        data = stepzip.to_steps_file(moves)
        self.assertEqual(len(data), len(moves))
        frame = stepzip.compress(data, format="steps")
        back = stepzip.from_steps_file(stepzip.decompress(frame), moves=True)
        self.assertTrue(np.array_equal(back, moves))
        self.assertTrue(np.array_equal(stepzip.from_steps_file(data), stepzip.from_moves(moves)))
        # idle ticks and DIR bits of resting axes are not steps
        ticks = bytes([0x00, 0x01, 0x08, 0x07, 0x02, 0x20])
        self.assertEqual(stepzip.from_steps_file(ticks, moves=True).tolist(), [[1, 0], [-1, 1]])
        with self.assertRaises(stepzip.Error):
            stepzip.to_steps_file(np.ones((3, 5), np.int8))

    def test_bad_moves_name_the_row(self):
        with self.assertRaises(stepzip.Error) as ctx:
            stepzip.from_moves(np.array([[1, 0], [0, 0], [1, 1]]))
        self.assertIn("row 1", str(ctx.exception))
        with self.assertRaises(stepzip.Error) as ctx:
            stepzip.from_moves(np.array([[1, 0], [1, 1], [2, 0]]))
        self.assertIn("row 2", str(ctx.exception))
        with self.assertRaises(TypeError):
            stepzip.from_moves(np.array([[0.5, 1.0]]))
        with self.assertRaises(stepzip.Error):
            stepzip.segment(np.ones((4, 2), np.int8), axes=3)


class TimedMovesTest(unittest.TestCase):
    def read(self, name):
        with open(os.path.join(SOURCE, "corpora", "timed", name), "rb") as f:
            return f.read()

    def test_excerpt_gives_its_job_moves(self):
        # corpora/timed/grbl-excerpt.steps: four moves of a Grbl job, 40 us ticks
        want = [tuple(int(v) for v in line.split()) for line in self.read("grbl-excerpt.moves").decode().splitlines()]
        chains = stepzip.timed_moves(self.read("grbl-excerpt.steps"), 40)
        self.assertEqual(len(chains), 1)
        chain = chains[0]
        self.assertEqual([m.delta for m in chain.moves], want)
        # a step event moves one axis or several: between the two counts
        self.assertGreaterEqual(chain.steps, sum(max(abs(v) for v in m) for m in want))
        self.assertLessEqual(chain.steps, sum(sum(abs(v) for v in m) for m in want))
        last = -1
        for m in chain.moves:
            self.assertGreater(m.ticks[0], last)
            self.assertGreaterEqual(m.ticks[1], m.ticks[0])
            last = m.ticks[1]
            self.assertGreater(m.cruise, 0)
            self.assertLessEqual(m.entry, m.cruise * 1.05)
            self.assertAlmostEqual(m.length, (m.delta[0] ** 2 + m.delta[1] ** 2) ** 0.5, places=6)
        # the axes' steps: every step of the moves, per axis
        self.assertEqual([a.steps for a in chain.axes], [sum(abs(m[i]) for m in want) for i in range(2)])
        # the same bytes through a memoryview; a smaller tolerance cuts more moves
        self.assertEqual(stepzip.timed_moves(memoryview(self.read("grbl-excerpt.steps")), 40), chains)
        self.assertGreater(len(stepzip.timed_moves(self.read("trapezoid-2axis.steps"), 30, tolerance=0.3)[0].moves),
                           len(stepzip.timed_moves(self.read("trapezoid-2axis.steps"), 30)[0].moves))

    def test_axes_give_the_planner_settings(self):
        # corpora/timed/trapezoid-2axis.steps: planned at 500 mm/s^2 and
        # 6000 mm/min per axis, 80 steps/mm, 30 us ticks
        chain = stepzip.timed_moves(self.read("trapezoid-2axis.steps"), 30)[0]
        for axis in chain.axes:
            self.assertGreater(axis.windows, 0)
            # (tests/timed_motion_test.cpp: rates within 2 %, accelerations 10 %)
            self.assertAlmostEqual(axis.acceleration / 80 / 500, 1, delta=0.10)
            self.assertAlmostEqual(axis.max_rate / 80 * 60 / 6000, 1, delta=0.02)

    def test_bad_arguments(self):
        data = self.read("grbl-excerpt.steps")
        for tick in (0, -40, float("nan"), float("inf")):
            with self.assertRaises(stepzip.Error):
                stepzip.timed_moves(data, tick)
        with self.assertRaises(stepzip.Error):
            stepzip.timed_moves(data, 40, tolerance=0)
        with self.assertRaises(TypeError):
            stepzip.timed_moves("not bytes", 40)


class DefaultsTest(unittest.TestCase):
    def test_profile_auto_as_the_command_line(self):
        steps = stepzip.freeman_to_steps("0000111122223333")
        seg = stepzip.segment(steps)  # default profile "auto"
        fewest = min(len(stepzip.segment(steps, p).deltas)
                     for p in ("eval8", "grbl", "marlin"))
        self.assertEqual(len(seg.deltas), fewest)
        self.assertIn(seg.profile, stepzip.PROFILES)
        self.assertTrue(np.array_equal(stepzip.expand(seg), steps))
        data = b"0 0 0011223344556677\n"
        self.assertEqual(stepzip.compress(data), stepzip.compress(data, profile="auto", level=3))

    def test_step_size_as_number_or_string(self):
        text = "G21\nG0 X1 Y1\nG1 X2 Y1.5\n"
        want = stepzip.interpolate(text, "eval8", step_size="0.5")
        for size in (0.5, decimal.Decimal("0.5"), "0.50"):
            got = stepzip.interpolate(text, "eval8", step_size=size)
            self.assertEqual(got[0][0], want[0][0])
            self.assertTrue(np.array_equal(got[0][1], want[0][1]))
        whole = stepzip.interpolate("G0 X0 Y0\nG1 X7 Y3\n", "patent", step_size=1)
        self.assertEqual(stepzip.steps_to_freeman(whole[0][1]), "0020020020")
        tiny = stepzip.interpolate("G21\nG1 X0.00003 Y0\n", "eval8", step_size=1e-05)
        self.assertEqual(stepzip.steps_to_freeman(tiny[0][1]), "000")
        with self.assertRaises(TypeError):
            stepzip.interpolate(text, "eval8", step_size=True)
        with self.assertRaises(stepzip.Error):
            stepzip.interpolate(text, "eval8", step_size=float("nan"))
        (start, moves), = stepzip.interpolate(text.encode(), "eval8", step_size=0.5, moves=True)
        self.assertEqual(moves.tolist(), [[1, 0], [1, 1]])


class GilTest(unittest.TestCase):
    @staticmethod
    def runs_beside(call):
        """True when the main thread runs Python code while `call` runs in
        another thread. The switch interval is made huge, so the interpreter
        never takes the GIL from a thread: the main thread (sleeping, which
        releases the GIL) can run during `call` only if `call` releases it."""
        state = {"inside": False}

        def work():
            state["inside"] = True
            call()
            state["inside"] = False

        old = sys.getswitchinterval()
        sys.setswitchinterval(1000.0)
        try:
            t = threading.Thread(target=work)
            t.start()
            seen = False
            while t.is_alive() and not seen:
                time.sleep(0.001)
                seen = state["inside"]
            t.join()
        finally:
            sys.setswitchinterval(old)
        return seen

    def test_the_probe_sees_a_held_gil(self):
        self.assertFalse(self.runs_beside(lambda: sum(range(3000000))))

    def test_long_calls_release_the_gil(self):
        data = corpus("hershey-grbl.fc") * 4
        frame = stepzip.compress(data)
        steps = stepzip.freeman_to_steps(random_codes(random.Random(9), 300000))
        moves = stepzip.to_moves(steps)
        seg = stepzip.segment(steps, "eval8")
        with open(os.path.join(SOURCE, "corpora", "timed", "trapezoid-3axis.steps"), "rb") as f:
            log = f.read()
        for name, call in (("compress", lambda: stepzip.compress(data)),
                           ("decompress", lambda: stepzip.decompress(frame)),
                           # (three times the data: a streaming call that only buffers
                           # returns within a few ms, too soon for the probe on a busy machine)
                           ("Compressor", lambda: stepzip.Compressor().compress(data * 3)),
                           ("Decompressor", lambda: stepzip.Decompressor().decompress(frame)),
                           ("segment", lambda: stepzip.segment(steps, "eval8", segmenter="optimal")),
                           ("segment auto", lambda: stepzip.segment(steps)),
                           ("expand", lambda: [stepzip.expand(seg) for _ in range(20)]),
                           ("from_moves", lambda: [stepzip.from_moves(moves) for _ in range(20)]),
                           ("timed_moves", lambda: [stepzip.timed_moves(log, 40) for _ in range(3)])):
            with self.subTest(call=name):
                self.assertTrue(self.runs_beside(call), name)


if __name__ == "__main__":
    unittest.main()
