// Helpers shared by the segmenter drivers (not installed).
#pragma once

#include <cstdint>
#include <span>

#include "stepzip/step.hpp"

namespace stepzip {

/// Steps from steps[0] that keep one axis per step and one sign per axis, at
/// most `cap`: the hard limit of a segment under the `patent` profile.
std::int64_t patent_reach(std::span<const Step> steps, std::int64_t cap);

/// Does some phase in phase_range(patent, a, b) make the patent forward mode
/// (Fig. 4) reproduce steps[0, m), whose x and y totals are (a, b) (signs
/// fixed)? One linear constraint on F0 per free step (see fit.cpp); stops at
/// the first contradiction. Complexity: O(m).
bool patent_prefix_exact(std::span<const Step> steps, std::int64_t m, std::int64_t a,
                         std::int64_t b);

}  // namespace stepzip
