// The context-mixing step models (docs/FORMAT.md 1.11.2-1.11.4, block type
// 6 model bytes 4, 5 and 6): two-axis chains coded step by step, in the
// manner of lpaq1 and paq8 but over turns instead of bytes. Each step is an
// end bit and, but at a chain's end, its turn against the previous step,
// binarized by a small tree whose first decision is "straight on"; every
// decision of the tree is predicted by hashed context models (orders of 1 to
// 24 turns, the runs of the digital straight segment being drawn, the way
// back to the chain's start, the match model's prediction; model byte 6 adds
// the longest DSS ending at the last step and what each turn would do to it,
// dss_suffix.hpp, with fast-adapting counters of its state, and codes chain
// starts with mixed predictions, StartModel),
// their stretched probabilities mixed by online-trained
// mixers whose weights a small context selects, then refined by two
// adaptive probability maps (model bytes 5 and 7: two models, one mixer, no
// map; 7 with at most 2^16 rows).
// A stretch repeated anywhere before is repeated steps, whatever cut a
// segment model would give it. One template (CmStepCoder<Io, CmKind>) runs
// both directions of all three; integer arithmetic only, so any decoder
// that follows FORMAT.md reproduces every probability.
// Complexity: one plain bit and 0-5 mixed bits per step (11 or 13 hashed
// models each; one mixed bit for a step straight on, five for a turn of
// +-135 degrees), one cache line per model and step, fetched while the step
// before is coded (0.3-0.6 us a step on the development machine; model byte
// 6 about a third slower than 4); memory 32 bytes per hashed row,
// 2^12..2^21 rows by the block's step count (FORMAT.md; model byte 7 at most
// 2^16), plus the step history.
#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <type_traits>
#include <vector>

#include "dss_suffix.hpp"
#include "mix.hpp"
#include "modeled_block.hpp"
#include "range_coder.hpp"
#include "step_history.hpp"

namespace stepzip::stz {

namespace {

// Decisions of the turn tree (t = the turn, 0..7, in 45-degree units):
// node 0: t != 0; node 1: t not in {1, 7}; node 2: t == 7 (of 1, 7);
// node 3: t not in {2, 6}; node 4: t == 6 (of 2, 6); node 5: t != 4;
// node 6: t == 5 (of 3, 5).
constexpr int kNodes = 7;
// kPath[t][n]: the bit turn t takes at node n, or -1 off its path.
constexpr std::array<std::array<std::int8_t, kNodes>, 8> kPath = {{
    {0, -1, -1, -1, -1, -1, -1},  // 0
    {1, 0, 0, -1, -1, -1, -1},    // 1
    {1, 1, -1, 0, 0, -1, -1},     // 2
    {1, 1, -1, 1, -1, 1, 0},      // 3
    {1, 1, -1, 1, -1, 0, -1},     // 4
    {1, 1, -1, 1, -1, 1, 1},      // 5
    {1, 1, -1, 0, 1, -1, -1},     // 6
    {1, 0, 1, -1, -1, -1, -1},    // 7
}};

constexpr int kModels = 11;                 // hashed context models of model byte 4 (13 of model byte 6)
constexpr int kCountLimit = 255;            // a counter's rate settles at 1/(limit + 1.5)
constexpr std::int64_t kMixRate = 3;        // mixer learning rate (see train())
constexpr std::int32_t kInitWeight = 16384; // 0.25 in 16.16
constexpr std::int32_t kMaxWeight = 1 << 22;
constexpr int kApmRate = 7;
constexpr int kMinRowBits = 12, kMaxRowBits = 21;
// Model byte 7's cap (the light model's two rows a step): 2 MiB of rows,
// against 64 MiB for a block of 2^20 steps: 0.1-0.4 % larger on large
// contours, 11-17 % less CPU time each way (docs/benchmarks.md "The light
// step model in 2 MiB").
constexpr int kLightSmallRowBits = 16;

// The counters' rates (StateMap-like, lpaq1).
constexpr mixdetail::RecipTable<kCountLimit + 1> kRecip{};

// A counter: probability of a 1 in the high 22 bits, count in the low 10.
constexpr std::uint32_t kCounterInit = std::uint32_t{1} << 31;

[[gnu::always_inline]] inline std::uint32_t counter_p16(std::uint32_t e) { return e >> 16; }
// After bit `bit`: rate 1/(n + 1.5), the count n stopping at `Limit`.
template <std::uint32_t Limit = kCountLimit>
[[gnu::always_inline]] inline void counter_update(std::uint32_t& e, int bit) {
    static_assert(Limit <= kCountLimit);
    const std::uint32_t n = e & 1023u;
    const std::int32_t p = static_cast<std::int32_t>(e >> 10);
    const std::int32_t target = bit ? (1 << 22) - 1 : 0;
    const std::int32_t q = p + static_cast<std::int32_t>((static_cast<std::int64_t>(target - p) * kRecip.v[n]) >> 16);
    e = (static_cast<std::uint32_t>(q) << 10) | (n < Limit ? n + 1 : n);
}
// Model byte 6's fast counters stop counting at 8 (their rate settles at
// 1/9.5): next to the slow hashed counters they follow a drift.
constexpr std::uint32_t kFastLimit = 8;

// One hashed context's counters for the nodes of a step, with a check of
// the context (0: empty row) and a use count for replacement.
struct Row {
    std::uint16_t check;
    std::uint16_t uses;
    std::uint32_t p[kNodes];
};
static_assert(sizeof(Row) == 32);

// The rows of all hashed models: 2^bits rows, looked up in pairs (one
// 64-byte line).
class RowTable {
public:
    // Fresh zero rows in 2 MiB pages where the kernel allows (ZeroPages):
    // every step touches a row of each model anywhere in the table, and
    // 4 KiB pages cost a TLB miss on most of them.
    explicit RowTable(int bits)
        : mask_((std::size_t{1} << bits) - 1), pages_((mask_ + 1) * sizeof(Row)), rows_(static_cast<Row*>(pages_.data())) {}
    RowTable(const RowTable&) = delete;
    RowTable& operator=(const RowTable&) = delete;

