// stepzip — the steps format: a binary STEP/DIR log, one byte per tick,
// bit 2i = axis i stepped, bit 2i+1 = axis i direction negative (4 axes).
// The whole file is one chain starting at the origin. Reader and writer; the
// layout byte code is described in docs/formats.md.
//
// Every byte value is a valid tick, so the reader never fails. What is not a
// step goes into the layout under a "sticky DIR" convention: a resting axis
// is expected to keep the DIR level of the previous tick, so only DIR changes
// on resting axes (exceptions) and idle ticks (no axis stepping) cost layout
// bytes. A log whose resting axes drop their DIR bit instead (software that
// writes each tick's step alone) has a flip after nearly every negative step
// of a minor axis; a block where that convention, "DIR 0 at rest", has fewer
// exceptions is read again under it (its layout starts with kZeroDir).
// Complexity: O(1) per tick.
#include <algorithm>

#include "document_internal.hpp"

namespace stepzip::io {
namespace {

// Layout operation byte: kind in bits 6-7, argument in bits 0-5.
enum : std::uint8_t {
    kSteps = 0x00,  // n step ticks following the convention
    kIdle = 0x40,   // n idle ticks at the current DIR level
    kFlip = 0x80,   // bits 0-3: DIR bits of resting axes that flip on the next tick
    kLevel = 0xC0,  // bits 0-3: DIR level at the start of the block (first op only)
    kPaced = 0xD0,  // varint g, varint n: n times (one step tick, then g idle ticks)
    kZeroDir = 0xD1,  // first op only: resting axes' DIR is 0 on every tick, not sticky
    kGaps = 0xD2,     // varint n, n varints g - 1: n times (one step tick, then g idle ticks)
};
// Repeated (1 step, g idle) pairs shorter than this go into a gap list
// (kGaps), where a general-purpose compressor sees the gaps side by side;
// longer ones stay kPaced.
constexpr std::uint64_t kPacedMin = 64;
// Steps of a block read under sticky DIR before it picks its convention
// (a smaller block picks at its end): only these are read twice when DIR 0
// at rest wins.
constexpr std::size_t kDecideSteps = 4096;
// Counts: argument 0..62 means 1..63; 63 means 64 + a varint that follows.
constexpr std::uint64_t kMaxRun = std::uint64_t{1} << 32;


void put_count(std::string& out, std::uint8_t kind, std::uint64_t n) {
    if (n <= 63) {
        out.push_back(static_cast<char>(kind | (n - 1)));
    } else {
        out.push_back(static_cast<char>(kind | 63));
        put_varint(out, n - 64);
    }
}

class StepsParser final : public FormatParser {
public:
    StepsParser(std::string source, std::size_t block_steps, bool zero_dir = false)
        : source_(std::move(source)), block_steps_(block_steps), cap_(layout_cap(block_steps)), zero_(zero_dir),
          decided_(zero_dir) {
        blk_.chains.emplace_back();
        if (zero_) layout_.push_back(static_cast<char>(kZeroDir));
    }

