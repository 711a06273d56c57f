// The default-phase segmenter: a cut of a chain that prefers default-phase
// segments (default_phase_cut.cpp). Internal to src/segment; other code
// reaches it through cut_block() (stepzip/segment/block_cut.hpp).
#pragma once

#include <span>
#include <vector>

#include "stepzip/profile.hpp"
#include "stepzip/segment.hpp"
#include "stepzip/step.hpp"

namespace stepzip {

/// Appends to `out` exact segments of `steps` under `p`: at each point the
/// longest segment drawn at the profile's default phase that is at least half
/// as long as the longest exact segment there, else the longest exact one.
/// Returns false (and leaves `out` partial) for the patent profile or when a
/// run cannot be fitted. `accepted`: the caller has checked the steps with
/// profile_accepts(p, steps, axes), which is then not done again. Thread-safe.
bool cut_preferring_default(std::span<const Step> steps, int axes, Profile p,
                            std::vector<Segment>& out, bool accepted = false);

/// The same cut read step by step, with every candidate pattern expanded
/// (the reference the fast two-axis path is tested against; used for more
/// than two axes).
bool cut_preferring_default_reference(std::span<const Step> steps, int axes, Profile p,
                                      std::vector<Segment>& out);

}  // namespace stepzip
