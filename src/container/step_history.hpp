// The step models' history (docs/FORMAT.md 1.6, 1.8): the Freeman symbols
// of a block and its window, the match table over them, the chain starts, and
// the parts both step coders share (the match pointer, chain-start coding).
// Internal to src/container.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <new>
#include <vector>

#include "modeled_block.hpp"
#include "range_coder.hpp"

namespace stepzip::stz {

inline constexpr int kEndSymbol = 8;
// Freeman code -> step on each axis.
inline constexpr std::int64_t kFreemanDx[8] = {1, 1, 0, -1, -1, -1, 0, 1};
inline constexpr std::int64_t kFreemanDy[8] = {0, 1, 1, 1, 0, -1, -1, -1};
inline constexpr std::size_t kMinMatch = 12;  // steps hashed to find a match

inline int step_len_bucket(std::uint64_t len) {
    if (len < 16) return static_cast<int>(len);
    const int b = 16 + bit_length(len) - 5;
    return b < 23 ? b : 23;
}

// The match table: the last kMinMatch symbols (each 0..8, packed base 9 in
// 39 bits) -> the history position that followed them most recently. Open
// addressing, one 64-bit slot per entry (key << 25 | position; a position
// is at least kMinMatch, so 0 marks an empty slot). Positions are below
// 2^25 (window, kMaxBlockSteps + kMaxBlockChains symbols). Same answers as a map.
//
// A key is looked up as (first 11 symbols, last symbol): the home slot is
// the hash of the first 11 times 8 plus the last symbol, so the keys that
// can follow one history (at most 9) share one 64-byte line, which is
// prefetched before the symbol is decoded (prefetch()).
class MatchTable {
public:
    static constexpr int kPosBits = 25;
    MatchTable() { resize(std::size_t{1} << 12); }

    // Stores `pos` under key = base * 9 + last; returns the position stored
    // before (0: none).
    std::uint32_t exchange(std::uint64_t base, unsigned last, std::uint32_t pos) {
        if ((used_ + 1) * 2 > size_) grow();
        const std::uint64_t key = base * 9 + last;
        std::uint64_t& slot = slots_[probe(base, last, key)];
        const std::uint64_t v = slot;
        slot = (key << kPosBits) | pos;
        used_ += v == 0;
        return static_cast<std::uint32_t>(v & ((1u << kPosBits) - 1));
    }
    // The position stored under key = base * 9 + last (0: none); nothing changes.
    std::uint32_t find(std::uint64_t base, unsigned last) const {
        return static_cast<std::uint32_t>(slots_[probe(base, last, base * 9 + last)] & ((1u << kPosBits) - 1));
    }
    // Brings the line of `base`'s keys into the cache.
    void prefetch(std::uint64_t base) const {
        __builtin_prefetch(slots_ + home(base, 0, size_ - 1), 1);
    }

private:
    // The slot holding `key` (= base * 9 + last), else the empty one where it goes.
    std::size_t probe(std::uint64_t base, unsigned last, std::uint64_t key) const {
        const std::size_t mask = size_ - 1;
        std::size_t i = home(base, last, mask);
        while (slots_[i] != 0 && (slots_[i] >> kPosBits) != key) i = (i + 1) & mask;
        return i;
    }
    static std::size_t home(std::uint64_t base, unsigned last, std::size_t mask) {
        return ((static_cast<std::size_t>((base * 0x9E3779B97F4A7C15ull) >> 24) << 3) + last) & mask;
    }
    struct Free {
        void operator()(void* p) const { std::free(p); }
    };
    using Storage = std::unique_ptr<std::uint64_t[], Free>;