    Result<void> feed(std::string_view data, bool last) override;

private:
    // Runs go through a small stage that folds (1 step, g idle) pairs, the
    // shape of a log sampled at a fixed tick rate, into kPaced (a long run
    // of one g) or a gap list (kGaps, the gaps of consecutive pairs).
    void flush_run() {
        if (run_n_ == 0) return;
        const std::uint64_t n = run_n_;
        run_n_ = 0;
        if (run_kind_ == kSteps) {
            release_held();
            if (n == 1) {
                held_ = true;
                return;
            }
            flush_pace();
            put_count(out(), kSteps, n);
            return;
        }
        if (held_) {
            held_ = false;
            if (pace_n_ != 0 && pace_g_ == n && pace_n_ < kMaxRun) {
                ++pace_n_;
                return;
            }
            flush_pace();
            pace_g_ = n;
            pace_n_ = 1;
            return;
        }
        flush_pace();
        put_count(out(), kIdle, n);
    }
    // A run of n pairs of one gap g: one pair as its two runs, a pace.
    void put_pace(std::uint64_t g, std::uint64_t n) {
        if (n == 1) {
            put_count(layout_, kSteps, 1);
            put_count(layout_, kIdle, g);
        } else {
            layout_.push_back(static_cast<char>(kPaced));
            put_varint(layout_, g);
            put_varint(layout_, n);
        }
    }
    void flush_pace() {
        if (pace_n_ == 0) return;
        if (pace_n_ >= kPacedMin || gap_n_ + pace_n_ > kMaxRun) {
            flush_gaps();
            put_pace(pace_g_, pace_n_);
        } else {
            if (gap_n_ == 0) {
                gap_g_ = pace_g_;
                gap_same_ = true;
            } else if (pace_g_ != gap_g_) {
                gap_same_ = false;
            }
            for (std::uint64_t k = 0; k < pace_n_; ++k) put_varint(gaps_, pace_g_ - 1);
            gap_n_ += pace_n_;
        }
        pace_n_ = 0;
    }
    /// The layout, after the pending gap list.
    std::string& out() {
        flush_gaps();
        return layout_;
    }
    void flush_gaps() {
        if (gap_n_ == 0) return;
        if (gap_same_) {
            put_pace(gap_g_, gap_n_);
        } else {
            layout_.push_back(static_cast<char>(kGaps));
            put_varint(layout_, gap_n_);
            layout_ += gaps_;
        }
        gaps_.clear();
        gap_n_ = 0;
    }
    void release_held() {
        if (!held_) return;
        held_ = false;
        flush_pace();
        put_count(out(), kSteps, 1);
    }
    /// Everything pending into the layout.
    void flush_all() {
        flush_run();
        release_held();
        flush_pace();
        flush_gaps();
    }
    std::size_t layout_size() const { return layout_.size() + gaps_.size(); }
    void run(std::uint8_t kind) {
        if (run_n_ != 0 && (run_kind_ != kind || run_n_ == kMaxRun)) flush_run();
        run_kind_ = kind;
        ++run_n_;
    }
    // The current block, with its layout and axes (flushes the pending runs).
    Block take_block(bool open);
    void cut(bool open);
    int axes() const {
        return log_axes(seen_);
    }

    std::string source_;
    std::size_t block_steps_;
    std::size_t cap_;
    // The layout of `b` (the block so far) read again under "DIR 0 at rest".
    std::string zero_dir_layout(const Block& b) const;
    // After kDecideSteps steps: DIR 0 at rest from here on when it has had
    // fewer exceptions than sticky DIR (zero_ticks_ against flips_); the
    // layout so far is read again under it.
    void decide();

