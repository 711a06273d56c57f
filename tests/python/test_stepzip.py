"""The Python module `stepzip`: round trips on bytes, reverse and forward
interpolation on numpy arrays, vectors in, the streaming segmenter and its
bound, and errors as stepzip.Error. Standard-library unittest; CTest runs it
with PYTHONPATH set to the built module."""
import os
import random
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
        deltas, phases = stepzip.segment(steps, "patent")
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
                deltas, phases = stepzip.segment(steps, profile, segmenter=segmenter)
                self.assertEqual(deltas.shape[1], 2)
                self.assertEqual(int(np.abs(deltas).max(axis=1).sum() if not four
                                     else np.abs(deltas).sum()), len(codes))
                back = stepzip.expand(deltas, phases, profile)
                self.assertTrue(np.array_equal(back, steps), (profile, segmenter))

    def test_lists_are_accepted_and_bad_input_raises(self):
        deltas, _ = stepzip.segment([1, 1, 1], "eval8")
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
            deltas, phases = stepzip.segment(steps, "eval8", segmenter="optimal")
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
        bd, bp = stepzip.segment(steps, "grbl")
        self.assertTrue(np.array_equal(deltas, bd))
        self.assertTrue(np.array_equal(phases, bp))

    def test_bad_arguments(self):
        with self.assertRaises(stepzip.Error):
            stepzip.StreamingSegmenter("eval4", 3)
        seg = stepzip.StreamingSegmenter("eval4")
        with self.assertRaises(stepzip.Error):
            seg.push_step(int(stepzip.freeman_to_steps("1")[0]))
        self.assertEqual(seg.held, 0)


if __name__ == "__main__":
    unittest.main()