    void prefetch(std::uint64_t h) const { __builtin_prefetch(&rows_[index(h)], 1); }
    // The row of context hash `h`: the pair's row with its check, else the
    // one used less, emptied for it (the other's use count decays).
    // (Always inline: once out of line, as GCC chose when the coder grew,
    // the decoder ran 2 % more instructions.)
    [[gnu::always_inline]] Row* find(std::uint64_t h) {
        const std::size_t i = index(h);
        const std::uint16_t check = static_cast<std::uint16_t>(((h >> 8) & 0xFFFFu) | 1u);
        Row* a = &rows_[i];
        Row* b = a + 1;
        if (a->check == check) return touch(a);
        if (b->check == check) return touch(b);
        Row* victim = b->uses < a->uses ? b : a;
        Row* other = victim == a ? b : a;
        other->uses = static_cast<std::uint16_t>(other->uses - (other->uses >> 2));
        victim->check = check;
        victim->uses = 0;
        for (auto& c : victim->p) c = kCounterInit;
        return touch(victim);
    }

private:
    std::size_t index(std::uint64_t h) const { return static_cast<std::size_t>(h >> 40) & mask_ & ~std::size_t{1}; }
    static Row* touch(Row* r) {
        r->uses = static_cast<std::uint16_t>(r->uses + (r->uses < 65535));
        return r;
    }
    std::size_t mask_;
    mixdetail::ZeroPages pages_;
    Row* rows_;
};

// An adaptive probability map (lpaq1's APM): per row 33 points over the
// stretched input; the output interpolates the two nearest, the nearer is
// trained.
class Apm {
public:
    // Every row starts the same; a row is filled when first used (a small
    // block touches few of them).
    explicit Apm(int rows) : t_(static_cast<std::size_t>(rows) * 33), ready_(static_cast<std::size_t>(rows)) {}
    std::int32_t refine(std::int32_t st, std::size_t row) {
        std::uint16_t* r = &t_[row * 33];
        if (!ready_[row]) {
            std::memcpy(r, mixdetail::kApmFirstRow.data(), sizeof mixdetail::kApmFirstRow);
            ready_[row] = 1;
        }
        return mixdetail::apm_refine(r, std::clamp(st, -2047, 2047), at_);
    }
    void update(int bit) { mixdetail::apm_train(at_, bit, kApmRate); }

private:
    std::vector<std::uint16_t> t_;
    std::vector<std::uint8_t> ready_;
    std::uint16_t* at_ = nullptr;
};

constexpr std::uint64_t hash_ctx(int k, std::uint64_t v) {
    std::uint64_t x = (v + static_cast<std::uint64_t>(k + 1) * 0x9E3779B97F4A7C15ull) * 0xD6E8FEB86659FD93ull;
    x ^= x >> 32;
    x *= 0x9E3779B97F4A7C15ull;
    return x ^ (x >> 29);
}

// The row table's size (FORMAT.md 1.11.2), at most 2^max_bits rows.
int row_bits_for(std::uint64_t nsteps, int max_bits) {
    const int b = bit_length(nsteps) + 1;
    return std::clamp(b, kMinRowBits, max_bits);
}

using CmCounts = StepCounts;

// The light model (model bytes 5 and 7, docs/FORMAT.md 1.11.3) keeps models
// kLightSet of the eleven (orders 3 and 16 turns), the match input, one
// weight set and no probability map. Chosen on glyphs-big.fc and
// icons-big-8.fc (docs/benchmarks.md "The light step model").
constexpr std::array<int, 2> kLightSet = {1, 5};
static_assert(std::none_of(kLightSet.begin(), kLightSet.end(), [](int k) { return k == 7 || k == 8 || k == 10; }),
              "the light model keeps no walk (StepWalk) for models 7, 8 and 10");

// The three models of the coder: model bytes 5 and 7, 4 and 6
// (docs/FORMAT.md 1.11.3, 1.11.2, 1.11.4).
enum class CmKind { light, full, dss };

// Model byte 6's third weight set: per node, the DSS state (dss_state()),
// the last break's side and the word's length class (dss_select()).
constexpr std::size_t kDssSets = kDssStates * 3 * 4;

// Model byte 6's DSS value (models 11 and 12): the word's state from `prev`,
// length class, place in its strip (8 classes), slope (17 classes) and last
// three break sides.
inline std::uint64_t dss_value(const DssWord& w, int prev) {
    const std::int64_t r = w.a * w.m.x - w.b * w.m.y;
    const auto place = static_cast<std::uint64_t>(((r - w.mu) * 8) / w.b);
    const auto slope = static_cast<std::uint64_t>((w.a * 16) / w.b);
    const auto len = static_cast<std::uint64_t>(std::min(bit_length(static_cast<std::uint64_t>(w.len)), 15));
    const std::uint64_t v = ((static_cast<std::uint64_t>(dss_state(w, prev)) << 4 | len) << 3 | place) << 5 | slope;
    return v * 27 + static_cast<std::uint64_t>(w.brk);
}
inline std::size_t dss_select(const DssWord& w, int prev) {
    const int len = std::min(bit_length(static_cast<std::uint64_t>(w.len)), 15);
    return static_cast<std::size_t>((dss_state(w, prev) * 3 + w.brk % 3) * 4 + std::min(len >> 1, 3));
}


// A weight set's output: its dot product with the inputs x (the first n
// of N), in 1/2^16, clamped to the stretched range.
template <int N>
std::int32_t set_output(const std::int32_t* w, const std::int32_t* x, int n) {
    const std::int64_t d = mix_dot<N>(w, x, n) >> 16;
    return static_cast<std::int32_t>(std::clamp<std::int64_t>(d, -2047, 2047));
}
// Each weight moves by input * error * kMixRate / 2^16 (error of the
// set's own output, 16-bit), within +-kMaxWeight. In 32 bits: |input|
// <= 2047 and |error| < 2^16 * kMixRate, so the product stays below 2^31.
static_assert(2047 * (std::int64_t{65536} * kMixRate) < (std::int64_t{1} << 31) &&
              kMaxWeight + ((2047 * (std::int64_t{65536} * kMixRate)) >> 16) < (std::int64_t{1} << 31));
template <int N>
void train_set(std::int32_t* w, const std::int32_t* x, std::int32_t out, int bit, int n) {
    const std::int32_t err = ((bit << 16) - out) * static_cast<std::int32_t>(kMixRate);
    mix_train<N>(w, x, err, kMaxWeight, n);
}
// The bit `want` coded (encoder), or one read (decoder), with probability
// p (1/65536) of a 1.
template <class I>
[[gnu::always_inline]] inline int code_bit_p(I& io, std::int32_t p, int want) {
    if constexpr (I::kDecode) {
        return io.rc.decode_p(static_cast<std::uint32_t>(65536 - p));
    } else {
        io.rc.encode_p(static_cast<std::uint32_t>(65536 - p), want);
        return want;
    }
}

// Model byte 6's chain starts (docs/FORMAT.md 1.11.4): a start the match
// does not predict is coded as its delta's y, then x, each a zero flag, a
// sign, the magnitude's bit length less one in unary and the magnitude's
// bits below its top, each bit mixed from seven hashed counters whose
// contexts read the chains before (their deltas, steps and boxes: a
// tracer's raster order and a text's advance). The step models before it
// code each coordinate by one adaptive binarization (code_sint()).
class StartModel {
public:
    static constexpr int kCtx = 7;
    // What the chains before a start were (all zero before a block's first
    // chain).
    struct Before {
        Point d{}, d2{};          // the last two chains' start deltas
        std::uint64_t steps = 0;  // the last chain's steps
        std::uint64_t w = 0, h = 0;  // its box's width and height
    };

