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
#include "step_history.hpp"

namespace stepzip::stz {

namespace {

constexpr int kMaxStepOrder = 4;  // previous turns in the direction context

int cap(int v, int hi) { return v < hi ? v : hi; }
int len_bucket(std::uint64_t len) { return step_len_bucket(len); }

struct StepContexts {
    Prob turn[4096][8];  // ctx: previous `order` turns (order 0..4)
    Prob end[4];         // ctx: (at start point) + 2 * (no step yet)
    Prob hit[24][2];     // ctx: length bucket x (predicted end)
    UIntModel start[2];
    Prob start_hit[24];  // version 2: chain start as the match predicts, ctx length bucket
};

using Counts = StepCounts;

}  // namespace

void StepHistoryDeleter::operator()(StepHistory* h) const { delete h; }
StepHistoryPtr make_step_history() { return StepHistoryPtr(new StepHistory); }
void step_history_add(StepHistory& h, const WindowBlock& b) { h.add(b); }
void step_history_begin_block(StepHistory& h, std::uint64_t window_start, std::uint64_t limit) {
    h.begin_block(window_start, limit);
}
std::uint64_t step_history_end(const StepHistory& h) { return h.base + h.size(); }

namespace {

template <class Io>
class StepCoder : public StepCoderShell<StepCoder<Io>, Io> {
    friend class StepCoderShell<StepCoder<Io>, Io>;

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

    Point start(const Point& want) {
        w_.start_chain();
        io_.field(3);
        return code_step_start(io_, h_, m_, ctx_->start, ctx_->start_hit, predict_starts_, want);
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
            const int pred = m_.predicted(h_);
            if constexpr (kMixedIo<I>) symbol_contexts(io, pred);
            bool hit = false;
            io.field(0);
            if (pred >= 0) hit = io.bit(ctx_->hit[len_bucket(m_.len)][pred == kEndSymbol], want == pred);
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
                w_.step(sym, turn);
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
                                    static_cast<std::uint64_t>(len_bucket(m_.len)) << 3 | (history_ & 7)));
        // The digital straight segment being drawn: the current run of one
        // direction and the runs and turns before it.
        mix_context(io, 3, ctx_join(ctx_join(p, static_cast<std::uint64_t>(cap(w_.run, 31))), w_.runs & 0xFFFFFFu));
        // Closure: where the chain start lies.
        const std::uint64_t where = w_.where();
        mix_context(io, 4, ctx_join(ctx_join(p, where), history_ & 7));
        mix_context(io, 5, ctx_join(ctx_join(p, history_ & 0x1FFu),
                                    static_cast<std::uint64_t>(cap(bit_length(w_.in_chain), 15))));
        if (curve_) {
            // The match's predicted symbol under three turns, and under how
            // the runs grow or shrink (the two runs and turns before).
            const auto q = static_cast<std::uint64_t>(pred + 1);
            mix_context(io, 6, ctx_join(ctx_join(ctx_join(p, history_ & 0x1FFu), q),
                                        static_cast<std::uint64_t>(len_bucket(m_.len))));
            const int r1 = static_cast<int>((w_.runs >> 3) & 31), r2 = static_cast<int>((w_.runs >> 11) & 31);
            const int t1 = static_cast<int>(w_.runs & 7), t2 = static_cast<int>((w_.runs >> 8) & 7);
            const std::uint64_t c = static_cast<std::uint64_t>(std::clamp(w_.run - r1, -3, 3) + 3) * 8 +
                                    static_cast<std::uint64_t>(std::clamp(r1 - r2, -3, 3) + 3);
            mix_context(io, 7, ctx_join(ctx_join(ctx_join(ctx_join(p, c), static_cast<std::uint64_t>(t1 * 8 + t2)),
                                                 static_cast<std::uint64_t>(cap(bit_length(static_cast<std::uint64_t>(r1)), 5))),
                                        q));
        }
    }

    void push(int sym) { m_.push(h_, sym); }

    Io& io_;
    std::unique_ptr<StepContexts> ctx_;
    unsigned mask_;
    bool predict_starts_;
    std::unique_ptr<StepHistory> own_;
    StepHistory& h_;
    StepMatch m_;
    int prev_ = 0;
    unsigned turns_ = 0;
    // Mixed predictions only (block type 6).
    std::unique_ptr<MixPredictor> mixer_;
    std::uint64_t history_ = 0;  // turns, 3 bits each, latest lowest (across chains)
    StepWalk w_;
    bool curve_ = false;
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
    if (!encode_step_chains(coder, block, c)) return {};
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
    return decode_step_chains(coder, io, c, expand, out, counts, base, where);
}

}  // namespace

Result<void> read_step_model(std::string_view payload, int axes, bool expand, Block& out,
                             BlockCounts& counts, const std::string& where, const WindowView* window,
                             int version, StepHistory* running, bool mixed) {
    if (mixed && !payload.empty() && is_cm_step_model(static_cast<unsigned char>(payload[0])))
        return read_cm_step_model(payload, axes, expand, out, counts, where, window, running);
    if (mixed)
        return read_step_model_with<MixDecIo>(payload, axes, expand, out, counts, where, window, version, running);
    return read_step_model_with<DecIo>(payload, axes, expand, out, counts, where, window, version, running);
}

}  // namespace stepzip::stz
