// stepzip — one call that cuts every chain of a block into exact segments,
// by a segmenter (segmenter.hpp) or by the default-phase segmenter.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "stepzip/chain.hpp"
#include "stepzip/error.hpp"
#include "stepzip/profile.hpp"
#include "stepzip/segment.hpp"
#include "stepzip/segmenter.hpp"

namespace stepzip {

/// How the chains of a block are cut.
enum class BlockCut : std::uint8_t {
    greedy,         ///< SegmenterKind::greedy
    optimal,        ///< SegmenterKind::optimal
    patent,         ///< SegmenterKind::patent
    /// Greedy, but at each point the longest segment drawn at the profile's
    /// default phase when it is at least half as long as the longest exact
    /// segment there (looking up to 64 steps back): a stream drawn by a
    /// controller is cut at its original vectors, which repeat and cost no
    /// phase. Not for the patent profile.
    default_phase,
};

/// The cut of a segmenter kind.
constexpr BlockCut block_cut_of(SegmenterKind k) noexcept {
    return k == SegmenterKind::optimal ? BlockCut::optimal
           : k == SegmenterKind::patent ? BlockCut::patent
                                        : BlockCut::greedy;
}

/// Cuts every chain of `chains` (all on `axes` axes) under `p`: out[i] are
/// the segments of chains[i]; `stats` gathers the patent segmenter's
/// statistics. Errors name the chain as "chain N: " with N = first_chain +
/// its index + 1: the segmenter's errors (segment_steps()), and
/// Errc::unsupported when the default-phase cut does not apply (patent
/// profile, or a run it cannot fit). Thread-safe.
Result<void> cut_block(std::span<const Chain> chains, int axes, Profile p, BlockCut kind,
                       std::vector<std::vector<Segment>>& out, SegmentStats* stats = nullptr,
                       std::uint64_t first_chain = 0);

}  // namespace stepzip