    explicit StartModel(std::uint64_t nchains)
        : bits_(std::clamp(bit_length(nchains) + 5, 10, 16)), t_(std::size_t{1} << bits_, kCounterInit) {
        for (auto& w : weights_) w = kInitWeight / 2;  // (eight inputs: their sum about one input at first)
    }

    // Codes `want` (the encoder's delta; the decoder's is ignored).
    template <class I>
    Point code(I& io, const Before& b, const Point& want) {
        Point d{};
        d[1] = code_axis(io, 1, b, 0, want[1]);
        d[0] = code_axis(io, 0, b, d[1], want[0]);
        return d;
    }

private:
    // A value's class: 0, else sign and bit length (cap 15).
    static std::uint64_t cls(std::int64_t v) {
        if (v == 0) return 0;
        const std::uint64_t m = v < 0 ? 0 - static_cast<std::uint64_t>(v) : static_cast<std::uint64_t>(v);
        return (v < 0 ? 32u : 16u) + static_cast<std::uint64_t>(std::min(bit_length(m), 15));
    }
    static std::uint64_t bl(std::uint64_t v, int cap) { return static_cast<std::uint64_t>(std::min(bit_length(v), cap)); }

    template <class I>
    std::int64_t code_axis(I& io, int axis, const Before& b, std::int64_t dy, std::int64_t want) {
        const std::uint64_t pd = cls(b.d[static_cast<std::size_t>(axis)]), pd2 = cls(b.d2[static_cast<std::size_t>(axis)]);
        const std::uint64_t w = bl(b.w, 7), h = bl(b.h, 7);
        std::array<std::uint64_t, kCtx> v = {0, pd, w * 8 + h, bl(b.steps, 12), (cls(b.d[0]) * 48 + cls(b.d[1])) * 48 + pd2, 0, 0};
        if (axis == 0) {
            v[5] = cls(dy) * 48 + pd;
            v[6] = cls(dy) * 8 + w;
        } else {
            v[5] = pd * 8 + h;
            v[6] = pd * 48 + pd2;
        }
        for (int i = 0; i < kCtx; ++i)
            base_[static_cast<std::size_t>(i)] = hash_ctx(16 + axis * kCtx + i, v[static_cast<std::size_t>(i)]);
        axis_ = axis;
        const std::uint64_t mag = want < 0 ? 0 - static_cast<std::uint64_t>(want) : static_cast<std::uint64_t>(want);
        if (!bit(io, 0, 0, want != 0)) return 0;
        const int neg = bit(io, 1, 1, want < 0);
        const int k = I::kDecode ? 0 : bit_length(mag) - 1;
        int got = 0;
        while (bit(io, 2 + std::min(got, 23), 2 + std::min(got, 11), got < k)) {
            if (++got > 63) {
                io.failed = true;
                return 0;
            }
        }
        std::uint64_t m = 1;
        for (int j = 0; j < got; ++j) {
            const int dc = 26 + std::min(got, 23) * 8 + std::min(j, 7);
            m = (m << 1) | static_cast<std::uint64_t>(bit(io, dc, 14 + std::min(j, 7), static_cast<int>((mag >> (got - 1 - j)) & 1u)));
        }
        return static_cast<std::int64_t>(neg ? 0 - m : m);
    }

