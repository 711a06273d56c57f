// stepzip — the timed format: the bytes of a steps log (one byte per tick,
// bit 2i = axis i stepped, bit 2i+1 = axis i direction negative, 4 axes)
// read as one chain in (time, axes): axis 0 is time and moves +1 on every
// tick, idle ticks included; axis i + 1 is the log's axis i. A stretch of
// ticks at a constant step rate is then a digital straight segment with
// time as the leading axis (docs/formats.md).
//
// The layout holds only what the chain does not: the DIR levels of resting
// axes, under the steps format's sticky-DIR convention (a resting axis keeps
// the previous tick's level). Layout: empty (level 0 at the block start, no
// flip), or one byte, the DIR level mask at the block start (0..15), then per
// flip a varint (ticks from the previous flip, or from the block start, to
// the flipping tick) and a byte (the mask of resting axes whose DIR level
// flips on that tick, 1..15). Every byte value is a valid tick, so the
// reader never fails. Complexity: O(1) per tick.
#include <algorithm>

#include "document_internal.hpp"

namespace stepzip::io {
namespace {

constexpr std::uint64_t kMaxGap = std::uint64_t{1} << 40;

/// The chain step of a tick byte: time +1, the stepping axes with their DIR.
Step tick_step(std::uint8_t b) {
    const std::uint8_t stepping = b & kStepBits;
    const auto kept = static_cast<std::uint8_t>(b & (stepping | (stepping << 1)));
    return static_cast<Step>(1u | (static_cast<unsigned>(kept) << 2));
}

class TimedParser final : public FormatParser {
public:
    TimedParser(std::string source, std::size_t block_steps)
        : source_(std::move(source)), block_steps_(block_steps) {
        blk_.chains.emplace_back();
        start_layout();
    }

    Result<void> feed(std::string_view data, bool last) override;

private:
    void start_layout() {
        layout_.clear();
        if (level_ != 0) layout_.push_back(static_cast<char>(dir_to_mask(level_)));
        since_ = 0;
    }
    int axes() const {
        return log_axes(seen_) + 1;  // time, then the log's axes
    }
    void finish(bool open) {
        Block b = std::move(blk_);
        b.axes = axes();
        for (Chain& c : b.chains) c.axes = b.axes;
        b.open = open;
        b.layout = std::move(layout_);
        Point end{};
        if (open) end = b.chains.back().end();
        ready.push_back(std::move(b));
        blk_ = Block{};
        blk_.continues = open;
        Chain c;
        c.start = end;
        blk_.chains.push_back(std::move(c));
        start_layout();
    }

    std::string source_;
    std::size_t block_steps_;
    std::uint8_t level_ = 0;  // DIR bits of the previous tick
    std::uint8_t seen_ = 0;   // STEP bits seen anywhere so far
    std::uint64_t since_ = 0; // ticks since the previous flip or the block start
    Block blk_;
    std::string layout_;
    bool finished_ = false;
};

Result<void> TimedParser::feed(std::string_view data, bool last) {
    if (finished_) return make_error(Errc::invalid_argument, source_ + ": input fed after its end");
    std::vector<Step>* steps = &blk_.chains.back().steps;
    for (const char ch : data) {
        const auto b = static_cast<std::uint8_t>(ch);
        if (steps->size() >= block_steps_) {
            finish(true);
            steps = &blk_.chains.back().steps;
        }
        if (steps->capacity() == 0) steps->reserve(std::min<std::size_t>(block_steps_, data.size()));
        const auto [stepping, moving_dirs, dirs, flip] = read_tick(b, level_);
        if (flip != 0) {
            if (layout_.empty()) layout_.push_back(0);
            put_varint(layout_, since_);
            layout_.push_back(static_cast<char>(dir_to_mask(flip)));
            since_ = 0;
        }
        steps->push_back(tick_step(b));
        ++since_;
        seen_ |= stepping;
        level_ = dirs;
    }
    if (last) {
        finished_ = true;
        finish(false);
    }
    return {};
}

// ---- writer ----------------------------------------------------------------------

class TimedRenderer final : public FormatRenderer {
public:
    Result<void> write(const Block& block, std::string& out) override;
};

Result<void> TimedRenderer::write(const Block& b, std::string& out) {
    auto got = log_block_steps(b, "timed");
    if (!got) return std::move(got).error();
    const std::vector<Step>& steps = **got;
    for (const Step s : steps)
        if ((s & 3u) != 1u || !step_valid(s, 5)) return corrupt("timed", "a step that is not one tick");
    LayoutCursor lc(b.layout);
    std::uint8_t level = 0;
    if (!lc.done()) {
        std::uint8_t m = 0;
        lc.u8(m);
        if (m > 15) return corrupt("timed", "a bad DIR level");
        level = mask_to_dir(m);
    }
    std::uint64_t next_flip = 0;  // tick index of the next flip
    std::uint8_t flip = 0;
    auto read_flip = [&](std::uint64_t from) -> bool {
        flip = 0;
        if (lc.done()) return true;
        std::uint64_t gap = 0;
        std::uint8_t m = 0;
        if (!lc.varint(gap) || gap > kMaxGap || !lc.u8(m) || m == 0 || m > 15) return false;
        if (from != 0 && gap == 0) return false;
        next_flip = from + gap;
        flip = mask_to_dir(m);
        return true;
    };
    if (!read_flip(0)) return corrupt("timed", "a bad flip");
    out.reserve(out.size() + steps.size());
    for (std::uint64_t k = 0; k < steps.size(); ++k) {
        const auto s = static_cast<std::uint8_t>(steps[k] >> 2);
        const auto moving_dirs = static_cast<std::uint8_t>((s & kStepBits) << 1);
        std::uint8_t f = 0;
        if (flip != 0 && next_flip == k) {
            f = flip;
            if (f & moving_dirs) return corrupt("timed", "a flip on a stepping axis");
            if (!read_flip(k)) return corrupt("timed", "a bad flip");
        }
        const std::uint8_t byte = tick_byte(s, level, f);
        out.push_back(static_cast<char>(byte));
        level = byte & kDirBits;
    }
    if (flip != 0) return corrupt("timed", "a flip after the last tick");
    return {};
}

}  // namespace

std::unique_ptr<FormatParser> make_timed_parser(std::string source, std::size_t block_steps) {
    return std::make_unique<TimedParser>(std::move(source), block_steps);
}

std::unique_ptr<FormatRenderer> make_timed_renderer() { return std::make_unique<TimedRenderer>(); }

}  // namespace stepzip::io
