// Cuts of chains whose steps the caller has already checked with
// profile_accepts() (block_cut.cpp, segmenter.cpp). Internal to the library:
// the frame's block strategy checks each block's chains once, when it asks
// whether the profile can represent the block, and then cuts them.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "stepzip/chain.hpp"
#include "stepzip/error.hpp"
#include "stepzip/profile.hpp"
#include "stepzip/segment.hpp"
#include "stepzip/segment/block_cut.hpp"
#include "stepzip/segmenter.hpp"

namespace stepzip {

/// segment_steps() without its profile_accepts() check. Precondition:
/// profile_accepts(p, steps, axes) succeeded. Errors: the patent
/// segmenter's only. Thread-safe.
Result<void> segment_accepted_steps(std::span<const Step> steps, int axes, Profile p, SegmenterKind kind,
                                    std::vector<Segment>& out, SegmentStats* stats = nullptr);

/// cut_block() of chains each accepted by profile_accepts(p, steps, axes):
/// the same cut, without checking the steps again. Errors as cut_block()'s
/// but profile_accepts()'s. Thread-safe.
Result<void> cut_accepted_block(std::span<const Chain> chains, int axes, Profile p, BlockCut kind,
                                std::vector<std::vector<Segment>>& out, SegmentStats* stats = nullptr,
                                std::uint64_t first_chain = 0);

}  // namespace stepzip
