// stepzip — segments: what reverse interpolation finds and forward
// interpolation expands.
#pragma once

#include <array>
#include <cstdint>
#include <cstdlib>

#include "stepzip/step.hpp"

namespace stepzip {

/// One line segment: per-axis totals plus the initial values of its
/// evaluation functions (the phase).
///
/// `phase[j]` is the initial value F0 of the j-th evaluation function:
///  - two-axis 4-connected profiles (eval4, patent): phase[0] is the F0 of
///    the single function;
///  - leading-axis profiles (eval8, grbl, marlin): phase[j] belongs to the
///    j-th minor axis, counting axes in increasing index and skipping the
///    leading axis (see leading_axis()).
/// A phase whose function never decides anything (a pure run or pure
/// diagonal on that axis) is ignored by forward interpolation.
struct Segment {
    Point delta{};
    std::array<std::int64_t, kMaxAxes - 1> phase{};
    friend bool operator==(const Segment&, const Segment&) = default;
};

/// The leading axis of `delta`: the lowest-index axis with the largest |total|.
/// Thread-safe (as are all functions in this header).
inline int leading_axis(const Point& delta, int axes) noexcept {
    int lead = 0;
    for (int i = 1; i < axes; ++i)
        if (std::llabs(delta[i]) > std::llabs(delta[lead])) lead = i;
    return lead;
}

/// Number of steps (ticks) in the segment under a 4-connected profile
/// (sum of |totals|) or an 8-connected one (max |total|).
inline std::int64_t segment_length(const Point& delta, int axes, bool eight_connected) noexcept {
    std::int64_t n = 0;
    for (int i = 0; i < axes; ++i) {
        const std::int64_t v = std::llabs(delta[i]);
        n = eight_connected ? (v > n ? v : n) : n + v;
    }
    return n;
}

}  // namespace stepzip
