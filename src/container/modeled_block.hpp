// Modeled chain blocks (docs/FORMAT.md "Segment-model block", "Step-model
// block"): the chains coded by context models and the adaptive binary range
// coder, instead of zstd. Internal to src/container.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "block_codec.hpp"
#include "../common/bytes.hpp"
#include "window.hpp"

namespace stepzip::stz {

/// Payload of a segment-model block (block type 3) for `block` cut into
/// `segs` under `p` (the same segments as write_chain_payload takes); with
/// `window`, the models start from it (a block flagged kFlagWindow).
/// `timed`: the frame's input format is timed (phases predicted, FORMAT.md).
/// `mixed`: the payload of a block type 6 instead (model byte 0, then the
/// same fields, coded with mixed predictions; docs/FORMAT.md 1.11).
/// `rates`: the payload of a timed block (block type 7, subtype byte 0 first;
/// phases predicted by TimedRates; docs/FORMAT.md "Timed block").
/// `curvature` (type 6 only): with the two curvature models (model byte
/// flag kMixedCurvature, docs/FORMAT.md 1.11.1).
std::string write_segment_model(const Block& block, Profile p,
                                const std::vector<std::vector<Segment>>& segs,
                                const WindowView* window = nullptr, bool timed = false, bool mixed = false,
                                bool rates = false, bool curvature = true);

/// Payload of a step-model block (block type 4); empty when the block is not
/// two-axis (the step model codes Freeman directions only). `order` 1..4
/// fixes the context order; 0 tries every order and keeps the smallest.
/// `chosen`, when not null, receives the order written.
std::string write_step_model(const Block& block, int order = 0, const WindowView* window = nullptr,
                             int* chosen = nullptr);

/// The payload of a block type 6 of the step model (model byte 1, then the
/// step-model fields with context order `order` (0..4), coded with mixed
/// predictions; docs/FORMAT.md 1.11); empty when the block is not two-axis.
/// `curvature`: with the two curvature models (docs/FORMAT.md 1.11.1).
std::string write_mixed_step_model(const Block& block, int order, const WindowView* window = nullptr,
                                   bool curvature = true);

/// The payload of a block type 6 of the context-mixing step model: model
/// byte kMixedStepCmDss (docs/FORMAT.md 1.11.4, what the encoder writes) or
/// kMixedStepCm (1.11.2, its version without the DSS; any other `model`:
/// empty); empty when the block is not two-axis. With `window`, its match
/// model starts from the window's steps.
std::string write_cm_step_model(const Block& block, const WindowView* window = nullptr,
                                unsigned model = kMixedStepCmDss);
/// The same with the light model (docs/FORMAT.md 1.11.3): two hashed
/// models, one weight set, no probability map; about twice as fast, 9-11 %
/// larger on large contours. `model`: kMixedStepCmLightSmall (what the
/// encoder writes: its rows in at most 2 MiB) or kMixedStepCmLight (rows by
/// the block's steps, up to 64 MiB); any other: empty.
std::string write_light_cm_step_model(const Block& block, const WindowView* window = nullptr,
                                      unsigned model = kMixedStepCmLightSmall);

/// Parse a payload of the given kind into `out` (chains and layout, when
/// `expand`) and add its counts to `counts`. Errors: Errc::corrupt,
/// Errc::limit, each naming the payload byte offset after `where`.
/// `window`: the block is flagged kFlagWindow; `items`, when not null,
/// receives the block's segment items (its contribution to the window).
Result<void> read_segment_model(std::string_view payload, Profile p, int axes, bool expand,
                                Block& out, BlockCounts& counts, const std::string& where,
                                const WindowView* window = nullptr, SegmentItems* items = nullptr,
                                bool timed = false, bool mixed = false, bool rates = false);
/// The decoder's step-model history of a frame with a window: the symbols of
/// every block, from the window's start on, and the match table over them.
/// A block flagged `window` decodes on it (O(1) per symbol) instead of
/// rebuilding its window; the result is the same.
struct StepHistory;
struct StepHistoryDeleter {
    void operator()(StepHistory* h) const;
};
using StepHistoryPtr = std::unique_ptr<StepHistory, StepHistoryDeleter>;
StepHistoryPtr make_step_history();
/// Appends a block's contribution (symbols and chain starts).
void step_history_add(StepHistory& h, const WindowBlock& b);
/// Before each block: `window_start` is the frame position of the first
/// symbol of the block's window, `limit` the frame's window.
void step_history_begin_block(StepHistory& h, std::uint64_t window_start, std::uint64_t limit);
/// Frame position after the last symbol.
std::uint64_t step_history_end(const StepHistory& h);

/// `mixed` (both readers): the payload is that of a block type 6 of this
/// model (its model byte first; mixed predictions, docs/FORMAT.md 1.11).
/// `version`: the frame's format version (version 1 step models predict no
/// chain start). `running`: with `window`, the frame's history to decode on
/// (it then holds the block's symbols too) instead of rebuilding the window.
Result<void> read_step_model(std::string_view payload, int axes, bool expand, Block& out,
                             BlockCounts& counts, const std::string& where,
                             const WindowView* window = nullptr, int version = kFormatVersion,
                             StepHistory* running = nullptr, bool mixed = false);

/// The reader of a context-mixing step model's payload (model byte 4, 5 or
/// 6; read_step_model() calls it; the same arguments).
Result<void> read_cm_step_model(std::string_view payload, int axes, bool expand, Block& out, BlockCounts& counts,
                                const std::string& where, const WindowView* window, StepHistory* running);

/// Decoder, both models: when `expand`, `out` becomes an empty block of
/// `axes` axes with `layout`.
void start_output(Block& out, bool expand, int axes, std::string&& layout);
/// Decoder, both models: a chain's start, `ref` + `delta` modulo 2^64 on
/// each axis; false when a coordinate lies beyond the start limit
/// (docs/FORMAT.md section 3).
bool rebuild_start(const Point& ref, const Point& delta, int axes, Point& start);
/// Decoder, both models: the next chain's start delta `d`, decoded by
/// `coder` (reading through `io`), and its start from `ref` into `chain`;
/// an error message, or nullptr.
template <class Coder, class Io>
const char* next_chain_start(Coder& coder, Io& io, const Point& ref, int axes, Chain& chain, Point& d) {
    chain.axes = axes;
    d = coder.start(Point{});
    if (io.failed || io.rc.overrun()) return "bad chain start";
    if (!rebuild_start(ref, d, axes, chain.start)) return "chain start out of range";
    return nullptr;
}

/// Layout field shared by both models: varint decoded size, varint stored
/// size, stored bytes (verbatim when the sizes are equal, else one zstd frame).
void put_layout(std::string& out, std::string_view layout);
/// Reads the layout field at `cur`. Errors: Errc::corrupt, Errc::limit, each
/// naming the payload byte after `where` (a damaged zstd frame: the field's
/// first byte).
Result<std::string> get_layout(Cursor& cur, const std::string& where);

}  // namespace stepzip::stz
