// stepzip — chains: a start point and a sequence of unit steps.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "stepzip/error.hpp"
#include "stepzip/step.hpp"

namespace stepzip {

/// A unit-step chain on 2 to kMaxAxes axes.
struct Chain {
    int axes = 2;
    Point start{};
    std::vector<Step> steps;

    /// The point after all steps.
    Point end() const noexcept;
    /// True when every step moves exactly one axis.
    bool four_connected() const noexcept;
    friend bool operator==(const Chain&, const Chain&) = default;
};

/// Freeman-8 digits ("0020020020") for a two-axis chain's steps.
/// Errors: Errc::invalid_argument when the chain is not two-axis or holds a
/// step that has no Freeman code.
Result<std::string> to_freeman(const Chain& chain);

/// A two-axis chain from a start point and Freeman-8 digits.
/// Errors: Errc::syntax naming the 1-based position of the first character
/// that is not a digit 0-7.
Result<Chain> from_freeman(std::int64_t x0, std::int64_t y0, std::string_view codes);

/// The points visited by `chain`, start included (steps.size() + 1 points).
/// Thread-safe (as are all functions in this header); does not check that
/// the steps are valid on chain.axes axes.
std::vector<Point> chain_points(const Chain& chain);

}  // namespace stepzip