    // One mixed bit: decision `dc` (its counters), weight set `set` of the axis.
    template <class I>
    int bit(I& io, int dc, int set, int want) {
        std::array<std::uint32_t*, kCtx> c{};
        std::array<std::int32_t, 8> x{};
        for (int i = 0; i < kCtx; ++i) {
            const std::uint64_t hh = ctx_join(base_[static_cast<std::size_t>(i)], static_cast<std::uint64_t>(dc)) * 0x9E3779B97F4A7C15ull;
            c[static_cast<std::size_t>(i)] = &t_[static_cast<std::size_t>(hh >> (64 - bits_))];
            x[static_cast<std::size_t>(i)] = stretch(counter_p16(*c[static_cast<std::size_t>(i)]));
        }
        x[kCtx] = 256;
        std::int32_t* wt = &weights_[static_cast<std::size_t>(axis_ * 22 + set) * 8];
        const std::int32_t p = mixdetail::squash_within(set_output<8>(wt, x.data(), 8));
        const int b = code_bit_p(io, std::clamp(p, 32, 65535 - 32), want);
        train_set<8>(wt, x.data(), p, b, 8);
        for (auto* e : c) counter_update(*e, b);
        return b;
    }

    int bits_;
    std::vector<std::uint32_t> t_;
    std::array<std::int32_t, 2 * 22 * 8> weights_;
    std::array<std::uint64_t, kCtx> base_{};
    int axis_ = 0;
};

template <class Io, CmKind K>
class CmStepCoder : public StepCoderShell<CmStepCoder<Io, K>, Io> {
    friend class StepCoderShell<CmStepCoder<Io, K>, Io>;
    static constexpr bool Light = K == CmKind::light, Dss = K == CmKind::dss;
    static constexpr int kM = Light ? static_cast<int>(kLightSet.size()) : Dss ? kModels + 2 : kModels;  // hashed models used
    // Inputs: the hashed models, the match, the bias and (model byte 6) the
    // fast counter.
    static constexpr int kIn = kM + 2 + (Dss ? 1 : 0);
    // A weight set's stride: the inputs rounded up to eight for the AVX2
    // loops (the inputs past kIn are 0, so their weights never move).
    static constexpr int kStride = Light ? kIn : (kIn + 7) / 8 * 8;
    static constexpr std::size_t kSets = Light ? kNodes * 7 : kNodes * 7 + kNodes * 64 + (Dss ? kNodes * kDssSets : 0);

public:
    // `max_row_bits`: the row table's cap (kMaxRowBits, or model byte 7's).
    CmStepCoder(Io& io, const CmCounts& counts, StepHistory* shared, int max_row_bits = kMaxRowBits)
        : io_(io), rows_(row_bits_for(counts.nsteps, max_row_bits)), apm1_(Light ? 1 : kNodes * 512), apm2_(Light ? 1 : kNodes * 2 * 24 * 2),
          own_(shared ? nullptr : std::make_unique<StepHistory>()), h_(shared ? *shared : *own_),
          starts_(Dss ? std::make_unique<StartModel>(counts.nchains) : nullptr) {
        for (auto& r : match_)
            for (auto& v : r) v = kCounterInit;
    }

