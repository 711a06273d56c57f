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

#include "mix.hpp"
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

}  // namespace

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

// The step model's history (docs/FORMAT.md 1.6, 1.8): symbols, the match
// table over them and the recorded chain starts. A coder owns one for a
// block (and its window, rebuilt); the decoder keeps one across the blocks
// of a frame (make_step_history()), so that a block flagged `window` needs
// no rebuild: a table position before the window's start (plus kMinMatch)
// counts as absent, which is what the table rebuilt from the window alone
// answers, since the table keeps the most recent position of each context.
struct StepHistory {
    std::vector<std::uint8_t> hist;
    std::uint64_t context = 0;  // last kMinMatch symbols, base 9
    MatchTable table;           // last kMinMatch symbols -> next position
    std::vector<std::uint32_t> start_pos;  // position of each chain's first symbol
    std::vector<Point> start_delta;        // and its start delta
    std::uint64_t base = 0;                // frame position of hist[0] (decoder)
    std::uint32_t min_valid = 1;           // smallest table position a lookup may return

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
        return table.exchange(b, static_cast<unsigned>(sym), static_cast<std::uint32_t>(n));
    }
    void note_start(const Point& d) {
        start_pos.push_back(static_cast<std::uint32_t>(hist.size()));
        start_delta.push_back(d);
    }
    // Appends a block's contribution (its symbols, and its chain starts at
    // the chains' first symbols). Each symbol's table line is fetched kAhead
    // symbols before it is stored.
    void add(const WindowBlock& b) {
        const std::vector<std::uint8_t>& all = b.symbols;
        constexpr std::size_t kAhead = 16;
        // `ahead`: the base next_base() will return kAhead symbols later.
        std::uint64_t ahead = next_base();
        std::size_t n = hist.size();
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
    // Decoder, before each block: positions before `window_start` (a frame
    // position) are outside the window; a dead prefix longer than the window
    // `limit` (at most 2^22) is dropped and the table rebuilt from the window,
    // so that memory stays O(window) and positions below 2^25; the rebuild
    // costs one more append per symbol at most.
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

void StepHistoryDeleter::operator()(StepHistory* h) const { delete h; }
StepHistoryPtr make_step_history() { return StepHistoryPtr(new StepHistory); }
void step_history_add(StepHistory& h, const WindowBlock& b) { h.add(b); }
void step_history_begin_block(StepHistory& h, std::uint64_t window_start, std::uint64_t limit) {
    h.begin_block(window_start, limit);
}
std::uint64_t step_history_end(const StepHistory& h) { return h.base + h.hist.size(); }

namespace {

template <class Io>
class StepCoder {
public:
    // `predict_starts`: version 2 (chain starts predicted by the match).
    // `shared`: the decoder's history of the frame (else the coder's own).
    StepCoder(Io& io, int order, bool predict_starts, StepHistory* shared = nullptr)
        : io_(io), ctx_(std::make_unique<StepContexts>()), mask_((1u << (3 * order)) - 1),
          predict_starts_(predict_starts), own_(shared ? nullptr : std::make_unique<StepHistory>()),
          h_(shared ? *shared : *own_) {
        if constexpr (kMixedIo<Io>) {
            static_assert(sizeof(StepContexts) % sizeof(Prob) == 0);
            curve_ = io_.curvature;
            mixer_ = std::make_unique<MixPredictor>(reinterpret_cast<const Prob*>(ctx_.get()),
                                                    curve_ ? kMixMaxModels : kMixBaseModels);
            io_.m = mixer_.get();
        }
    }

    // Starts the block from the window (docs/FORMAT.md "Window"): the
    // window's symbols enter the history and the match table in order; the
    // match, `prev` and `turns` stay as at a block's start.
    void prime(const WindowView& window) {
        for (const auto& b : window) h_.add(*b);
        ptr_ = -1;
        len_ = 0;
    }

    Point start(const Point& want) {
        Point d{};
        bool hit = false;
        dx_ = dy_ = 0;
        in_chain_ = 0;
        io_.field(3);
        if (predict_starts_ && ptr_ >= 0) {
            // The match predicts a chain start when it points at one.
            const auto& pos = h_.start_pos;
            const auto it = std::lower_bound(pos.begin(), pos.end(), static_cast<std::uint32_t>(ptr_));
            if (it != pos.end() && *it == static_cast<std::uint32_t>(ptr_)) {
                const Point& pred = h_.start_delta[static_cast<std::size_t>(it - pos.begin())];
                hit = io_.bit(ctx_->start_hit[len_bucket(len_)], want == pred);
                if (hit) d = pred;
            }
        }
        if (!hit)
            for (int i = 0; i < 2; ++i) {
                d[i] = code_sint(io_, ctx_->start[i], want[i]);  // the rebuilt start is range-checked
            }
        if (predict_starts_) h_.note_start(d);
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
        if (h_.hist.size() + 1 >= kMinMatch) h_.table.prefetch(h_.next_base());
        if (c.seen_steps == c.nsteps) {
            sym = kEndSymbol;  // forced: no bits
        } else {
            const int pred = ptr_ >= 0 ? h_.hist[static_cast<std::size_t>(ptr_)] : -1;
            if constexpr (kMixedIo<I>) symbol_contexts(io, pred);
            bool hit = false;
            io.field(0);
            if (pred >= 0) hit = io.bit(ctx_->hit[len_bucket(len_)][pred == kEndSymbol], want == pred);
            if (hit) {
                sym = pred;
            } else {
                bool end = false;
                io.field(1);
                if (pred != kEndSymbol)
                    end = io.bit(ctx_->end[(at_start_point ? 1 : 0) + (first ? 2 : 0)], want == kEndSymbol);
                if (end) {
                    sym = kEndSymbol;
                } else {
                    io.field(2);
                    const int t = static_cast<int>(code_tree(
                        io, ctx_->turn[turns_ & mask_], 3, static_cast<unsigned>((want - prev_) & 7)));
                    sym = (prev_ + t) & 7;
                }
            }
        }
        push(sym);
        if (sym != kEndSymbol) {
            const unsigned turn = static_cast<unsigned>((sym - prev_) & 7);
            turns_ = ((turns_ << 3) | turn) & 4095u;
            if constexpr (kMixedIo<I>) {
                history_ = (history_ << 3) | turn;
                dx_ += kFreemanDx[sym];
                dy_ += kFreemanDy[sym];
                ++in_chain_;
                if (turn == 0) {
                    ++run_;
                } else {
                    runs_ = (runs_ << 8) | (static_cast<std::uint64_t>(cap(run_, 31)) << 3) | turn;
                    run_ = 1;
                }
            }
            prev_ = sym;
        }
        return sym;
    }

    // The hashed contexts of the mixed predictions for the next symbol
    // (docs/FORMAT.md "Step-model contexts").
    template <class I>
    void symbol_contexts(I& io, int pred) {
        const auto p = static_cast<std::uint64_t>(prev_);
        mix_context(io, 0, ctx_join(p, history_ & 0x3FFFFu));  // six turns
        mix_context(io, 1, ctx_join(p, history_ & 0x3FFFFFFFu));  // ten turns
        mix_context(io, 2, ctx_join(ctx_join(p, static_cast<std::uint64_t>(pred + 1)),
                                    static_cast<std::uint64_t>(len_bucket(len_)) << 3 | (history_ & 7)));
        // The digital straight segment being drawn: the current run of one
        // direction and the runs and turns before it.
        mix_context(io, 3, ctx_join(ctx_join(p, static_cast<std::uint64_t>(cap(run_, 31))), runs_ & 0xFFFFFFu));
        // Closure: where the chain start lies.
        const std::int64_t ax = std::llabs(dx_), ay = std::llabs(dy_);
        std::uint64_t where = 0;
        if (ax <= 15 && ay <= 15)
            where = static_cast<std::uint64_t>((dx_ + 16) * 32 + (dy_ + 16));
        else
            where = 2048 + static_cast<std::uint64_t>((dx_ < 0) * 2 + (dy_ < 0)) * 256 +
                    static_cast<std::uint64_t>(cap(bit_length(static_cast<std::uint64_t>(ax)), 15)) * 16 +
                    static_cast<std::uint64_t>(cap(bit_length(static_cast<std::uint64_t>(ay)), 15));
        mix_context(io, 4, ctx_join(ctx_join(p, where), history_ & 7));
        mix_context(io, 5, ctx_join(ctx_join(p, history_ & 0x1FFu),
                                    static_cast<std::uint64_t>(cap(bit_length(in_chain_), 15))));
        if (curve_) {
            // The match's predicted symbol under three turns, and under how
            // the runs grow or shrink (the two runs and turns before).
            const auto q = static_cast<std::uint64_t>(pred + 1);
            mix_context(io, 6, ctx_join(ctx_join(ctx_join(p, history_ & 0x1FFu), q),
                                        static_cast<std::uint64_t>(len_bucket(len_))));
            const int r1 = static_cast<int>((runs_ >> 3) & 31), r2 = static_cast<int>((runs_ >> 11) & 31);
            const int t1 = static_cast<int>(runs_ & 7), t2 = static_cast<int>((runs_ >> 8) & 7);
            const std::uint64_t c = static_cast<std::uint64_t>(std::clamp(run_ - r1, -3, 3) + 3) * 8 +
                                    static_cast<std::uint64_t>(std::clamp(r1 - r2, -3, 3) + 3);
            mix_context(io, 7, ctx_join(ctx_join(ctx_join(ctx_join(p, c), static_cast<std::uint64_t>(t1 * 8 + t2)),
                                                 static_cast<std::uint64_t>(cap(bit_length(static_cast<std::uint64_t>(r1)), 5))),
                                        q));
        }
    }

    void push(int sym) {
        if (ptr_ >= 0 && h_.hist[static_cast<std::size_t>(ptr_)] == sym) {
            ++len_;
            ++ptr_;
        } else {
            len_ = 0;
            ptr_ = -1;
        }
        // The most recent earlier position preceded by the same kMinMatch
        // symbols, inside the window.
        const std::uint32_t before = h_.append(sym);
        if (before >= h_.min_valid && before != 0 && ptr_ < 0) ptr_ = before;
    }

    Io& io_;
    std::unique_ptr<StepContexts> ctx_;
    unsigned mask_;
    bool predict_starts_;
    std::unique_ptr<StepHistory> own_;
    StepHistory& h_;
    std::int64_t ptr_ = -1;
    std::uint64_t len_ = 0;
    int prev_ = 0;
    unsigned turns_ = 0;
    // Mixed predictions only (block type 6).
    std::unique_ptr<MixPredictor> mixer_;
    std::uint64_t history_ = 0;  // turns, 3 bits each, latest lowest (across chains)
    std::uint64_t runs_ = 0;     // finished runs: (length (cap 31) << 3 | turn after it), 8 bits each
    int run_ = 0;                // steps in the current direction
    bool curve_ = false;
    std::int64_t dx_ = 0, dy_ = 0;  // position relative to the chain's start
    std::uint64_t in_chain_ = 0;
};

}  // namespace

namespace {

template <class Io>
std::string write_step_model_with(const Block& block, int order, const WindowView* window, bool curvature = false) {
    Counts c;
    c.nchains = block.chains.size();
    for (const Chain& ch : block.chains) c.nsteps += ch.steps.size();
    std::string out;
    if constexpr (kMixedIo<Io>) put_u8(out, kMixedStep | (curvature ? kMixedCurvature : 0u));
    put_varint(out, c.nchains);
    put_varint(out, c.nsteps);
    put_u8(out, static_cast<unsigned>(order));
    put_layout(out, block.layout);
    Io io;
    if constexpr (kMixedIo<Io>) io.curvature = curvature;
    StepCoder<Io> coder(io, order, true);
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

std::string write_step_model_order(const Block& block, int order, const WindowView* window) {
    return write_step_model_with<EncIo>(block, order, window);
}

}  // namespace

std::string write_mixed_step_model(const Block& block, int order, const WindowView* window, bool curvature) {
    if (block.axes != 2 || order < 0 || order > kMaxStepOrder) return {};
    return write_step_model_with<MixEncIo>(block, order, window, curvature);
}

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

namespace {

template <class Io>
Result<void> read_step_model_with(std::string_view payload, int axes, bool expand, Block& out,
                                  BlockCounts& counts, const std::string& where, const WindowView* window,
                                  int version, StepHistory* running) {
    Cursor cur(payload);
    bool curvature = false;
    if (axes != 2) return make_error(Errc::corrupt, where + " byte 0: step-model block on " +
                                                        std::to_string(axes) + " axes");
    Counts c;
    if constexpr (kMixedIo<Io>) {
        unsigned kind;
        if (!cur.u8(kind) || mixed_model_of(kind) != kStepModel)
            return make_error(Errc::corrupt, where + " byte 0: not a mixed step model");
        curvature = (kind & kMixedCurvature) != 0;
    }
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
    Io io = [&] {
        if constexpr (kMixedIo<Io>) return Io(payload.substr(base), nullptr);  // the coder sets the predictor
        else return Io(payload.substr(base));
    }();
    if constexpr (kMixedIo<Io>) io.curvature = curvature;
    StepCoder<Io> coder(io, static_cast<int>(order), version >= 2, window ? running : nullptr);
    if (window && !running) coder.prime(*window);
    start_output(out, expand, axes, std::move(*layout));
    auto fail = [&](const std::string& what) {
        return make_error(Errc::corrupt, where + " byte " + std::to_string(base + io.rc.pos()) + ": " + what);
    };
    Point ref{};
    for (std::uint64_t i = 0; i < c.nchains; ++i) {
        Chain chain;
        Point d;
        if (const char* e = next_chain_start(coder, io, ref, 2, chain, d)) return fail(e);
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

}  // namespace

Result<void> read_step_model(std::string_view payload, int axes, bool expand, Block& out,
                             BlockCounts& counts, const std::string& where, const WindowView* window,
                             int version, StepHistory* running, bool mixed) {
    if (mixed)
        return read_step_model_with<MixDecIo>(payload, axes, expand, out, counts, where, window, version, running);
    return read_step_model_with<DecIo>(payload, axes, expand, out, counts, where, window, version, running);
}

}  // namespace stepzip::stz
