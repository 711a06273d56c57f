// Greedy cut of two-axis chains under a linear profile (not installed).
//
// On two axes every linear profile reduces to one two-letter word: under
// eval4 letter 0 is an x-step and letter 1 a y-step; under the 8-connected
// profiles letter 1 is a diagonal and letter 0 a step on one axis (the
// leading axis moves on every tick, so its own word is all ones). A segment
// holds at most two distinct step values, one per letter, and they must be
// compatible (one sign per axis; for the 8-connected profiles the axis step
// is a projection of the diagonal). TwoAxisGreedy decides words of up to
// 12 letters by a table and longer ones by the arithmetic recognition of
// digital straight segments (Debled-Rennesson & Reveilles 1995: the strip of
// the minimal characteristics and its four extreme leaning points), a letter
// at a time with a few additions and products: no hulls, no per-axis loops,
// no profile switches. Its answers are those of RunSegment and of the letter-by-letter
// SegmentRecognizer (tests/recognizer_test.cpp,
// tests/segmenter_two_axis_test.cpp).
// Invariant: longest() returns RunSegment's (and SegmentRecognizer's) longest
// exact prefix. Complexity: O(1) per letter (the exactness test only on
// the segment's last stretches, read twice); fit() is O(m) after the
// table's short words and O(log m) (a gcd) after the arithmetic recognition.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "dss.hpp"
#include "stepzip/profile.hpp"
#include "stepzip/segment.hpp"
#include "stepzip/step.hpp"

namespace stepzip::detail {

class TwoAxisGreedy {
public:
    /// Precondition: p is not Profile::patent.
    explicit TwoAxisGreedy(Profile p);
    /// Length of the longest exact segment at steps[0] (>= 1; 0 for empty
    /// input). The steps must be valid for the profile on two axes.
    std::int64_t longest(std::span<const Step> steps);
    /// fit_segment(p, steps.first(m), 2), for m = longest(steps) called just
    /// before on the same steps (it takes the letters' step values that call
    /// admitted). nullopt only if the prefix is not one exact segment.
    std::optional<Segment> fit(std::span<const Step> steps, std::int64_t m) const;

private:
    Profile profile_;
    bool eight_;
    // The step value of each letter, admitted by the last longest(); its
    // answer and the ones (letter 1) in that prefix; the least value of
    // p*b - q*a over its positions when the arithmetic recognition found it.
    Step value_[2] = {0, 0};
    std::int64_t best_length_ = 0, best_ones_ = 0;
    std::optional<std::int64_t> best_lowest_;
};

}  // namespace stepzip::detail