    Point start(const Point& want) {
        ahead_sym_ = -1;
        if constexpr (Dss) {
            before_.steps = w_.in_chain;  // (the chain before)
            before_.w = static_cast<std::uint64_t>(box_[1] - box_[0]);
            before_.h = static_cast<std::uint64_t>(box_[3] - box_[2]);
            box_ = {};
            w_.start_chain();
            dss_.start_chain();
            const Point d = code_step_start_with(io_, h_, m_, start_hit_, true, want,
                                                 [&](Io& io) { return starts_->code(io, before_, want); });
            before_.d2 = before_.d;
            before_.d = d;
            return d;
        } else {
            w_.start_chain();
            return code_step_start(io_, h_, m_, start_, start_hit_, true, want);
        }
    }

private:
    template <class I>
    [[gnu::always_inline]] int code_symbol(I& io, int want, bool at_start_point, bool first, const CmCounts& c) {
        if (h_.hist.size() + 1 >= kMinMatch) h_.table.prefetch(h_.next_base());
        int sym;
        if (c.seen_steps == c.nsteps) {
            sym = kEndSymbol;  // forced: no bits
        } else {
            const int pred = m_.predicted(h_);
            if constexpr (Dss) {
                dss_sel_ = dss_select(dss_.word(), prev_);
                fast_row_ = &fast_[(dss_sel_ * 8 + static_cast<std::size_t>(prev_)) * kNodes];
            }
            contexts(pred);
            if constexpr (I::kDecode) prefetch_after(prev_);
            else if (want != kEndSymbol) prefetch_after(want);
            const int pe = pred < 0 ? 0 : pred == kEndSymbol ? 1 : 2;
            if (io.bit(end_[pe][at_start_point][first], want == kEndSymbol)) {
                sym = kEndSymbol;
            } else {
                for (int k = 0; k < kM; ++k) row_[static_cast<std::size_t>(k)] = rows_.find(hash_[static_cast<std::size_t>(k)]);
                pred_turn_ = pred >= 0 && pred != kEndSymbol ? (pred - prev_) & 7 : -1;
                const int t = code_turn(io, (want - prev_) & 7);
                sym = (prev_ + t) & 7;
            }
        }
        m_.push(h_, sym);
        if (sym != ahead_sym_) ahead_sym_ = -1;  // (an END is never guessed)
        if (sym != kEndSymbol) note_turn(sym);
        return sym;
    }

    template <class I>
    [[gnu::always_inline]] int code_turn(I& io, int t) {
        if (!node(io, 0, t != 0)) return 0;
        if (!node(io, 1, t != 1 && t != 7)) return node(io, 2, t == 7) ? 7 : 1;
        if (!node(io, 3, t != 2 && t != 6)) return node(io, 4, t == 6) ? 6 : 2;
        if (!node(io, 5, t != 4)) return 4;
        return node(io, 6, t == 5) ? 5 : 3;
    }

