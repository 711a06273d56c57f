// Table blocks (block type 5, docs/FORMAT.md "Table block"): the segment
// items of a block (chain starts, segments, chain ends) coded as operations
// (known shape by successor or recent rank, shape in full, match over
// earlier items) whose fields are entropy-coded with per-block static
// tables (rANS) and raw extra bits. The fast levels' encoding: a few table
// look-ups per field where the segment model (type 3) decides tens of
// adaptive bits per segment. Internal to src/container.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "block_codec.hpp"
#include "window.hpp"

namespace stepzip::stz {

/// Block type 7 subtype of a table block whose minor totals are coded as
/// they are, not as residuals of the previous segment's slope
/// (docs/FORMAT.md 1.10.2): payload byte 0 the subtype, byte 1 its flags.
inline constexpr unsigned kTableSubtype = 4;
/// Its flags byte: bit 0, the minor totals unpredicted (the only flag).
inline constexpr unsigned kTableRawMinors = 1;

/// How the table encoder codes minor totals (not part of the format).
enum class MinorCoding {
    predicted,  ///< residuals of the previous slope: block type 5
    raw,        ///< the totals themselves: block type 7, subtype kTableSubtype
    smaller,    ///< whichever of the two the block's symbol counts say is smaller
};

/// Encoder effort of a table block (not part of the format).
struct TableEffort {
    int recent_search = 64;   ///< recent-list entries searched for a known shape (at most 1024)
    int min_match = 4;        ///< shortest match taken at a new offset, in items
    int min_rep_match = 2;    ///< shortest match taken at a repeat offset
    MinorCoding minors = MinorCoding::predicted;
};

/// Payload of a table block for `block` cut into `segs` under `p` (the
/// segments write_chain_payload takes); with `window`, matches may copy
/// the window's items (a block flagged kFlagWindow). `own`: the keys of
/// `segs`' items from an earlier coding (`made` of it, or window_keys() of
/// the block's contribution), used instead of computing them; `made`, when
/// not null and `own` is not used: receives them. `type`, when not null:
/// the payload's block type, kTable, or kExtended when it codes the minor
/// totals unpredicted (its first bytes are then kTableSubtype and the flags).
std::string write_table_block(const Block& block, Profile p, const std::vector<std::vector<Segment>>& segs,
                              const TableEffort& effort = {}, const WindowView* window = nullptr,
                              const TableItemKeys* own = nullptr, TableItemKeys* made = nullptr,
                              unsigned* type = nullptr);

/// The table coder's keys of `b`'s items under `p` and `axes` (the frame's),
/// and their match hashes, made on the first call and kept with `b` for the
/// later table blocks whose window holds it: the keys taken from `made` when
/// it holds as many (the keys a write_table_block of the same items filled),
/// else computed. Thread-safe.
const TableItemKeys& window_keys(const WindowBlock& b, Profile p, int axes, TableItemKeys* made = nullptr);

/// Parses a table-block payload into `out` (chains and layout, when
/// `expand`) and adds its counts to `counts`. Errors: Errc::corrupt and
/// Errc::limit, each naming the payload byte offset after `where`.
/// `window`: the block is flagged kFlagWindow; `items`, when not null,
/// receives the block's segment items (its contribution to the window).
/// `type`: the block's type, kTable or kExtended (a payload that begins with
/// kTableSubtype and its flags byte).
Result<void> read_table_block(std::string_view payload, Profile p, int axes, bool expand, Block& out,
                              BlockCounts& counts, const std::string& where, const WindowView* window = nullptr,
                              SegmentItems* items = nullptr, unsigned type = kTable);

}  // namespace stepzip::stz