    bool zero_ = false;            // "DIR 0 at rest": the level is 0 before every tick
    bool decided_ = false;         // the block's convention is fixed
    std::uint8_t last_dirs_ = 0;   // DIR bits of the previous tick (level_ unless zero_)
    std::uint64_t flips_ = 0;      // sticky flips in the block
    std::uint64_t zero_ticks_ = 0; // ticks of the block with a DIR bit on a resting axis
    std::uint8_t level_ = 0;  // DIR bits of the previous tick
    std::uint8_t seen_ = 0;   // STEP bits seen anywhere so far
    Block blk_;
    std::size_t blk_steps_ = 0;
    std::string layout_;
    std::uint8_t run_kind_ = kSteps;
    std::uint64_t run_n_ = 0;
    bool held_ = false;            // a run of one step waits for its idle run
    std::uint64_t pace_g_ = 0;     // pending kPaced: idle ticks per pair
    std::uint64_t pace_n_ = 0;     // pending kPaced: pairs
    std::string gaps_;             // pending gap list: varint g - 1 per pair
    std::uint64_t gap_n_ = 0;      // its pairs
    std::uint64_t gap_g_ = 0;      // the gap of its pairs while they all have one
    bool gap_same_ = true;
    bool finished_ = false;
};

Block StepsParser::take_block(bool open) {
    flush_all();
    Block b = std::move(blk_);
    b.axes = axes();
    for (Chain& c : b.chains) c.axes = b.axes;
    b.open = open;
    b.layout = std::move(layout_);
    layout_.clear();
    if (!decided_ && zero_ticks_ < flips_) {
        std::string z = zero_dir_layout(b);
        if (!z.empty()) b.layout = std::move(z);
    }
    flips_ = 0;
    zero_ticks_ = 0;
    zero_ = decided_ = false;
    level_ = last_dirs_;
    return b;
}

std::string StepsParser::zero_dir_layout(const Block& b) const {
    // The ticks, rendered from the sticky layout, read again.
    std::string ticks;
    if (!make_steps_renderer()->write(b, ticks)) return {};
    StepsParser again(source_, SIZE_MAX, true);
    if (!again.feed(ticks, true) || again.ready.size() != 1) return {};
    return std::move(again.ready.front().layout);
}

void StepsParser::decide() {
    decided_ = true;
    if (zero_ticks_ >= flips_) return;
    flush_all();
    Block so_far;
    so_far.axes = axes();
    so_far.continues = blk_.continues;
    so_far.chains = blk_.chains;
    for (Chain& c : so_far.chains) c.axes = so_far.axes;
    so_far.layout = layout_;
    std::string z = zero_dir_layout(so_far);
    if (z.empty()) return;
    layout_ = std::move(z);
    zero_ = true;
    level_ = 0;
}

void StepsParser::cut(bool open) {
    Block b = take_block(open);
    Point end{};
    if (open) end = b.chains.back().end();
    ready.push_back(std::move(b));
    blk_ = Block{};
    blk_.continues = open;
    Chain c;
    c.start = end;
    blk_.chains.push_back(std::move(c));
    blk_steps_ = 0;
    if (level_ != 0) layout_.push_back(static_cast<char>(kLevel | dir_to_mask(level_)));
}

Result<void> StepsParser::feed(std::string_view data, bool last) {
    if (finished_) return make_error(Errc::invalid_argument, source_ + ": input fed after its end");
    std::vector<Step>* steps = &blk_.chains.back().steps;
    if (steps->capacity() == 0) steps->reserve(std::min<std::size_t>(block_steps_, data.size()));
    const auto* in = reinterpret_cast<const std::uint8_t*>(data.data());
    const std::size_t size = data.size();
    for (std::size_t i = 0; i < size; ++i) {
        if (!decided_ && blk_steps_ >= kDecideSteps) decide();
        const std::uint8_t b = in[i];
        Tick tick = read_tick(b, level_);
        if ((tick.stepping != 0 && blk_steps_ >= block_steps_) || layout_size() >= cap_) {
            cut(true);
            steps = &blk_.chains.back().steps;
            steps->reserve(std::min<std::size_t>(block_steps_, data.size()));
            // The new block starts sticky from the last tick's DIR levels:
            // the tick is read again against them (the old block may have
            // been read under DIR 0 at rest).
            tick = read_tick(b, level_);
        }
        const auto [stepping, moving_dirs, dirs, flip] = tick;
        if (flip != 0) {
            flush_all();
            layout_.push_back(static_cast<char>(kFlip | dir_to_mask(flip)));
            ++flips_;
        }
        zero_ticks_ += (dirs & ~moving_dirs) != 0;
        if (stepping != 0) {
            run(kSteps);
            steps->push_back(static_cast<Step>(b & (stepping | moving_dirs)));
            ++blk_steps_;
            seen_ |= stepping;
        } else {
            run(kIdle);
        }
        level_ = zero_ ? 0 : dirs;
        last_dirs_ = dirs;
        if (stepping == 0 || layout_size() >= cap_) continue;
        // The step ticks that follow without a DIR change on a resting axis
        // (the common case) in one pass: the same run, no layout byte, no
        // cut before the block is full; measured first, then written at once.
        std::size_t e = i + 1;
        // (Undecided, it stops at kDecideSteps: the choice is made there
        // whatever the feeding.)
        const std::size_t full = decided_ ? block_steps_ : std::min(block_steps_, kDecideSteps);
        const std::size_t room = std::min<std::uint64_t>(full - std::min(blk_steps_, full), kMaxRun - run_n_);
        const std::size_t lim = i + 1 + std::min(size - i - 1, room);
        std::uint8_t lvl = level_, seen = 0;
        const std::uint8_t keep = zero_ ? 0 : kDirBits;
        std::uint64_t rest_dirs = 0;
        while (e < lim) {
            const std::uint8_t c = in[e];
            const auto st = static_cast<std::uint8_t>(c & kStepBits);
            const auto resting = static_cast<std::uint8_t>(~(st << 1) & kDirBits);
            const auto flips = static_cast<std::uint8_t>(((c & kDirBits) ^ lvl) & resting);
            if (st == 0 || flips != 0) break;
            rest_dirs += (c & resting) != 0;
            lvl = c & keep;
            seen |= st;
            ++e;
        }
        zero_ticks_ += rest_dirs;
        const std::size_t k = e - i - 1;
        if (k == 0) continue;
        const std::size_t base = steps->size();
        steps->resize(base + k);
        Step* o = steps->data() + base;
        for (std::size_t j = 0; j < k; ++j) {
            const std::uint8_t c = in[i + 1 + j];
            o[j] = static_cast<Step>(c & ((c & kStepBits) * 3u));
        }
        blk_steps_ += k;
        run_n_ += k;
        seen_ |= seen;
        level_ = lvl;
        last_dirs_ = in[e - 1] & kDirBits;
        i = e - 1;
    }
    if (last) {
        finished_ = true;
        ready.push_back(take_block(false));
    }
    return {};
}

// ---- writer ----------------------------------------------------------------------

class StepsRenderer final : public FormatRenderer {
public:
    Result<void> write(const Block& block, std::string& out) override;
};

Result<void> StepsRenderer::write(const Block& b, std::string& out) {
    auto got = log_block_steps(b, "steps");
    if (!got) return std::move(got).error();
    const std::vector<Step>& steps = **got;
    for (const Step s : steps)
        if (!step_valid(s, 4)) return corrupt("steps", "a step outside four axes");
    std::uint8_t level = 0;
    std::uint8_t flip = 0;
    std::uint8_t keep = kDirBits;  // 0 under kZeroDir: no level carries to the next tick
    std::size_t k = 0;
    auto emit_steps = [&](std::uint64_t n) {
        for (std::uint64_t j = 0; j < n; ++j) {
            const auto s = static_cast<std::uint8_t>(steps[k++]);
            if (flip & ((s & kStepBits) << 1)) return false;
            const std::uint8_t byte = tick_byte(s, level, flip);
            out.push_back(static_cast<char>(byte));
            level = byte & keep;
            flip = 0;
        }
        return true;
    };
    if (b.layout.empty()) {
        out.reserve(out.size() + steps.size());
        emit_steps(steps.size());
        return {};
    }
    out.reserve(out.size() + steps.size());
    LayoutCursor lc(b.layout);
    bool first = true;
    while (!lc.done()) {
        std::uint8_t op = 0;
        lc.u8(op);
        const std::uint8_t kind = op & 0xC0;
        const std::uint8_t arg = op & 0x3F;
        if (op == kZeroDir) {
            if (!first) return corrupt("steps", "DIR 0 at rest after the first operation");
            first = false;
            keep = 0;
            continue;
        }
        if (op == kGaps) {
            first = false;
            std::uint64_t n = 0;
            if (!lc.varint(n) || n < 2 || n > kMaxRun) return corrupt("steps", "a bad gap list");
            if (n > steps.size() - k) return corrupt("steps", "a run past the block's steps");
            for (std::uint64_t j = 0; j < n; ++j) {
                std::uint64_t g1 = 0;
                if (!lc.varint(g1) || g1 >= kMaxRun) return corrupt("steps", "a bad gap list");
                if (!emit_steps(1)) return corrupt("steps", "a flip on a stepping axis");
                out.append(static_cast<std::size_t>(g1 + 1), static_cast<char>(level));
            }
            continue;
        }
        if (op == kPaced) {
            first = false;
            std::uint64_t g = 0, n = 0;
            if (!lc.varint(g) || !lc.varint(n) || g == 0 || g > kMaxRun || n < 2 || n > kMaxRun)
                return corrupt("steps", "a bad paced run");
            if (n > steps.size() - k) return corrupt("steps", "a run past the block's steps");
            for (std::uint64_t j = 0; j < n; ++j) {
                if (!emit_steps(1)) return corrupt("steps", "a flip on a stepping axis");
                out.append(static_cast<std::size_t>(g), static_cast<char>(level));
            }
            continue;
        }
        if (kind == kFlip || kind == kLevel) {
            if (arg == 0 || arg > 15) return corrupt("steps", "a bad DIR mask");
            if (kind == kLevel) {
                if (!first) return corrupt("steps", "a DIR level after the first operation");
                level = mask_to_dir(arg);
            } else {
                if (flip != 0) return corrupt("steps", "two flips for one tick");
                flip = mask_to_dir(arg);
            }
            first = false;
            continue;
        }
        first = false;
        std::uint64_t n = arg + 1u;
        if (arg == 63) {
            std::uint64_t extra = 0;
            if (!lc.varint(extra) || extra > kMaxRun) return corrupt("steps", "a bad run length");
            n = 64 + extra;
        }
        if (kind == kSteps) {
            if (n > steps.size() - k) return corrupt("steps", "a run past the block's steps");
            if (!emit_steps(n)) return corrupt("steps", "a flip on a stepping axis");
        } else {
            out.push_back(static_cast<char>(level ^ flip));
            level = (level ^ flip) & keep;
            flip = 0;
            out.append(static_cast<std::size_t>(n - 1), static_cast<char>(level));
        }
    }
    if (k != steps.size()) return corrupt("steps", "steps left over after the layout");
    if (flip != 0) return corrupt("steps", "a flip after the last tick");
    return {};
}

}  // namespace

std::unique_ptr<FormatParser> make_steps_parser(std::string source, std::size_t block_steps) {
    return std::make_unique<StepsParser>(std::move(source), block_steps);
}

std::unique_ptr<FormatRenderer> make_steps_renderer() { return std::make_unique<StepsRenderer>(); }

}  // namespace stepzip::io