    // One mixed decision of the turn tree.
    template <class I>
    [[gnu::always_inline]] int node(I& io, int n, int want) {
        std::array<std::int32_t, kStride> x{};
        for (int k = 0; k < kM; ++k)
            x[static_cast<std::size_t>(k)] = stretch(counter_p16(row_[static_cast<std::size_t>(k)]->p[n]));
        // The match model: its turn's bit at this node, as sure as matches
        // of its length have been.
        const int expect = pred_turn_ >= 0 ? kPath[static_cast<std::size_t>(pred_turn_)][static_cast<std::size_t>(n)] : -1;
        const int lb = step_len_bucket(m_.len);
        std::uint32_t* mm = expect >= 0 ? &match_[lb][n] : nullptr;
        if (mm) {
            const std::int32_t st = stretch(counter_p16(*mm));
            x[kM] = expect ? st : -st;
        } else {
            x[kM] = 0;
        }
        x[kM + 1] = 256;
        // Model byte 6: a fast counter of the DSS weight set's selector and
        // the last code.
        if constexpr (Dss) x[kM + 2] = stretch(counter_p16(fast_row_[n]));
        const int mstate = expect < 0 ? 0 : 1 + expect + 2 * std::min(lb >> 3, 2);
        std::int32_t* w1 = weight_set(static_cast<std::size_t>(n * 7 + mstate));
        std::int32_t* w2 = Light ? w1 : weight_set(static_cast<std::size_t>(kNodes * 7 + n * 64 + (turns_ & 63)));
        // Model byte 6: a third set by the DSS (dss_select()), weighted double.
        std::int32_t* w3 = Dss ? weight_set(kNodes * 7 + kNodes * 64 + static_cast<std::size_t>(n) * kDssSets + dss_sel_) : w1;
        const std::int32_t s1 = dot(w1, x), s2 = Light ? s1 : dot(w2, x), s3 = Dss ? dot(w3, x) : s1;
        std::int32_t p;
        if constexpr (Light) {
            p = mixdetail::squash_within(s1);  // (dot() clamps to +-2047)
        } else {
            const std::int32_t s = Dss ? (s1 + s2 + 2 * s3) >> 2 : (s1 + s2) >> 1;
            const std::int32_t a1 = apm1_.refine(s, static_cast<std::size_t>(n) * 512 + (turns_ & 511));
            const std::size_t row2 = (static_cast<std::size_t>(n) * 2 * 24 + (expect < 0 ? 0 : 24 * expect) +
                                      static_cast<std::size_t>(lb)) * 2 + (expect >= 0 ? 1u : 0u);
            const std::int32_t a2 = apm2_.refine(s, row2);
            p = (a1 + a2) >> 1;
        }
        const int bit = code_bit_p(io, std::clamp(p, 32, 65535 - 32), want);
        train(w1, x, mixdetail::squash_within(s1), bit);
        if constexpr (!Light) {
            train(w2, x, mixdetail::squash_within(s2), bit);
            if constexpr (Dss) train(w3, x, mixdetail::squash_within(s3), bit);
            apm1_.update(bit);
            apm2_.update(bit);
        }
        for (int k = 0; k < kM; ++k) counter_update(row_[static_cast<std::size_t>(k)]->p[n], bit);
        if (mm) counter_update(*mm, bit == expect);
        if constexpr (Dss) counter_update<kFastLimit>(fast_row_[n], bit);
        return bit;
    }

    // Weight set `s`, every weight kInitWeight when first used (model byte
    // 6 has 3689 sets, a small block uses few).
    std::int32_t* weight_set(std::size_t s) {
        std::int32_t* w = &weights_[s * kStride];
        if (!ready_[s]) {
            std::fill(w, w + kStride, kInitWeight);
            ready_[s] = 1;
        }
        return w;
    }

    static std::int32_t dot(const std::int32_t* w, const std::array<std::int32_t, kStride>& x) {
        return set_output<kStride>(w, x.data(), kIn);
    }
    static void train(std::int32_t* w, const std::array<std::int32_t, kStride>& x, std::int32_t out, int bit) {
        train_set<kStride>(w, x.data(), out, bit, kIn);
    }

    // The hashed contexts of a step (docs/FORMAT.md 1.11.2) after the turns
    // `lo` (latest lowest) and `hi`, the last step `prev` and the walk `w`,
    // with the match predicting `pred` after `mlen` right symbols: emit(i,
    // hash of model k) for each model k used, i its index among them. Model
    // kPredModel alone reads pred and mlen.
    static constexpr int kPredModel = 9;
    // Model kPredModel's value: the predicted symbol, the match length's
    // bucket and the last two turns of `lo`.
    static std::uint64_t pred_context(int pred, std::uint64_t mlen, std::uint64_t lo) {
        return ctx_join(static_cast<std::uint64_t>(pred + 1) << 5 | static_cast<std::uint64_t>(step_len_bucket(mlen)),
                        lo & 63);
    }
    static constexpr int slot_of(int k) {
        if constexpr (Dss) return k;
        if constexpr (!Light) return k < kModels ? k : -1;
        for (std::size_t i = 0; i < kLightSet.size(); ++i)
            if (kLightSet[i] == k) return static_cast<int>(i);
        return -1;
    }
    template <class Emit>
    [[gnu::always_inline]] static void context_hashes(int prev, std::uint64_t lo, std::uint64_t hi, const StepWalk& w,
                                                      const DssWord& dss, int pred, std::uint64_t mlen, Emit&& emit) {
        const auto p = static_cast<std::uint64_t>(prev);
        auto order = [&](int n) -> std::uint64_t {  // the last n turns (n <= 24)
            if (n <= 21) return lo & ((std::uint64_t{1} << (3 * n)) - 1);
            return ctx_join(lo & ((std::uint64_t{1} << 63) - 1), hi & ((std::uint64_t{1} << (3 * (n - 21))) - 1));
        };
        // (the value of a model not used is never computed)
        auto set = [&]<int M>(std::integral_constant<int, M>, auto value) {
            if constexpr (slot_of(M) >= 0) emit(slot_of(M), hash_ctx(M, value()));
        };
        using std::integral_constant;
        set(integral_constant<int, 0>{}, [&] { return p << 3 | order(1); });
        set(integral_constant<int, 1>{}, [&] { return p << 9 | order(3); });
        set(integral_constant<int, 2>{}, [&] { return order(6); });
        set(integral_constant<int, 3>{}, [&] { return order(8); });
        set(integral_constant<int, 4>{}, [&] { return order(12); });
        set(integral_constant<int, 5>{}, [&] { return order(16); });
        set(integral_constant<int, 6>{}, [&] { return order(24); });
        // The digital straight segment being drawn: the current run and the
        // runs and turns before it (a DSS is two run lengths).
        set(integral_constant<int, 7>{}, [&] {
            return ctx_join(ctx_join(p, static_cast<std::uint64_t>(std::min(w.run, 63))), w.runs & 0xFFFFFFu);
        });
        // Closure: where the chain's start lies.
        set(integral_constant<int, 8>{}, [&] { return ctx_join(w.where(), p << 3 | order(1)); });
        // The match's predicted symbol, its length and the last turns.
        if constexpr (!std::is_same_v<std::decay_t<Emit>, SkipPred>)
            set(integral_constant<int, kPredModel>{}, [&] { return pred_context(pred, mlen, lo); });
        // The position relative to the chain's start, finer (clamped to 64).
        set(integral_constant<int, 10>{}, [&] {
            const std::int64_t cx = std::clamp<std::int64_t>(w.dx, -64, 64), cy = std::clamp<std::int64_t>(w.dy, -64, 64);
            return ctx_join(static_cast<std::uint64_t>((cx + 64) * 129 + cy + 64), p << 6 | order(2));
        });
        // Model byte 6: the longest DSS ending here (dss_value()), with the
        // last turn, and with the runs of model 7.
        if constexpr (Dss) {
            const std::uint64_t dv = dss_value(dss, prev);
            set(integral_constant<int, 11>{}, [&] { return ctx_join(dv, order(1)); });
            set(integral_constant<int, 12>{}, [&] {
                return ctx_join(ctx_join(dv, static_cast<std::uint64_t>(std::min(w.run, 63))), w.runs & 0xFFFFu);
            });
        }
    }

