// stepzip — online recognition of one exact segment (reverse interpolation).
//
// Every linear profile except `patent` (PatentRecognizer below) reduces to one binary rule per
// evaluation function (the "two-letter word"): with counts (a, b) and phase
// F0, F >= 0 emits letter 0 and F -= b, F < 0 emits letter 1 and F += a.
//   eval4: letter 0 = x-step, letter 1 = y-step, (a, b) = (|dx|, |dy|);
//   eval8, grbl, marlin: per minor axis, letter 0 = the axis rests on a tick,
//   letter 1 = it moves, (a, b) = (L - S, S).
// After p zeros and q ones F = F0 - p·b + q·a, so a word with totals (A, B)
// is produced by phase F0 iff F0 >= p·B - q·A at every position (p, q) before
// a 0 and F0 < p·B - q·A at every position before a 1. The word is a digital
// straight segment (DSS) while some slope B/A admits such an F0; the set of
// those slopes is an open interval that only shrinks as the word grows.
// Sources: seed 000 (evaluation function), seed 002 (multi-axis), the DSS
// recognition of Debled-Rennesson & Reveillès 1995 (here in its dual form:
// convex hulls of the two position sets and their tangents).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <variant>
#include <vector>

#include "stepzip/profile.hpp"
#include "stepzip/segment.hpp"
#include "stepzip/step.hpp"

namespace stepzip {

/// Online recognizer of one two-letter word.
/// Invariant: (t_lo, t_hi) is exactly the set of real slopes b/a for which
/// some F0 produces the word read so far; valid() is true iff the word's own
/// slope B/A lies in it (or the word uses one letter only). Phases in the
/// profile's range [-B, A) need no separate check: the last 0 and the last 1
/// of a word already bound F0 to that range.
/// Complexity: O(log h) per letter, h = vertices of the two convex hulls
/// (O(log n) for a digital straight segment of n letters); O(n) memory.
/// Not thread-safe (an object per thread).
class WordRecognizer {
public:
    /// Forgets every letter.
    void reset() noexcept;
    /// Appends letter 0 or 1. Returns alive(): false once no slope fits, after
    /// which no longer word can be valid either (further letters are ignored).
    bool extend(int letter);
    /// Some slope and phase still produce the word.
    bool alive() const noexcept { return alive_; }
    /// The word is produced by the rule with (a, b) = (zeros(), ones()).
    bool valid() const noexcept;
    std::int64_t zeros() const noexcept { return p_; }
    std::int64_t ones() const noexcept { return q_; }

private:
    struct Pt {
        std::int64_t p, q;
    };
    // A slope n/d with d > 0; `set` false means unbounded.
    struct Slope {
        std::int64_t n = 0, d = 1;
        bool set = false;
    };
    std::vector<Pt> zeros_hull_;  // lower hull of the positions before a 0
    std::vector<Pt> ones_hull_;   // upper hull of the positions before a 1
    Slope lo_, hi_;
    std::int64_t p_ = 0, q_ = 0;
    bool alive_ = true;
};

/// Grows one segment under a linear profile (eval4, eval8, grbl, marlin),
/// tick by tick: the hard limits (signs fixed per segment, one axis per step
/// for eval4, a leading axis that moves on every tick for the 8-connected
/// profiles, kMaxSegmentTotal) are checked by can_extend(); exactness by one
/// WordRecognizer per evaluation function.
/// Invariant: longest_valid() is the longest prefix read that is one exact
/// segment. Complexity: O(axes · log h) per step. Not thread-safe.
class SegmentRecognizer {
public:
    /// Precondition: p is not Profile::patent; 2 <= axes <= profile_max_axes(p).
    SegmentRecognizer(Profile p, int axes);
    void reset() noexcept;
    /// True when `s` may follow the steps read so far without breaking a hard
    /// limit and the words are still alive. `s` must be valid for the profile.
    bool can_extend(Step s) const noexcept;
    /// Appends `s` (precondition: can_extend(s)). Returns false when no
    /// segment starting with the steps read so far can be exact any more.
    bool extend(Step s);
    /// The steps read so far form one exact segment (some phase reproduces them).
    bool valid() const noexcept;
    /// Length of the longest prefix of the steps read that was valid (0: none).
    std::int64_t longest_valid() const noexcept { return best_; }
    std::int64_t length() const noexcept { return length_; }
    const Point& delta() const noexcept { return delta_; }

private:
    Profile profile_;
    int axes_;
    bool eight_;
    std::int64_t length_ = 0;
    std::int64_t best_ = 0;
    Point delta_{};
    int sign_[kMaxAxes] = {};
    unsigned always_ = 0;  // axes that moved on every tick (8-connected)
    WordRecognizer words_[kMaxAxes];
};

/// Longest segment accepted under the `patent` profile. Its forward mode is
/// path dependent (the adder sums the remaining counters, i.e. a swept area),
/// so a candidate end point is checked exactly in O(length); this cap bounds
/// that work to O(cap) per candidate.
inline constexpr std::int64_t kPatentMaxSegment = 1024;

/// Grows one segment under the `patent` profile (SU 1089551 forward mode,
/// Fig. 4), step by step. The hard limits (one axis per step, one sign per
/// axis, kPatentMaxSegment steps) are checked by can_extend(). The forward
/// mode adds the *remaining* counters, so whether a prefix is exact depends
/// on its own totals: each free step (both counters non-zero) bounds F0 by
/// one linear constraint, intersected with phase_range(patent, X, Y); the
/// check stops at the first contradiction. The pair of constraints that
/// contradicted each other last is tried first on the next candidate (the
/// next shorter one, in longest_valid(): usually the same pair contradicts
/// again), which rejects most candidates in O(1).
/// Invariant: the steps read so far keep one axis per step and one sign per
/// axis. Complexity: O(1) per extend(); valid() O(length);
/// longest_valid() O(length) per candidate, longest first. O(length) memory.
/// Not thread-safe (an object per thread; const calls update the pair).
class PatentRecognizer {
public:
    void reset() noexcept;
    /// True when `s` may follow the steps read so far: one axis, a sign that
    /// agrees with the segment's, fewer than kPatentMaxSegment steps read.
    bool can_extend(Step s) const noexcept;
    /// Appends `s` (precondition: can_extend(s)). Returns false once the cap
    /// is reached: no longer segment is accepted.
    bool extend(Step s);
    /// reset(), then every step of `steps` that can_extend() takes, as
    /// extend() would, without a call per step. Returns the count read.
    std::int64_t read(std::span<const Step> steps);
    /// The steps read so far form one exact segment.
    bool valid() const;
    /// Length of the longest prefix of the steps read that is one exact
    /// segment (1 when only one step is; 0 when none was read).
    std::int64_t longest_valid() const;
    std::int64_t length() const noexcept { return static_cast<std::int64_t>(ystep_.size()); }
    const Point& delta() const noexcept { return delta_; }

private:
    // Is the prefix of m steps, xs of them x-steps, exact under some phase
    // in its phase range?
    bool exact(std::int64_t m, std::int64_t xs) const noexcept;
    // Brings xs_before_ and c_ up to the steps read.
    void sync() const;

