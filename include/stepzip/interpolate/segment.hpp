// stepzip — forward interpolation of one segment under a profile.
//
// The container format depends on this definition: a segment stored under a
// profile must expand, by the profile's interpolator, to exactly its steps.
// docs/FORMAT.md gives the same arithmetic as normative pseudocode.
#pragma once

#include <vector>

#include "stepzip/profile.hpp"
#include "stepzip/segment.hpp"
#include "stepzip/step.hpp"

namespace stepzip {

/// Forward interpolation: appends the steps of `seg` under profile `p` to
/// `out` (eval4: eval_linear; patent: patent_forward; eval8, grbl, marlin:
/// multiaxis_linear, all in interpolate/linear.hpp).
/// Precondition: check_segment(p, seg, axes) succeeds.
/// Thread-safe (no shared state). Complexity: O(steps * axes).
void expand_segment(Profile p, const Segment& seg, int axes, std::vector<Step>& out);

}  // namespace stepzip