    void resize(std::size_t n) {
        // Zeroed by calloc (fresh pages are not written twice); 64-byte
        // aligned, so that a home line is one cache line.
        storage_.reset(static_cast<std::uint64_t*>(std::calloc(n + 8, sizeof(std::uint64_t))));
        if (!storage_) throw std::bad_alloc();
        const auto addr = reinterpret_cast<std::uintptr_t>(storage_.get());
        slots_ = storage_.get() + ((64 - addr % 64) % 64) / sizeof(std::uint64_t);
        size_ = n;
    }
    void grow() {
        Storage old = std::move(storage_);
        const std::uint64_t* from = slots_;
        const std::size_t n = size_;
        resize(n * 2);
        const std::size_t mask = size_ - 1;
        for (std::size_t k = 0; k < n; ++k) {
            const std::uint64_t v = from[k];
            if (v == 0) continue;
            const std::uint64_t key = v >> kPosBits;
            std::size_t i = home(key / 9, static_cast<unsigned>(key % 9), mask);
            while (slots_[i] != 0) i = (i + 1) & mask;
            slots_[i] = v;
        }
    }
    Storage storage_;
    std::uint64_t* slots_ = nullptr;
    std::size_t size_ = 0;
    std::size_t used_ = 0;
};

// A block's history: the window's symbols (at most 2^kMaxWindowLog), then its own.
static_assert((std::uint64_t{1} << kMaxWindowLog) + kMaxBlockSteps + kMaxBlockChains <
              (std::uint64_t{1} << MatchTable::kPosBits));
static_assert(kMinMatch == 12);  // 9^12 < 2^39: key and position share one 64-bit slot

constexpr std::uint64_t pow9(int k) { return k == 0 ? 1 : 9 * pow9(k - 1); }

// The step model's history (docs/FORMAT.md 1.6, 1.8): symbols, the match
// table over them and the recorded chain starts. A coder owns one for a
// block (and its window, rebuilt); the decoder keeps one across the blocks
// of a frame (make_step_history()), so that a block flagged `window` needs
// no rebuild: a table position before the window's start (plus kMinMatch)
// counts as absent, which is what the table rebuilt from the window alone
// answers, since the table keeps the most recent position of each context.
// The encoder's coders, which run several blocks at once, stack their own
// history on the frame's (stack_on()): they copy its symbols, and a context
// their own table has not seen is looked up in the frame's table (only read
// meanwhile), as are the chain starts below `under_size`. The answers are
// again those of the rebuilt window.
struct StepHistory {
    std::vector<std::uint8_t> hist;
    std::uint64_t context = 0;  // last kMinMatch symbols, base 9
    MatchTable table;           // last kMinMatch symbols -> next position
    std::vector<std::uint32_t> start_pos;  // position of each chain's first symbol
    std::vector<Point> start_delta;        // and its start delta
    std::uint64_t base = 0;                // frame position of position 0 (decoder, frame history)
    std::uint32_t min_valid = 1;           // smallest table position a lookup may return
    const StepHistory* under = nullptr;    // stack_on(): the frame's history below this one
    std::uint32_t under_size = 0;          // its positions

