// Run-at-a-time recognition of one two-letter word (not installed).
//
// RunWord answers the same questions as WordRecognizer (recognizer.hpp) but
// reads a whole run of identical letters at once: for a run of k letters it
// says, in O(log h), how many of them keep the word a digital straight
// segment and which prefix lengths inside the run make the word valid (an
// interval); then commit() appends the run. The answers are exactly those of
// feeding the letters one by one to WordRecognizer (tests/recognizer_test.cpp
// compares the two on random and exhaustive inputs).
//
// Why runs suffice. Position c = (p, q) counts the zeros and ones read before
// a letter. The slope interval (lo, hi) of WordRecognizer is
//   lo = max slope(z, c) over a 0-position z and a later 1-position c,
//   hi = min slope(u, c) over a 1-position u and a later 0-position c.
// Inside a run of zeros at (p..p+k-1, q) the slope from any earlier
// 1-position to the j-th zero decreases with j (fixed positive rise, growing
// run), so only the run's last zero lowers hi, and the first zero that makes
// hi <= lo is found by one support query on the upper hull of the
// 1-positions. The word after j+1 zeros has slope q / (p+j+1); each bound on
// it (lo, the old hi, and the new tangents, which reduce to
// (p+j+1) * max u.q/(u.p+1) < q over the 1-positions u) is a bound on p+j+1,
// so the valid prefixes of the run form an interval. Runs of ones are the
// mirror image. The hulls change only by the run's end points.
// What it keeps of its own: the valid prefixes of a run as an interval; the
// hulls, bounds and run updates are the kernel's (dss.hpp, RunState).
// Invariant: after each commit() the state equals WordRecognizer's after the
// same letters one by one. Complexity: O(log h) per run, h = hull vertices
// (O(log n) for a DSS).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "dss.hpp"
#include "stepzip/profile.hpp"
#include "stepzip/step.hpp"

namespace stepzip::detail {

class RunWord {
public:
    /// What appending a run of k equal letters would do.
    struct Probe {
        std::int64_t alive;  ///< letters of the run read while the word stays a DSS (0..k)
        std::int64_t lo;     ///< valid prefixes of the run: lengths m in [lo, hi],
        std::int64_t hi;     ///< 1 <= m <= alive (empty when lo > hi)
    };

    void reset() noexcept { st_.reset(); }
    /// Precondition: the word is alive, k >= 1, letter is 0 or 1.
    Probe probe(int letter, std::int64_t k) const noexcept;
    /// Appends the run. Precondition: probe(letter, k).alive == k.
    void commit(int letter, std::int64_t k);
    std::int64_t zeros() const noexcept { return st_.p; }
    std::int64_t ones() const noexcept { return st_.q; }

private:
    dss::RunState st_;  // hulls and slope bounds (dss.hpp)
};

/// One segment under a linear profile (not patent) grown run by run: the
/// words of SegmentRecognizer (one for eval4, one per axis for the
/// 8-connected profiles) plus its hard limits (one sign per axis, a leading
/// axis moving on every tick, kMaxSegmentTotal), with the same answers.
/// Complexity: O(axes · log h) per run of identical steps.
class RunSegment {
public:
    RunSegment(Profile p, int axes);
    void reset() noexcept;
    /// Appending k copies of step s: `alive` steps keep the segment
    /// extendable (0 when a hard limit refuses s); the steps read so far plus
    /// m of the run form one exact segment for m in [lo, min(hi, alive)].
    RunWord::Probe probe(Step s, std::int64_t k) const noexcept;
    /// Precondition: probe(s, k).alive == k.
    void commit(Step s, std::int64_t k);
    std::int64_t length() const noexcept { return length_; }

private:
    bool eight_;
    int axes_;
    std::int64_t length_ = 0;
    unsigned signs_ = 0;   // STEP/DIR bits of the moves seen (one sign per axis)
    unsigned always_ = 0;  // axes that moved on every tick (8-connected)
    RunWord words_[kMaxAxes];
};

/// Length of the longest exact segment at steps[0] under `rec`'s linear
/// profile, read run by run; 0 for no steps. `rec` is scratch state, reset
/// here, reused across calls. Complexity: O(runs read), reading stops where
/// the word can no longer be extended.
std::int64_t longest_exact_prefix(RunSegment& rec, std::span<const Step> steps);

}  // namespace stepzip::detail
