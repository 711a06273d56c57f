// Step-model blocks (docs/FORMAT.md "Step model"): two-axis chains coded
// step by step, each Freeman direction as the turn from the previous one in
// the context of the three previous turns, with a match model over the
// block's earlier steps (repeated contours anywhere before). Wins over
// segments where segments are short (noisy contours, random walks).
// One template (StepCoder<Io>) runs both directions.
// Complexity: 4-5 range-coder bits per step; memory O(steps) plus ~1 MiB of
// fixed tables.
#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <new>
#include <unordered_map>

#include "modeled_block.hpp"
#include "range_coder.hpp"

namespace stepzip::stz {

namespace {

constexpr int kEndSymbol = 8;
// Freeman code -> step on each axis.
constexpr std::int64_t kFreemanDx[8] = {1, 1, 0, -1, -1, -1, 0, 1};
constexpr std::int64_t kFreemanDy[8] = {0, 1, 1, 1, 0, -1, -1, -1};
constexpr std::size_t kMinMatch = 12;    // steps hashed to find a match
constexpr int kMaxStepOrder = 4;  // previous turns in the direction context

int cap(int v, int hi) { return v < hi ? v : hi; }
int len_bucket(std::uint64_t len) {
    if (len < 16) return static_cast<int>(len);
    return cap(16 + bit_length(len) - 5, 23);
}

struct StepContexts {
    Prob turn[4096][8];  // ctx: previous `order` turns (order 0..4)
    Prob end[4];         // ctx: (at start point) + 2 * (no step yet)
    Prob hit[24][2];     // ctx: length bucket x (predicted end)
    UIntModel start[2];
    Prob start_hit[24];  // version 2: chain start as the match predicts, ctx length bucket
};

struct Counts {
    std::uint64_t nchains = 0, nsteps = 0, seen_steps = 0;
};

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
        const std::size_t mask = size_ - 1;
        for (std::size_t i = home(base, last, mask);; i = (i + 1) & mask) {
            const std::uint64_t v = slots_[i];
            if (v == 0) {
                slots_[i] = (key << kPosBits) | pos;
                ++used_;
                return 0;
            }
            if ((v >> kPosBits) == key) {
                slots_[i] = (key << kPosBits) | pos;
                return static_cast<std::uint32_t>(v & ((1u << kPosBits) - 1));
            }
        }
    }
    // Brings the line of `base`'s keys into the cache.
    void prefetch(std::uint64_t base) const {
        __builtin_prefetch(slots_ + home(base, 0, size_ - 1), 1);
    }

private:
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

template <class Io>
class StepCoder {
public:
    // `predict_starts`: version 2 (chain starts predicted by the match).
    StepCoder(Io& io, int order, bool predict_starts)
        : io_(io), ctx_(std::make_unique<StepContexts>()), mask_((1u << (3 * order)) - 1),
          predict_starts_(predict_starts) {}

    // Starts the block from the window (docs/FORMAT.md "Window"): the
    // window's symbols enter the history and the match table in order; the
    // match, `prev` and `turns` stay as at a block's start.
    void prime(const WindowView& window) {
        std::vector<std::uint8_t> all;  // the window's symbols, oldest first
        for (const auto& b : window) all.insert(all.end(), b->symbols.begin(), b->symbols.end());
        hist_.reserve(all.size() + all.size() / 4);
        // Each symbol's table line is fetched kAhead symbols before it is
        // stored: base of the context ahead, rolled as next_base() rolls.
        constexpr std::size_t kAhead = 16;
        std::uint64_t ahead = 0;
        auto roll = [&](std::size_t j) {  // ahead: base before symbol j -> before symbol j + 1
            if (j >= kMinMatch - 1) ahead -= all[j - (kMinMatch - 1)] * pow9(kMinMatch - 2);
            ahead = ahead * 9 + all[j];
        };
        for (std::size_t j = 0; j < std::min(kAhead, all.size()); ++j) roll(j);
        const WindowBlock* block = nullptr;
        std::size_t wb = 0, chain = 0, block_end = 0;
        bool at_start = true;
        for (std::size_t i = 0; i < all.size(); ++i) {
            while (i == block_end) {  // the block this symbol belongs to
                block = window[wb++].get();
                block_end += block->symbols.size();
                chain = 0;
                at_start = true;
            }
            if (i + kAhead < all.size()) {
                table_.prefetch(ahead);
                roll(i + kAhead);
            }
            if (at_start && chain < block->starts.size()) note_start(block->starts[chain++]);
            push(all[i]);
            at_start = all[i] == kEndSymbol;
        }
        ptr_ = -1;
        len_ = 0;
    }

