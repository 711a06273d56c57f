// Internal: forward interpolation of one segment into a caller's buffer, for
// the decoders' hot paths (no vector growth per segment). Not installed.
#pragma once

#include "stepzip/profile.hpp"
#include "stepzip/segment.hpp"
#include "stepzip/step.hpp"

namespace stepzip::detail {

/// Writes the steps of `seg` to out[0, segment_length) where a fast path of
/// the profile's interpolator applies (exactly what expand_segment appends,
/// tests/container_fast_paths_test.cpp compares them); false, and nothing
/// written, otherwise (the caller falls back to expand_segment).
/// Precondition: check_segment(p, seg, axes) succeeds and `out` holds
/// segment_length(seg.delta, axes, profile_eight_connected(p)) steps.
bool expand_segment_into(Profile p, const Segment& seg, int axes, Step* out);

}  // namespace stepzip::detail
