// Timed blocks (docs/FORMAT.md "Timed block"): block type 7, subtype 0. A
// timed frame's segments coded by the segment model with the phase of each
// axis predicted from where it last moved, to a fraction of a tick, and the
// periods before and after (TimedRates) instead of the whole-tick
// prediction of block type 3. Internal to src/container.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "block_codec.hpp"
#include "window.hpp"

namespace stepzip::stz {

/// Subtype 0 of block type 7: the timed block.
inline constexpr unsigned kTimedSubtype = 0;
/// A timed block's second byte: its coding, as block type 3 (adaptive
/// contexts) or as block type 6 (mixed predictions).
inline constexpr unsigned kTimedPlain = 0, kTimedMixed = 1;

/// Payload of a timed block for `block` cut into `segs` under `p`; the
/// phases of `segs` are re-picked first (align_phases with TimedRates), so
/// `segs` ends as the segments written. Empty when the block cannot be one:
/// a profile other than eval8, grbl or marlin, or a segment that time
/// (axis 0) does not lead.
/// `mixed`: coded with mixed predictions (the strong levels).
std::string write_timed_block(const Block& block, Profile p, std::vector<std::vector<Segment>>& segs,
                              const WindowView* window = nullptr, bool mixed = false);

/// Parses a timed-block payload (subtype and coding bytes included) into `out` (when
/// `expand`) and adds its counts to `counts`; `items`, when not null,
/// receives the block's segment items (its contribution to the window).
/// Errors: Errc::corrupt and Errc::limit naming the payload byte after `where`.
Result<void> read_timed_block(std::string_view payload, Profile p, int axes, bool expand, Block& out,
                              BlockCounts& counts, const std::string& where, const WindowView* window = nullptr,
                              SegmentItems* items = nullptr);

/// Parses the payload of an extended block (block type 7) by its subtype
/// (payload byte 0): the timed block (read_timed_block) or the tick block
/// (read_tick_block, timed_tick.hpp; it neither reads the window nor
/// contributes items). Errors: as those, and Errc::corrupt at byte 0 for
/// another subtype.
Result<void> read_extended_block(std::string_view payload, Profile p, int axes, bool expand, Block& out,
                                 BlockCounts& counts, const std::string& where, const WindowView* window = nullptr,
                                 SegmentItems* items = nullptr);

}  // namespace stepzip::stz