    // Positions so far (the next symbol's position).
    std::size_t size() const { return hist.size(); }
    // The first kMinMatch - 1 symbols of the context the next symbol will
    // complete (base 9).
    std::uint64_t next_base() const {
        const std::size_t n = hist.size();
        return n >= kMinMatch ? context - hist[n - kMinMatch] * pow9(kMinMatch - 1) : context;
    }
    // Appends a symbol; returns the position that followed its context most
    // recently (0: none), then records the new one.
    std::uint32_t append(int sym) {
        const std::uint64_t b = next_base();
        hist.push_back(static_cast<std::uint8_t>(sym));
        const std::size_t n = hist.size();
        context = b * 9 + static_cast<unsigned>(sym);
        if (n < kMinMatch) return 0;
        const std::uint32_t before = table.exchange(b, static_cast<unsigned>(sym), static_cast<std::uint32_t>(n));
        return before != 0 || !under ? before : under->table.find(b, static_cast<unsigned>(sym));
    }
    void note_start(const Point& d) {
        start_pos.push_back(static_cast<std::uint32_t>(hist.size()));
        start_delta.push_back(d);
    }
    // The start delta recorded for a chain whose first symbol is at `pos`,
    // or null.
    const Point* start_at(std::uint32_t pos) const {
        const StepHistory& h = pos >= under_size || !under ? *this : *under;
        const auto it = std::lower_bound(h.start_pos.begin(), h.start_pos.end(), pos);
        if (it == h.start_pos.end() || *it != pos) return nullptr;
        return &h.start_delta[static_cast<std::size_t>(it - h.start_pos.begin())];
    }
    // Appends a block's contribution (its symbols, and its chain starts at
    // the chains' first symbols). Each symbol's table line is fetched kAhead
    // symbols before it is stored.
    void add(const WindowBlock& b) {
        const std::vector<std::uint8_t>& all = b.symbols;
        constexpr std::size_t kAhead = 16;
        // `ahead`: the base next_base() will return kAhead symbols later.
        std::uint64_t ahead = next_base();
        const std::size_t n = hist.size();
        auto roll = [&](std::size_t j) {  // symbol j of the block enters `ahead`
            const std::size_t pos = n + j;  // its position in hist
            if (pos >= kMinMatch - 1) {
                const std::size_t out = pos - (kMinMatch - 1);
                ahead -= (out >= n ? all[out - n] : hist[out]) * pow9(kMinMatch - 2);
            }
            ahead = ahead * 9 + all[j];
        };
        for (std::size_t j = 0; j < std::min(kAhead, all.size()); ++j) roll(j);
        std::size_t chain = 0;
        bool at_start = true;
        for (std::size_t i = 0; i < all.size(); ++i) {
            if (i + kAhead < all.size()) {
                table.prefetch(ahead);
                roll(i + kAhead);
            }
            if (at_start && chain < b.starts.size()) note_start(b.starts[chain++]);
            append(all[i]);
            at_start = all[i] == kEndSymbol;
        }
    }
    // Encoder: an empty history becomes one stacked on `frame` (a frame
    // history, only read from now on) for a block whose window starts at
    // frame position `window_start` (a position in `frame`).
    void stack_on(const StepHistory& frame, std::uint64_t window_start) {
        under = &frame;
        under_size = static_cast<std::uint32_t>(frame.hist.size());
        hist = frame.hist;
        base = frame.base;
        context = frame.context;
        min_valid = static_cast<std::uint32_t>(window_start - base) + kMinMatch;
    }
    // Decoder, before each block: positions before `window_start` (a frame
    // position) are outside the window; a dead prefix longer than the window
    // `limit` (at most 2^22) is dropped and the table rebuilt from the window,
    // so that memory stays O(window) and positions below 2^25; the rebuild
    // costs one more append per symbol at most. (Not on a stacked history.)
    void begin_block(std::uint64_t window_start, std::uint64_t limit) {
        const std::uint64_t max_dead = std::min<std::uint64_t>(limit, std::uint64_t{1} << 22);
        if (window_start - base > max_dead) {
            const std::size_t drop = static_cast<std::size_t>(window_start - base);
            WindowBlock kept;
            kept.symbols.assign(hist.begin() + static_cast<std::ptrdiff_t>(drop), hist.end());
            bool at_start = true;
            std::size_t k = std::lower_bound(start_pos.begin(), start_pos.end(), static_cast<std::uint32_t>(drop)) -
                            start_pos.begin();
            for (std::size_t i = 0; i < kept.symbols.size(); ++i) {
                // the starts of the kept chains, in order (a chain cut by the
                // window start has none, as when the window is rebuilt)
                if (at_start && k < start_pos.size() && start_pos[k] == drop + i) kept.starts.push_back(start_delta[k++]);
                else if (at_start) kept.starts.push_back(Point{});
                at_start = kept.symbols[i] == kEndSymbol;
            }
            *this = StepHistory{};
            base = window_start;
            add(kept);
        }
        min_valid = static_cast<std::uint32_t>(window_start - base) + kMinMatch;
    }
};


// The match of a step coder: the history position whose symbol is
// predicted next (-1: none) and how many symbols it has predicted right.
struct StepMatch {
    std::int64_t ptr = -1;
    std::uint64_t len = 0;

    // The predicted symbol, or -1.
    int predicted(const StepHistory& h) const { return ptr >= 0 ? h.hist[static_cast<std::size_t>(ptr)] : -1; }
    // Appends `sym` to the history and follows or finds the match.
    void push(StepHistory& h, int sym) {
        if (ptr >= 0 && h.hist[static_cast<std::size_t>(ptr)] == sym) {
            ++len;
            ++ptr;
        } else {
            len = 0;
            ptr = -1;
        }
        // The most recent earlier position preceded by the same kMinMatch
        // symbols, inside the window.
        const std::uint32_t before = h.append(sym);
        if (before >= h.min_valid && before != 0 && ptr < 0) ptr = before;
    }
};

// A chain's start delta (version 2 of the step model, FORMAT.md 1.8): a hit
// bit when the match points at a recorded chain start (its delta
// predicted), else the delta by `miss(io)`; the start is recorded.
template <class Io, class Miss>
Point code_step_start_with(Io& io, StepHistory& h, const StepMatch& m, Prob (&start_hit)[24], bool predict_starts,
                           const Point& want, Miss&& miss) {
    Point d{};
    bool hit = false;
    if (predict_starts && m.ptr >= 0) {
        // The match predicts a chain start when it points at one.
        if (const Point* pred = h.start_at(static_cast<std::uint32_t>(m.ptr))) {
            hit = io.bit(start_hit[step_len_bucket(m.len)], want == *pred);
            if (hit) d = *pred;
        }
    }
    if (!hit) d = miss(io);
    if (predict_starts) h.note_start(d);
    return d;
}
// The same with each coordinate of a missed delta by `start`.
template <class Io>
Point code_step_start(Io& io, StepHistory& h, const StepMatch& m, UIntModel (&start)[2], Prob (&start_hit)[24],
                      bool predict_starts, const Point& want) {
    return code_step_start_with(io, h, m, start_hit, predict_starts, want, [&](Io& in) {
        Point d{};
        for (int i = 0; i < 2; ++i) d[i] = code_sint(in, start[i], want[i]);  // the rebuilt start is range-checked
        return d;
    });
}

// Where a step coder is in its chain and in the runs of one direction (the
// contexts of the mixed step models, docs/FORMAT.md 1.11 and 1.11.2).
struct StepWalk {
    std::int64_t dx = 0, dy = 0;  // position relative to the chain's start
    std::uint64_t in_chain = 0;   // steps of the chain so far
    int run = 0;                  // steps in the current direction
    std::uint64_t runs = 0;       // finished runs: (length (cap 31) << 3 | turn after it), 8 bits each

