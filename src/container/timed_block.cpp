// Timed blocks; see timed_block.hpp and docs/FORMAT.md "Timed block".
// Complexity: as the segment model, plus the phase alignment of the
// encoder, O(L · axes · log L) per segment.
#include "timed_block.hpp"

#include "modeled_block.hpp"
#include "timed_phase.hpp"
#include "timed_tick.hpp"

namespace stepzip::stz {

std::string write_timed_block(const Block& block, Profile p, std::vector<std::vector<Segment>>& segs,
                              const WindowView* window, bool mixed) {
    if (p != Profile::eval8 && p != Profile::grbl && p != Profile::marlin) return {};
    for (const auto& chain : segs)
        for (const Segment& s : chain)
            if (!time_leads(s, block.axes)) return {};
    for (auto& chain : segs) {
        TimedRates rates;
        align_phases(p, block.axes, chain, rates);
    }
    return write_segment_model(block, p, segs, window, true, mixed, true);
}

Result<void> read_timed_block(std::string_view payload, Profile p, int axes, bool expand, Block& out,
                              BlockCounts& counts, const std::string& where, const WindowView* window,
                              SegmentItems* items) {
    return read_segment_model(payload, p, axes, expand, out, counts, where, window, items, true, false, true);
}

Result<void> read_extended_block(std::string_view payload, Profile p, int axes, bool expand, Block& out,
                                 BlockCounts& counts, const std::string& where, const WindowView* window,
                                 SegmentItems* items) {
    const unsigned subtype = payload.empty() ? 0xFFu : static_cast<unsigned char>(payload[0]);
    if (is_tick_subtype(subtype)) {
        if (items) *items = SegmentItems{};
        return read_tick_block(payload, axes, expand, out, counts, where, window);
    }
    if (subtype != kTimedSubtype)
        return make_error(Errc::corrupt, where + " byte 0: unknown subtype of an extended block");
    return read_timed_block(payload, p, axes, expand, out, counts, where, window, items);
}

}  // namespace stepzip::stz
