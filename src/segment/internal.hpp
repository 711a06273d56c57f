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

/// Times a segmenter fell back to a shorter cut because a recognizer claimed
/// a prefix that no segment fits. The output stays exact, so only this count
/// shows such a recognizer bug in a release build; the tests require zero.
void count_segmenter_fallback() noexcept;
std::uint64_t segmenter_fallbacks() noexcept;

}  // namespace stepzip