    void start_chain() {
        dx = dy = 0;
        in_chain = 0;
    }
    // After a step of Freeman code `sym`, `turn` from the previous one.
    void step(int sym, unsigned turn) {
        dx += kFreemanDx[sym];
        dy += kFreemanDy[sym];
        ++in_chain;
        if (turn == 0) {
            ++run;
        } else {
            runs = (runs << 8) | (static_cast<std::uint64_t>(run < 31 ? run : 31) << 3) | turn;
            run = 1;
        }
    }
    // The way back to the chain's start: (dx, dy) when both are within 15,
    // else their signs and bit lengths.
    std::uint64_t where() const {
        const std::int64_t ax = dx < 0 ? -dx : dx, ay = dy < 0 ? -dy : dy;
        if (ax <= 15 && ay <= 15) return static_cast<std::uint64_t>((dx + 16) * 32 + (dy + 16));
        const auto bl = [](std::int64_t v) { return static_cast<std::uint64_t>(std::min(bit_length(static_cast<std::uint64_t>(v)), 15)); };
        return 2048 + static_cast<std::uint64_t>((dx < 0) * 2 + (dy < 0)) * 256 + bl(ax) * 16 + bl(ay);
    }
};

// A step coder's counts: the block's chains and steps, and the steps coded.
struct StepCounts {
    std::uint64_t nchains = 0, nsteps = 0, seen_steps = 0;
};

// Decoder: the symbols of one chain starting at (x, y), up to its END, each
// from `symbol(io, at_start_point, first, c)`; moves (x, y) and counts the
// steps in c.seen_steps, appending them to `steps` when not null. The range
// decoder runs on a local copy of `io_` (kept in registers). Returns false
// when the stream is overrun.
template <class Io, class Symbol>
[[gnu::always_inline]] inline bool decode_step_chain(Io& io_, StepCounts& c, std::int64_t& x, std::int64_t& y,
                                                     std::vector<Step>* steps, Symbol&& symbol) {
    Io io = io_;
    const std::int64_t sx = x, sy = y;
    bool ok = true;
    for (bool first = true;; first = false) {
        const int sym = symbol(io, x == sx && y == sy, first, c);
        if (io.rc.overrun()) {
            ok = false;
            break;
        }
        if (sym == kEndSymbol) break;
        x += kFreemanDx[sym];
        y += kFreemanDy[sym];
        ++c.seen_steps;
        if (steps) steps->push_back(freeman_to_step(sym));
    }
    io_ = io;
    return ok;
}

// Encoder: every chain of `block` through `coder` (start(delta) from the
// previous chain's end, then next(symbol, at_start_point, first, c) up to
// END); false when a step is not a Freeman code.
template <class Coder>
bool encode_step_chains(Coder& coder, const Block& block, StepCounts& c) {
    Point ref{};
    for (const Chain& chain : block.chains) {
        Point d{};
        for (int a = 0; a < 2; ++a) d[a] = stz::wrap_sub(chain.start[a], ref[a]);
        coder.start(d);
        std::int64_t x = chain.start[0], y = chain.start[1];
        for (std::size_t k = 0;; ++k) {
            const int want = k < chain.steps.size() ? step_to_freeman(chain.steps[k]) : kEndSymbol;
            if (want < 0) return false;
            if (coder.next(want, x == chain.start[0] && y == chain.start[1], k == 0, c) == kEndSymbol) break;
            x += kFreemanDx[want];
            y += kFreemanDy[want];
            ++c.seen_steps;
        }
        ref = Point{};
        ref[0] = x;
        ref[1] = y;
    }
    return true;
}

// Decoder: the chains of a step-model payload whose range-coded stream
// starts at payload byte `base`, through `coder` (start(), decode_chain())
// reading `io`, into `out` when `expand`; adds the counts to `counts`.
// Errors: Errc::corrupt naming the payload byte after `where`.
template <class Coder, class Io>
Result<void> decode_step_chains(Coder& coder, Io& io, StepCounts& c, bool expand, Block& out, BlockCounts& counts,
                                std::size_t base, const std::string& where) {
    auto fail = [&](const std::string& what) {
        return make_error(Errc::corrupt, where + " byte " + std::to_string(base + io.rc.pos()) + ": " + what);
    };
    Point ref{};
    for (std::uint64_t i = 0; i < c.nchains; ++i) {
        Chain chain;
        Point d;
        if (const char* e = next_chain_start(coder, io, ref, 2, chain, d)) return fail(e);
        std::int64_t x = chain.start[0], y = chain.start[1];
        if (!coder.decode_chain(c, x, y, expand ? &chain.steps : nullptr) || io.failed) return fail("bad step");
        ref = Point{};
        ref[0] = x;
        ref[1] = y;
        if (expand) out.chains.push_back(std::move(chain));
    }
    if (c.seen_steps != c.nsteps) return fail("declared step count does not match");
    if (!io.rc.finished()) return fail("range-coded stream does not end at the payload's end");
    counts.chains += c.nchains;
    counts.steps += c.nsteps;
    return {};
}

// The frame history a fresh history `h` can stack on for `window`: the one
// holding the window's first blocks as its last (each block's `history`),
// with room for the rest of the window and a block below 2^25 positions;
// else null (the window is added whole).
inline const StepHistory* stack_base(const WindowView& window, const StepHistory& h) {
    if (window.empty() || !window.front()->history || h.size() != 0 || h.under) return nullptr;
    const StepHistory* frame = window.front()->history;
    std::size_t k = 0;
    while (k < window.size() && window[k]->history == frame) ++k;
    const WindowBlock& last = *window[k - 1];
    if (last.first_symbol + last.symbols.size() != frame->base + frame->size() || window.front()->first_symbol < frame->base)
        return nullptr;
    std::uint64_t more = frame->size() + kMaxBlockSteps + kMaxBlockChains;
    for (std::size_t j = k; j < window.size(); ++j) {
        if (window[j]->history) return nullptr;  // (not a frame history's tail)
        more += window[j]->symbols.size();
    }
    return more < (std::uint64_t{1} << MatchTable::kPosBits) ? frame : nullptr;
}

// What both step coders (step_model.cpp, step_cm.cpp) offer the drivers
// above, over the derived coder's io_, h_ (StepHistory&), m_ (StepMatch) and
// code_symbol(io, want, at_start_point, first, counts) (CRTP).
template <class Derived, class Io>
class StepCoderShell {
public:
    // Starts the block from the window (docs/FORMAT.md "Window"): the
    // window's symbols enter the history and the match table in order; the
    // match and the coder's own state stay as at a block's start.
    // The encoder's coders stack their history on the frame's where the
    // window's first blocks are the frame history's last (compress.cpp) and
    // add only the blocks after them; the answers are the same.
    void prime(const WindowView& window) {
        Derived& d = self();
        std::size_t k = 0;
        if (const StepHistory* frame = stack_base(window, d.h_)) {
            d.h_.stack_on(*frame, window.front()->first_symbol);
            while (k < window.size() && window[k]->history == frame) ++k;
        }
        for (; k < window.size(); ++k) d.h_.add(*window[k]);
        d.m_ = StepMatch{};
    }
    // Codes the next symbol of a chain: a Freeman code 0..7, or kEndSymbol.
    int next(int want, bool at_start_point, bool first, const StepCounts& c) {
        return self().code_symbol(self().io_, want, at_start_point, first, c);
    }
    // Decoder: one chain's symbols (decode_step_chain()).
    bool decode_chain(StepCounts& c, std::int64_t& x, std::int64_t& y, std::vector<Step>* steps)
        requires Io::kDecode
    {
        Derived& d = self();
        return decode_step_chain(d.io_, c, x, y, steps, [&d](Io& io, bool at_start_point, bool first, const StepCounts& n) {
            return d.code_symbol(io, 0, at_start_point, first, n);
        });
    }

private:
    Derived& self() { return static_cast<Derived&>(*this); }
};

}  // namespace stepzip::stz