    // Per step k read: whether it is a y-step; made by sync(): the x-steps
    // before it (i_k; j_k = k - i_k) and c_k, the part of the adder's change
    // before it that does not depend on the totals: f_k = i_k*Y - j_k*X + c_k.
    std::vector<std::uint8_t> ystep_;
    mutable std::vector<std::int32_t> xs_before_;
    mutable std::vector<std::int64_t> c_;
    mutable std::int32_t synced_xs_ = 0;  // i and c of the next step to sync
    mutable std::int64_t synced_c_ = 0;
    Point delta_{};
    // The steps of the two constraints that contradicted last (-1: none).
    mutable std::int64_t last_lo_ = -1, last_hi_ = -1;
};

/// The recognizer of a profile: PatentRecognizer for `patent`, a
/// SegmentRecognizer for the linear profiles. Both have reset(),
/// can_extend(), extend(), valid(), longest_valid(), length() and delta().
using ProfileRecognizer = std::variant<SegmentRecognizer, PatentRecognizer>;
/// Precondition: 2 <= axes <= profile_max_axes(p).
ProfileRecognizer make_recognizer(Profile p, int axes);

/// The one segment that reproduces `steps` exactly under `p` (any profile,
/// patent included), with each phase the valid one nearest the profile's
/// default (SPEC §3), or nullopt when no single segment does.
/// Complexity: O(steps · axes). Thread-safe. Does not check connectivity
/// beyond what exactness implies.
std::optional<Segment> fit_segment(Profile p, std::span<const Step> steps, int axes);

}  // namespace stepzip
