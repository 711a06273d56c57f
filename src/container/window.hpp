// The window across blocks (docs/FORMAT.md "Window"): what the earlier blocks
// of a frame add to the models of a later block. A block's contribution is a
// function of its decoded content and its type only, so the encoder's jobs
// and the decoder rebuild the same state. Internal to src/container.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <vector>

#include "stepzip/container.hpp"
#include "stepzip/document.hpp"
#include "stepzip/segment.hpp"

namespace stepzip::stz {

struct StepHistory;  // step_history.hpp

/// The items a segment-model block adds: per chain its start delta (from the
/// previous chain's end, the first from the origin) and its segments.
struct SegmentItems {
    std::vector<Point> starts;
    std::vector<std::uint32_t> counts;  ///< segments of each chain
    std::vector<Segment> segments;
    /// The block holds arc items (table blocks, docs/FORMAT.md 1.10.1): its
    /// items enter the windows of table blocks only.
    bool arcs = false;
};

/// The table coder's form of a block's segment items (table_block.cpp):
/// per history entry (start, segments, end of each chain) its match key,
/// and the segments in canonical form.
struct TableItemKeys {
    /// The segments in canonical form; empty when `canon_is_items`.
    std::vector<Segment> canon;
    /// Every segment of the items is canonical already: the canonical forms
    /// are the items' own segments (no copy kept).
    bool canon_is_items = false;
    std::vector<std::uint64_t> keys;
    /// A window block's: per entry but the last two, the hash of its key
    /// and the next two (the match finder's, before its shift).
    std::vector<std::uint64_t> hashes;
};

/// One earlier block as the window holds it.
struct WindowBlock {
    std::uint64_t weight = 0;           ///< steps + chains
    SegmentItems items;                 ///< segment-model blocks; else empty
    /// Decoder: a table block's decoded chains, one per chain of `items`
    /// (a later table block's match that copies a whole chain copies its
    /// steps); else empty.
    std::vector<Chain> chains;
    std::vector<std::uint8_t> symbols;  ///< two-axis chain blocks: Freeman codes, 8 after each chain
    std::vector<Point> starts;          ///< with `symbols`: each chain's start delta
    /// Timed frames' chain blocks: each step's mask of the axes besides
    /// time (tick_masks(); the tick block's match, docs/FORMAT.md 1.8).
    std::vector<std::uint8_t> ticks;
    /// Encoder: `ticks` were made before the first pass and dropped after
    /// it (the block became a raw one): the first pass of a later block read
    /// them (compress.cpp).
    bool ticks_dropped = false;
    std::uint64_t first_symbol = 0;     ///< frame position of its first symbol (the frame history's)
    /// Encoder: the frame history that holds its symbols (compress.cpp), or null.
    const StepHistory* history = nullptr;
    unsigned first_type = 0;            ///< encoder: the block type its first pass chose
    /// Encoder: `items` as the table coder keys them, made by the first
    /// table block that reads this block from its window (under the frame's
    /// profile and axes) and kept for the later ones.
    mutable std::once_flag table_keys_once;
    mutable TableItemKeys table_keys;
};

/// The blocks inside the window, oldest first.
using WindowView = std::vector<std::shared_ptr<const WindowBlock>>;

/// The blocks a frame's next block sees: the longest run of at most
/// kMaxWindowBlocks immediately preceding blocks whose weights add up to at
/// most the window.
class Window {
public:
    explicit Window(std::uint64_t limit = 0) : limit_(limit) {}
    std::uint64_t limit() const { return limit_; }
    WindowView view() const { return WindowView(blocks_.begin(), blocks_.end()); }
    void push(std::shared_ptr<const WindowBlock> b) {
        if (limit_ == 0) return;
        weight_ += b->weight;
        blocks_.push_back(std::move(b));
        while (!blocks_.empty() && (weight_ > limit_ || blocks_.size() > kMaxWindowBlocks)) {
            weight_ -= blocks_.front()->weight;
            blocks_.pop_front();
        }
    }

private:
    std::uint64_t limit_;
    std::uint64_t weight_ = 0;
    std::deque<std::shared_ptr<const WindowBlock>> blocks_;
};

/// Freeman codes of a two-axis block's chains, 8 after each chain; empty
/// when the block is not two-axis or holds a step that is no Freeman code.
std::vector<std::uint8_t> step_symbols(const Block& block);

/// Per step of `block`, chain after chain, its step mask: bit a - 1 set
/// when axis a >= 1 moves (what a timed frame's chain block adds to the
/// window for the tick block's match, docs/FORMAT.md 1.8 "Ticks").
std::vector<std::uint8_t> tick_masks(const Block& block);

/// Each chain's start delta: from the previous chain's end (the first from
/// the origin), as the models code it.
std::vector<Point> start_deltas(const Block& block);

/// The step-model contribution of a chain block: its symbols and starts.
void add_steps(WindowBlock& w, const Block& block);

/// add_steps() of a block whose chains may be with its contribution (a
/// table block's, kept in `w.chains` for whole-chain copies; `block` has
/// none then): they are lent to `block` for it, and given back.
void add_steps_lent(WindowBlock& w, Block& block);

/// The segment items of `block` cut into `segs`.
SegmentItems segment_items(const Block& block, const std::vector<std::vector<Segment>>& segs);

}  // namespace stepzip::stz
