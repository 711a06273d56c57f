// stepzip — online recognition of one exact segment (reverse interpolation).
//
// Every linear profile except `patent` reduces to one binary rule per
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
/// Complexity: O(axes · log h) per step. Not thread-safe.
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
    std::int64_t length() const noexcept { return length_; }
    const Point& delta() const noexcept { return delta_; }

private:
    Profile profile_;
    int axes_;
    bool eight_;
    std::int64_t length_ = 0;
    Point delta_{};
    int sign_[kMaxAxes] = {};
    unsigned always_ = 0;  // axes that moved on every tick (8-connected)
    WordRecognizer words_[kMaxAxes];
};

/// The one segment that reproduces `steps` exactly under `p` (any profile,
/// patent included), with each phase the valid one nearest the profile's
/// default (SPEC §3), or nullopt when no single segment does.
/// Complexity: O(steps · axes). Thread-safe. Does not check connectivity
/// beyond what exactness implies.
std::optional<Segment> fit_segment(Profile p, std::span<const Step> steps, int axes);

}  // namespace stepzip