    // The contexts of the next step, their rows prefetched. When the step
    // before was the one prefetch_after() guessed, its hashes (all but the
    // match model's) are those it made, rows fetched already.
    [[gnu::always_inline]] void contexts(int pred) {
        if (ahead_sym_ >= 0) {
            hash_ = ahead_;
            if constexpr (slot_of(kPredModel) >= 0) {
                const std::uint64_t h = hash_ctx(kPredModel, pred_context(pred, m_.len, turns_));
                hash_[static_cast<std::size_t>(slot_of(kPredModel))] = h;
                rows_.prefetch(h);
            }
            return;
        }
        context_hashes(prev_, turns_, turns_hi_, w_, dss_word(), pred, m_.len, [this](int k, std::uint64_t h) {
            hash_[static_cast<std::size_t>(k)] = h;
            rows_.prefetch(h);
        });
    }

    // The rows the step after this one reads if this one is `sym`,
    // prefetched while this one is coded: a row is a cache miss, and the
    // contexts are known only a few instructions before it is read. The
    // decoder guesses straight on (most steps are); the encoder knows. The
    // match model's context, unknown yet, is left out.
    // Their hashes are kept for the next step's contexts() (ahead_).
    struct SkipPred {
        const RowTable* rows;
        std::array<std::uint64_t, kM>* keep;
        void operator()(int k, std::uint64_t h) const {
            (*keep)[static_cast<std::size_t>(k)] = h;
            rows->prefetch(h);
        }
    };
    [[gnu::always_inline]] void prefetch_after(int sym) {
        const auto turn = static_cast<std::uint64_t>((sym - prev_) & 7);
        StepWalk w = w_;
        if constexpr (!Light) w.step(sym, static_cast<unsigned>(turn));  // (as in note_turn())
        // (a step that ends the DSS word: its hashes are made again after it)
        DssWord d = dss_word();
        const bool ends_word = Dss && (d.len >= DssSuffix::kCap - 1 || !d.push(sym));
        context_hashes(sym, (turns_ << 3) | turn, (turns_hi_ << 3) | ((turns_ >> 60) & 7), w, d, -1, 0,
                       SkipPred{&rows_, &ahead_});
        ahead_sym_ = ends_word ? -1 : sym;
    }

    [[gnu::always_inline]] void note_turn(int sym) {
        const auto turn = static_cast<unsigned>((sym - prev_) & 7);
        turns_hi_ = (turns_hi_ << 3) | ((turns_ >> 60) & 7);  // the turn leaving turns_
        turns_ = (turns_ << 3) | turn;
        if constexpr (!Light) w_.step(sym, turn);  // (the light models do not read the walk)
        if constexpr (Dss) {
            dss_.push(sym);
            box_ = {std::min(box_[0], w_.dx), std::max(box_[1], w_.dx), std::min(box_[2], w_.dy), std::max(box_[3], w_.dy)};
        }
        prev_ = sym;
    }
    const DssWord& dss_word() const {
        if constexpr (Dss) return dss_.word();
        static const DssWord none;
        return none;
    }

