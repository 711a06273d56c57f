// Modeled chain blocks (docs/FORMAT.md "Segment-model block", "Step-model
// block"): the chains coded by context models and the adaptive binary range
// coder, instead of zstd. Internal to src/container.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "block_codec.hpp"
#include "bytes.hpp"
#include "window.hpp"

namespace stepzip::stz {

/// Payload of a segment-model block (block type 3) for `block` cut into
/// `segs` under `p` (the same segments as write_chain_payload takes); with
/// `window`, the models start from it (a block flagged kFlagWindow).
/// `timed`: the frame's input format is timed (phases predicted, FORMAT.md).
std::string write_segment_model(const Block& block, Profile p,
                                const std::vector<std::vector<Segment>>& segs,
                                const WindowView* window = nullptr, bool timed = false);

/// Payload of a step-model block (block type 4); empty when the block is not
/// two-axis (the step model codes Freeman directions only). `order` 1..4
/// fixes the context order; 0 tries every order and keeps the smallest.
/// `chosen`, when not null, receives the order written.
std::string write_step_model(const Block& block, int order = 0, const WindowView* window = nullptr,
                             int* chosen = nullptr);

/// Parse a payload of the given kind into `out` (chains and layout, when
/// `expand`) and add its counts to `counts`. Errors: Errc::corrupt,
/// Errc::limit, each naming the payload byte offset after `where`.
/// `window`: the block is flagged kFlagWindow; `items`, when not null,
/// receives the block's segment items (its contribution to the window).
Result<void> read_segment_model(std::string_view payload, Profile p, int axes, bool expand,
                                Block& out, BlockCounts& counts, const std::string& where,
                                const WindowView* window = nullptr, SegmentItems* items = nullptr,
                                bool timed = false);
/// `version`: the frame's format version (version 1 step models predict no
/// chain start).
Result<void> read_step_model(std::string_view payload, int axes, bool expand, Block& out,
                             BlockCounts& counts, const std::string& where,
                             const WindowView* window = nullptr, int version = kFormatVersion);

/// Layout field shared by both models: varint decoded size, varint stored
/// size, stored bytes (verbatim when the sizes are equal, else one zstd frame).
void put_layout(std::string& out, std::string_view layout);
/// Reads the layout field at `cur`. Errors: Errc::corrupt, Errc::limit.
Result<std::string> get_layout(Cursor& cur, const std::string& where);

}  // namespace stepzip::stz
