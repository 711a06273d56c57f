// cut_block(): the block-level entry point of the segmenters
// (stepzip/segment/block_cut.hpp).
#include "stepzip/segment/block_cut.hpp"

#include <string>

#include "accepted_cut.hpp"
#include "default_phase_cut.hpp"

namespace stepzip {

namespace {

// cut_block(), checking each chain's steps first unless `accepted`.
Result<void> cut_chains(std::span<const Chain> chains, int axes, Profile p, BlockCut kind,
                        std::vector<std::vector<Segment>>& out, SegmentStats* stats, std::uint64_t first_chain,
                        bool accepted) {
    out.assign(chains.size(), {});
    // The chain's name for an error message, built only on error (no
    // allocation per chain on the way).
    auto chain = [&](std::size_t c) {
        return "chain " + std::to_string(first_chain + c + 1) + ": profile " + std::string(profile_name(p)) + ": ";
    };
    for (std::size_t c = 0; c < chains.size(); ++c) {
        if (kind == BlockCut::default_phase) {
            if (!cut_preferring_default(chains[c].steps, axes, p, out[c], accepted))
                return make_error(Errc::unsupported, chain(c) + "no default-phase cut");
            continue;
        }
        const SegmenterKind k = kind == BlockCut::optimal ? SegmenterKind::optimal
                                : kind == BlockCut::patent ? SegmenterKind::patent
                                                           : SegmenterKind::greedy;
        auto r = accepted ? segment_accepted_steps(chains[c].steps, axes, p, k, out[c], stats)
                          : segment_steps(chains[c].steps, axes, p, k, out[c], stats);
        if (!r) return make_error(r.error().code, chain(c) + r.error().message);
    }
    return {};
}

}  // namespace

Result<void> cut_block(std::span<const Chain> chains, int axes, Profile p, BlockCut kind,
                       std::vector<std::vector<Segment>>& out, SegmentStats* stats, std::uint64_t first_chain) {
    return cut_chains(chains, axes, p, kind, out, stats, first_chain, false);
}

Result<void> cut_accepted_block(std::span<const Chain> chains, int axes, Profile p, BlockCut kind,
                                std::vector<std::vector<Segment>>& out, SegmentStats* stats,
                                std::uint64_t first_chain) {
    return cut_chains(chains, axes, p, kind, out, stats, first_chain, true);
}

}  // namespace stepzip