    Io& io_;
    RowTable rows_;
    Apm apm1_, apm2_;
    std::array<std::int32_t, kSets * kStride> weights_;  // (filled by weight_set())
    std::array<std::uint8_t, kSets> ready_{};
    std::array<std::uint64_t, kM> hash_{};
    std::array<std::uint64_t, kM> ahead_{};  // the hashes prefetch_after() made
    int ahead_sym_ = -1;                      // for a next step of this code (-1: none)
    std::array<Row*, kM> row_{};
    std::uint32_t match_[24][kNodes];
    Prob end_[3][2][2];
    UIntModel start_[2];
    Prob start_hit_[24];
    std::unique_ptr<StepHistory> own_;
    StepHistory& h_;
    StepMatch m_;
    int prev_ = 0;
    int pred_turn_ = -1;
    std::uint64_t turns_ = 0;     // turns, 3 bits each, latest lowest (across chains)
    std::uint64_t turns_hi_ = 0;  // the turns before those (turns_ holds 21 whole ones)
    StepWalk w_;
    DssSuffix dss_;           // model byte 6 only
    std::size_t dss_sel_ = 0;  // its weight set's index (dss_select())
    std::unique_ptr<StartModel> starts_;  // model byte 6 only
    std::vector<std::uint32_t> fast_ = std::vector<std::uint32_t>(Dss ? kDssSets * 8 * kNodes : 0, kCounterInit);
    std::uint32_t* fast_row_ = nullptr;  // the step's fast counters (one per node)
    StartModel::Before before_;           // the chain before, for starts_
    std::array<std::int64_t, 4> box_{};   // the chain's box so far: x min, max, y min, max (from its start)
};

}  // namespace

namespace {

// The row table's cap of model byte `model`.
int max_row_bits_of(unsigned model) { return model == kMixedStepCmLightSmall ? kLightSmallRowBits : kMaxRowBits; }

// (`model`: the model byte, one of K's)
template <CmKind K>
std::string write_cm(const Block& block, const WindowView* window, unsigned model) {
    if (block.axes != 2) return {};
    CmCounts c;
    c.nchains = block.chains.size();
    for (const Chain& ch : block.chains) c.nsteps += ch.steps.size();
    std::string out;
    put_u8(out, model);
    put_varint(out, c.nchains);
    put_varint(out, c.nsteps);
    put_layout(out, block.layout);
    EncIo io;
    auto coder = std::make_unique<CmStepCoder<EncIo, K>>(io, c, nullptr, max_row_bits_of(model));
    if (window) coder->prime(*window);
    if (!encode_step_chains(*coder, block, c)) return {};
    out += io.rc.finish();
    return out;
}

}  // namespace

std::string write_cm_step_model(const Block& block, const WindowView* window, unsigned model) {
    if (model == kMixedStepCm) return write_cm<CmKind::full>(block, window, model);
    if (model == kMixedStepCmDss) return write_cm<CmKind::dss>(block, window, model);
    return {};
}

std::string write_light_cm_step_model(const Block& block, const WindowView* window, unsigned model) {
    if (model != kMixedStepCmLight && model != kMixedStepCmLightSmall) return {};
    return write_cm<CmKind::light>(block, window, model);
}

Result<void> read_cm_step_model(std::string_view payload, int axes, bool expand, Block& out, BlockCounts& counts,
                                const std::string& where, const WindowView* window, StepHistory* running) {
    Cursor cur(payload);
    if (axes != 2)
        return make_error(Errc::corrupt, where + " byte 0: step-model block on " + std::to_string(axes) + " axes");
    unsigned kind;
    if (!cur.u8(kind) || !is_cm_step_model(kind))
        return make_error(Errc::corrupt, where + " byte 0: not a context-mixing step model");
    CmCounts c;
    if (!cur.varint(c.nchains) || !cur.varint(c.nsteps))
        return make_error(Errc::corrupt, where + " byte " + std::to_string(cur.pos()) + ": bad payload header");
    if (c.nchains > kMaxBlockChains || c.nsteps > kMaxBlockSteps)
        return make_error(Errc::limit, where + " byte 0: payload declares more chains or steps than the limits");
    auto layout = get_layout(cur, where);
    if (!layout) return std::move(layout).error();
    const std::size_t base = cur.pos();
    DecIo io(payload.substr(base));
    auto run = [&](auto& coder) {
        if (window && !running) coder.prime(*window);
        start_output(out, expand, axes, std::move(*layout));
        return decode_step_chains(coder, io, c, expand, out, counts, base, where);
    };
    StepHistory* shared = window ? running : nullptr;
    if (kind == kMixedStepCmLight || kind == kMixedStepCmLightSmall) {
        auto coder = std::make_unique<CmStepCoder<DecIo, CmKind::light>>(io, c, shared, max_row_bits_of(kind));
        return run(*coder);
    }
    if (kind == kMixedStepCmDss) {
        auto coder = std::make_unique<CmStepCoder<DecIo, CmKind::dss>>(io, c, shared);
        return run(*coder);
    }
    auto coder = std::make_unique<CmStepCoder<DecIo, CmKind::full>>(io, c, shared);
    return run(*coder);
}

}  // namespace stepzip::stz