    Point start(const Point& want) {
        Point d{};
        bool hit = false;
        if (predict_starts_ && ptr_ >= 0) {
            // The match predicts a chain start when it points at one.
            const auto it = std::lower_bound(start_pos_.begin(), start_pos_.end(), static_cast<std::uint32_t>(ptr_));
            if (it != start_pos_.end() && *it == static_cast<std::uint32_t>(ptr_)) {
                const Point& pred = start_delta_[static_cast<std::size_t>(it - start_pos_.begin())];
                hit = io_.bit(ctx_->start_hit[len_bucket(len_)], want == pred);
                if (hit) d = pred;
            }
        }
        if (!hit)
            for (int i = 0; i < 2; ++i) {
                d[i] = code_sint(io_, ctx_->start[i], want[i]);  // the rebuilt start is range-checked
            }
        if (predict_starts_) note_start(d);
        return d;
    }

    // Codes the next symbol of a chain: a Freeman code 0..7, or kEndSymbol.
    int next(int want, bool at_start_point, bool first, const Counts& c) {
        return code_symbol(io_, want, at_start_point, first, c);
    }

    // Decoder: the symbols of one chain starting at (x, y), up to its END;
    // moves (x, y) and counts the steps in c.seen_steps, appending them to
    // `steps` when not null. The range decoder runs on a local copy (kept in
    // registers). Returns false when the stream is overrun.
    bool decode_chain(Counts& c, std::int64_t& x, std::int64_t& y, std::vector<Step>* steps)
        requires Io::kDecode
    {
        Io io = io_;
        const std::int64_t sx = x, sy = y;
        bool ok = true;
        for (bool first = true;; first = false) {
            const int sym = code_symbol(io, 0, x == sx && y == sy, first, c);
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

private:
    template <class I>
    [[gnu::always_inline]] int code_symbol(I& io, int want, bool at_start_point, bool first, const Counts& c) {
        int sym;
        // The table line this symbol will update, fetched while it is decoded.
        if (hist_.size() + 1 >= kMinMatch) table_.prefetch(next_base());
        if (c.seen_steps == c.nsteps) {
            sym = kEndSymbol;  // forced: no bits
        } else {
            const int pred = ptr_ >= 0 ? hist_[static_cast<std::size_t>(ptr_)] : -1;
            bool hit = false;
            if (pred >= 0) hit = io.bit(ctx_->hit[len_bucket(len_)][pred == kEndSymbol], want == pred);
            if (hit) {
                sym = pred;
            } else {
                bool end = false;
                if (pred != kEndSymbol)
                    end = io.bit(ctx_->end[(at_start_point ? 1 : 0) + (first ? 2 : 0)], want == kEndSymbol);
                if (end) {
                    sym = kEndSymbol;
                } else {
                    const int t = static_cast<int>(code_tree(
                        io, ctx_->turn[turns_ & mask_], 3, static_cast<unsigned>((want - prev_) & 7)));
                    sym = (prev_ + t) & 7;
                }
            }
        }
        push(sym);
        if (sym != kEndSymbol) {
            turns_ = ((turns_ << 3) | static_cast<unsigned>((sym - prev_) & 7)) & 4095u;
            prev_ = sym;
        }
        return sym;
    }

    // The first kMinMatch - 1 symbols of the context the next symbol will
    // complete (base 9), and whether a match is looked up after it.
    std::uint64_t next_base() const {
        const std::size_t n = hist_.size();
        return n >= kMinMatch ? context_ - hist_[n - kMinMatch] * pow9(kMinMatch - 1) : context_;
    }

    void push(int sym) {
        if (ptr_ >= 0 && hist_[static_cast<std::size_t>(ptr_)] == sym) {
            ++len_;
            ++ptr_;
        } else {
            len_ = 0;
            ptr_ = -1;
        }
        const std::uint64_t base = next_base();
        hist_.push_back(static_cast<std::uint8_t>(sym));
        const std::size_t n = hist_.size();
        context_ = base * 9 + static_cast<unsigned>(sym);
        if (n >= kMinMatch) {
            // The most recent earlier position preceded by the same kMinMatch symbols.
            const std::uint32_t before =
                table_.exchange(base, static_cast<unsigned>(sym), static_cast<std::uint32_t>(n));
            if (before != 0 && ptr_ < 0) ptr_ = before;
        }
    }

    void note_start(const Point& d) {
        start_pos_.push_back(static_cast<std::uint32_t>(hist_.size()));
        start_delta_.push_back(d);
    }

    Io& io_;
    std::unique_ptr<StepContexts> ctx_;
    unsigned mask_;
    bool predict_starts_;
    std::vector<std::uint32_t> start_pos_;  // history position of each chain's first symbol
    std::vector<Point> start_delta_;        // and its start delta
    MatchTable table_;          // last kMinMatch symbols -> next position
    std::uint64_t context_ = 0;  // last kMinMatch symbols, base 9
    std::vector<std::uint8_t> hist_;
    std::int64_t ptr_ = -1;
    std::uint64_t len_ = 0;
    int prev_ = 0;
    unsigned turns_ = 0;
};

}  // namespace

namespace {

std::string write_step_model_order(const Block& block, int order, const WindowView* window) {
    Counts c;
    c.nchains = block.chains.size();
    for (const Chain& ch : block.chains) c.nsteps += ch.steps.size();
    std::string out;
    put_varint(out, c.nchains);
    put_varint(out, c.nsteps);
    put_u8(out, static_cast<unsigned>(order));
    put_layout(out, block.layout);
    EncIo io;
    StepCoder<EncIo> coder(io, order, true);
    if (window) coder.prime(*window);
    Point ref{};
    for (const Chain& chain : block.chains) {
        Point d{};
        for (int a = 0; a < 2; ++a) d[a] = stz::wrap_sub(chain.start[a], ref[a]);
        coder.start(d);
        std::int64_t x = chain.start[0], y = chain.start[1];
        for (std::size_t k = 0;; ++k) {
            const int want = k < chain.steps.size() ? step_to_freeman(chain.steps[k]) : kEndSymbol;
            if (want < 0) return {};
            if (coder.next(want, x == chain.start[0] && y == chain.start[1], k == 0, c) == kEndSymbol) break;
            x += kFreemanDx[want];
            y += kFreemanDy[want];
            ++c.seen_steps;
        }
        ref = Point{};
        ref[0] = x;
        ref[1] = y;
    }
    out += io.rc.finish();
    return out;
}

}  // namespace

std::string write_step_model(const Block& block, int order, const WindowView* window, int* chosen) {
    if (block.axes != 2) return {};
    if (order >= 1 && order <= kMaxStepOrder) {
        if (chosen) *chosen = order;
        return write_step_model_order(block, order, window);
    }
    // The context order is the encoder's choice: the smallest output wins
    // (a low order learns fast on small or noisy blocks, a high one models
    // contours).
    std::string best;
    for (int order = 1; order <= kMaxStepOrder; ++order) {
        std::string alt = write_step_model_order(block, order, window);
        if (alt.empty()) return {};
        if (best.empty() || alt.size() < best.size()) {
            best = std::move(alt);
            if (chosen) *chosen = order;
        }
    }
    return best;
}

Result<void> read_step_model(std::string_view payload, int axes, bool expand, Block& out,
                             BlockCounts& counts, const std::string& where, const WindowView* window,
                             int version) {
    Cursor cur(payload);
    if (axes != 2) return make_error(Errc::corrupt, where + " byte 0: step-model block on " +
                                                        std::to_string(axes) + " axes");
    Counts c;
    if (!cur.varint(c.nchains) || !cur.varint(c.nsteps))
        return make_error(Errc::corrupt, where + " byte " + std::to_string(cur.pos()) + ": bad payload header");
    if (c.nchains > kMaxBlockChains || c.nsteps > kMaxBlockSteps)
        return make_error(Errc::limit, where + " byte 0: payload declares more chains or steps than the limits");
    unsigned order;
    if (!cur.u8(order) || order > static_cast<unsigned>(kMaxStepOrder))
        return make_error(Errc::corrupt, where + " byte " + std::to_string(cur.pos()) + ": bad context order");
    auto layout = get_layout(cur, where);
    if (!layout) return std::move(layout).error();
    const std::size_t base = cur.pos();
    DecIo io(payload.substr(base));
    StepCoder<DecIo> coder(io, static_cast<int>(order), version >= 2);
    if (window) coder.prime(*window);
    if (expand) {
        out.axes = axes;
        out.chains.clear();
        out.layout = std::move(*layout);
    }
    auto fail = [&](const std::string& what) {
        return make_error(Errc::corrupt, where + " byte " + std::to_string(base + io.rc.pos()) + ": " + what);
    };
    Point ref{};
    for (std::uint64_t i = 0; i < c.nchains; ++i) {
        Chain chain;
        chain.axes = axes;
        const Point d = coder.start(Point{});
        if (io.failed || io.rc.overrun()) return fail("bad chain start");
        for (int a = 0; a < 2; ++a) {
            chain.start[a] = stz::wrap_add(ref[a], d[a]);
            if (!stz::start_in_range(chain.start[a])) return fail("chain start out of range");
        }
        std::int64_t x = chain.start[0], y = chain.start[1];
        if (!coder.decode_chain(c, x, y, expand ? &chain.steps : nullptr) || io.failed)
            return fail("bad step");
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

}  // namespace stepzip::stz
