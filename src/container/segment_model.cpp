// Segment-model blocks (docs/FORMAT.md "Segment model"): each chain as a
// start delta and its segments, coded by the adaptive binary range coder
// with contexts taken from the previous segment, plus a match model over
// whole items (chain starts, segments, chain ends) that finds repeated
// strokes anywhere earlier in the block.
// One template (SegmentCoder<Io>) runs both directions, so the encoder and
// the decoder cannot disagree on a context.
// Complexity: O(axes) range-coder bits per segment (a few tens), O(1) table
// work per item; memory O(items) plus fixed context tables (~300 KiB).
#include <zstd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <numeric>
#include <optional>

#include "bench_hooks.hpp"
#include "mix.hpp"
#include "modeled_block.hpp"
#include "mtf_list.hpp"
#include "segment_fields.hpp"
#include "range_coder.hpp"
#include "timed_block.hpp"
#include "timed_phase.hpp"

namespace stepzip::stz {

namespace {

// 2D octants as in the record layout (docs/FORMAT.md): indexed by
// lead * 4 + negmask, and back.
constexpr int kOctantOf[8] = {0, 3, 7, 4, 1, 2, 6, 5};
constexpr int kCodeOfOctant[8] = {0, 4, 5, 1, 3, 7, 6, 2};

enum Kind : std::uint8_t { kStart = 0, kSeg = 1, kEnd = 2 };

// One coded item. For a segment, `phase` holds the phases of its
// non-degenerate functions and 0 elsewhere (a canonical form for equality).
struct Item {
    Kind kind = kEnd;
    Point delta{};
    std::array<std::int64_t, kMaxAxes - 1> phase{};
    std::uint64_t hash = 0;
    bool operator==(const Item& o) const {
        return kind == o.kind && delta == o.delta && phase == o.phase;
    }
};

std::uint64_t mix(std::uint64_t h, std::uint64_t v) {
    h ^= v + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    return h * 0xBF58476D1CE4E5B9ull;
}

// A hash of the item (for finding known segments; not part of the format).
void seal(Item& it) {
    std::uint64_t h = it.kind;
    for (int i = 0; i < kMaxAxes; ++i) h = mix(h, static_cast<std::uint64_t>(it.delta[i]));
    for (auto ph : it.phase) h = mix(h, static_cast<std::uint64_t>(ph));
    it.hash = h;
}

int cap(int v, int hi) { return v < hi ? v : hi; }


// Match-length bucket: 0..15 as is, then one bucket per power of two, up to 23.
int len_bucket(std::uint64_t len) {
    if (len < 16) return static_cast<int>(len);
    return cap(16 + bit_length(len) - 5, 23);
}


struct Contexts {
    Prob turn[32][8];        // 2D: octant turn, ctx prev turn x prev-L class
    Prob dir_same[2];        // N-D: same direction as the previous segment
    Prob dir_tree[512];      // N-D: (lead << 6 | negmask), 9-bit tree
    UIntModel lead[24];      // L - 1, ctx bit_length(prev L) (cap 11) x (turn != 0)
    UIntModel minor[12];     // S - prediction, ctx bit_length(L) (cap 11)
    UIntModel phase[12];     // phase - default, ctx bit_length(L) (cap 11)
    UIntModel start[kMaxAxes][8];  // chain start - previous end, per axis x size class
    Prob end[8];             // end of chain, ctx (at start point) x segments so far
    Prob hit[24][3];         // match hit, ctx length bucket x predicted kind
    Prob succ_in[4][2];      // segment followed the previous one before, ctx list size x previous was
    UIntModel succ_rank[4];  // which one, ctx list size
    Prob known[2];           // segment is in the recent-shapes list, ctx previous one was
    UIntModel rank[8];       // its rank, ctx bit_length(previous rank) (cap 7)
};


constexpr std::size_t kShapes = 1024;    // recent distinct segments, most recent first
constexpr std::size_t kSuccessors = 8;  // segments seen after a given segment

struct Counts {
    std::uint64_t nchains = 0, nsegments = 0, nsteps = 0;
    std::uint64_t seen_segments = 0, seen_steps = 0;
};

constexpr std::uint32_t kNone = 0xFFFFFFFFu;

// The recent-shapes list (move to front, at most kShapes entries) kept as
// last-use times: a shape's rank is the number of listed shapes used after
// it, counted in a Fenwick tree over a window of kWindow times; when the
// window is used up, the listed shapes are renumbered 1..size in the same
// order. Same answers as the list.
// Complexity: O(log kWindow) per rank, lookup or use; amortized O(1) renumbering.
class RecentShapes {
public:
    std::size_t size() const { return size_; }

    // Rank of `id` (0 = most recent), or kNone when it is not listed.
    std::uint32_t rank(std::uint32_t id) const {
        const std::uint32_t t = id < time_of_.size() ? time_of_[id] : 0;
        if (t == 0) return kNone;
        return static_cast<std::uint32_t>(size_) - prefix(t);
    }
    // The shape of rank r < size().
    std::uint32_t at(std::size_t r) const { return id_at_[nth(static_cast<std::uint32_t>(size_ - r))]; }

    // Moves `id` to the front (inserting it, and dropping the least recent
    // shape when the list is full).
    void use(std::uint32_t id) {
        if (id >= time_of_.size()) time_of_.resize(std::max<std::size_t>(id + 1, time_of_.size() * 2), 0);
        if (clock_ == kWindow) renumber();
        std::uint32_t& t = time_of_[id];
        if (t != 0) {
            add(t, -1);
        } else if (size_ == kShapes) {
            const std::uint32_t oldest = nth(1);
            add(oldest, -1);
            time_of_[id_at_[oldest]] = 0;
        } else {
            ++size_;
        }
        t = ++clock_;
        id_at_[t] = id;
        add(t, +1);
    }

private:
    static constexpr std::uint32_t kWindow = 4096;  // a power of two, at least 2 * kShapes

    void add(std::uint32_t t, int d) {
        for (; t <= kWindow; t += t & (0u - t)) tree_[t] = static_cast<std::uint16_t>(tree_[t] + d);
    }
    std::uint32_t prefix(std::uint32_t t) const {
        std::uint32_t s = 0;
        for (; t != 0; t &= t - 1) s += tree_[t];
        return s;
    }
    // Smallest time t with prefix(t) == k (1 <= k <= size).
    std::uint32_t nth(std::uint32_t k) const {
        std::uint32_t t = 0;
        for (std::uint32_t step = kWindow; step != 0; step >>= 1)
            if (t + step <= kWindow && tree_[t + step] < k) {
                t += step;
                k -= tree_[t];
            }
        return t + 1;
    }
    void renumber() {
        std::uint32_t n = 0;
        for (std::uint32_t t = 1; t <= kWindow; ++t) {
            const std::uint32_t id = id_at_[t];
            if (time_of_[id] == t) {
                time_of_[id] = ++n;
                id_at_[n] = id;
            }
        }
        tree_.fill(0);
        for (std::uint32_t t = 1; t <= kWindow; ++t) {  // linear Fenwick build: times 1..n set
            if (t <= n) tree_[t] = static_cast<std::uint16_t>(tree_[t] + 1);
            const std::uint32_t up = t + (t & (0u - t));
            if (up <= kWindow) tree_[up] = static_cast<std::uint16_t>(tree_[up] + tree_[t]);
        }
        clock_ = n;
    }

    std::array<std::uint16_t, kWindow + 1> tree_{};  // Fenwick tree over times 1..kWindow
    std::array<std::uint32_t, kWindow + 1> id_at_{};  // shape last used at each time
    std::vector<std::uint32_t> time_of_;              // listed shape -> its time; 0: not listed
    std::uint32_t clock_ = 0;
    std::size_t size_ = 0;
};

// Shapes that followed a shape (move to front, at most kSuccessors).
using Successors = MtfList<kSuccessors>;

// Open-addressing hash table from a 64-bit key to a nonzero 32-bit value
// (0: absent). Grows at half load.
class FlatMap {
public:
    FlatMap() : slots_(std::size_t{1} << 10) {}
    // The value stored under `key` (0: none); stores `value` in its place.
    std::uint32_t exchange(std::uint64_t key, std::uint32_t value) {
        if ((used_ + 1) * 2 > slots_.size()) grow();
        Slot& s = find(slots_, key);
        const std::uint32_t before = s.value;
        if (before == 0) ++used_;
        s.key = key;
        s.value = value;
        return before;
    }

private:
    struct Slot {
        std::uint64_t key = 0;
        std::uint32_t value = 0;
    };
    static Slot& find(std::vector<Slot>& slots, std::uint64_t key) {
        const std::size_t mask = slots.size() - 1;
        std::size_t i = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 32) & mask;
        while (slots[i].value != 0 && slots[i].key != key) i = (i + 1) & mask;
        return slots[i];
    }
    void grow() {
        std::vector<Slot> old(slots_.size() * 2);
        old.swap(slots_);
        for (const Slot& s : old)
            if (s.value != 0) find(slots_, s.key) = s;
    }
    std::vector<Slot> slots_;
    std::size_t used_ = 0;
};

template <class Io>
class SegmentCoder {
public:
    SegmentCoder(Io& io, Profile p, int axes, TimedPrediction timed = TimedPrediction::none)
        : io_(io), p_(p), axes_(axes), timed_(timed), ctx_(std::make_unique<Contexts>()), shape_index_(1024, 0) {
        succ_.resize(1);  // succ_[0]: after no segment
        if constexpr (kMixedIo<Io>) {
            static_assert(sizeof(Contexts) % sizeof(Prob) == 0);
            curve_ = io_.curvature;
            mixer_ = std::make_unique<MixPredictor>(reinterpret_cast<const Prob*>(ctx_.get()),
                                                    curve_ ? kMixMaxModels : kMixBaseModels);
            io_.m = mixer_.get();
        }
    }

    void set_grid(std::int64_t g) { grid_ = g; }

    // Starts the block from the window (docs/FORMAT.md "Window"): every item
    // of the window's segment-model blocks, in order, enters the history,
    // the match table and the shape lists as if it had been coded; the
    // match and the coding contexts stay as at a block's start.
    void prime(const WindowView& window) {
        for (const auto& b : window) {
            const SegmentItems& w = b->items;
            if (w.arcs) continue;  // a table block with arcs: table-block windows only
            std::size_t k = 0;
            for (std::size_t c = 0; c < w.starts.size(); ++c) {
                push(kStartTag | static_cast<std::uint32_t>(starts_.size()), false);
                starts_.push_back(w.starts[c]);
                prev_shape_ = kNone;
                for (std::uint32_t n = 0; n < w.counts[c]; ++n, ++k) {
                    const Item it = item_of(w.segments[k]);
                    std::uint32_t id = find_shape(it);
                    if (id == kNewShape) id = add_shape(it);
                    note_shape(id);
                    push(id, false);
                }
                push(kEndId, false);
            }
        }
        ptr_ = -1;
        len_ = 0;
        prev_shape_ = kNone;
    }

    // Codes a chain start delta (encoder: `want`); returns it.
    Point start(const Point& want) {
        const std::uint32_t pred = predicted(kStart);
        tphase_.reset();
        rates_.reset();
        from_start_ = Point{};
        if constexpr (kMixedIo<Io>) item_contexts(kStart, pred, 0);
        bool hit = false;
        io_.field(0);
        if (pred != kNoPrediction) hit = code_hit(kStart, want == starts_[pred & ~kStartTag]);
        io_.field(1);
        Point delta{};
        std::int64_t last_v = 0;
        if (hit) {
            delta = starts_[pred & ~kStartTag];
            prev_start0_ = delta[0] / grid_;
        } else {
            for (int i = 0; i < axes_; ++i) {
                // Context: size class of the axis coded before (axis 0: of the
                // previous chain's axis-0 value).
                const std::uint64_t before = stz::magnitude(i == 0 ? prev_start0_ : last_v);
                const std::int64_t v = code_sint(io_, ctx_->start[i][cap(bit_length(before), 7)], want[i] / grid_);
                last_v = v;
                if (i == 0) prev_start0_ = v;
                // wrapping: the start is checked once it is rebuilt
                delta[i] = static_cast<std::int64_t>(static_cast<std::uint64_t>(v) * static_cast<std::uint64_t>(grid_));
            }
        }
        prev_shape_ = kNone;
        const std::uint32_t id = kStartTag | static_cast<std::uint32_t>(starts_.size());
        starts_.push_back(delta);
        push(id, pred != kNoPrediction && starts_[pred & ~kStartTag] == delta);
        return delta;
    }

    // Codes what follows in a chain: a segment (returns true, `seg` set) or
    // the chain's end (false). `want` is the encoder's segment or nullptr at
    // the end. Decoder errors set io.failed or `error_`.
    bool next(const Segment* want, bool at_start_point, std::uint64_t in_chain, const Counts& c,
              Segment& seg) {
        const std::uint32_t pred = predicted(kSeg);
        if (c.seen_steps == c.nsteps || c.seen_segments == c.nsegments) {
            push(kEndId, pred == kEndId);  // forced end: no bits
            return false;
        }
        // Encoder: the wanted item (kEndId, a known shape id, or kNewShape
        // with `w` the new shape).
        Item w;
        std::uint32_t want_id = kEndId;
        if constexpr (!Io::kDecode) {
            if (want) {
                w = item_of(*want);
                want_id = find_shape(w);
            }
        }
        if constexpr (kMixedIo<Io>) item_contexts(kSeg, pred, in_chain);
        bool hit = false;
        io_.field(2);
        if (pred != kNoPrediction) hit = code_hit(pred == kEndId ? kEnd : kSeg, want_id == pred);
        std::uint32_t id = kEndId;
        bool coded_in_full = false;
        if (hit) {
            id = pred;
        } else {
            bool end = false;
            io_.field(3);
            if (pred != kEndId)
                end = io_.bit(ctx_->end[(at_start_point ? 4 : 0) + cap(static_cast<int>(in_chain), 3)],
                              want_id == kEndId);
            if (!end) {
                io_.field(8);
                id = code_shape(want_id);
                if (io_.failed) return fail("bad shape rank");
                if (id == kNewShape) {
                    if (!code_segment(want, seg)) return false;
                    coded_in_full = true;
                    if constexpr (Io::kDecode) {
                        w = item_of(seg);
                        id = find_shape(w);
                    } else {
                        id = want_id;
                    }
                }
            }
        }
        if (id == kEndId) {
            push(kEndId, pred == kEndId);
            return false;
        }
        if (id == kNewShape) id = add_shape(w);
        if (!coded_in_full) segment_of(uniq_[id], seg);
        note_segment(seg);
        note_shape(id);
        push(id, pred == id);
        return true;
    }

    const std::string& error() const { return error_; }

private:
    // History entries: a segment's shape id, kEndId, or kStartTag | chain
    // index (its delta in starts_). As a match context a chain start is
    // kStartTag whatever its delta, so a repeated chain is found after its
    // first segment wherever it starts.
    static constexpr std::uint32_t kEndId = 0xFFFFFFFFu, kStartTag = 0x80000000u;
    // Not a history entry: no prediction; a shape that is not known yet.
    static constexpr std::uint32_t kNoPrediction = 0xFFFFFFFEu, kNewShape = 0xFFFFFFFDu;
    static_assert(kNone == kEndId);  // prev_shape_ "none" is succ_[0]

    static bool is_start(std::uint32_t id) { return id != kEndId && (id & kStartTag); }

    // Index of a known segment (kNewShape if new).
    std::uint32_t find_shape(const Item& it) const {
        const std::size_t mask = shape_index_.size() - 1;
        for (std::size_t i = static_cast<std::size_t>(it.hash >> 20) & mask; shape_index_[i] != 0; i = (i + 1) & mask) {
            const std::uint32_t id = shape_index_[i] - 1;
            if (uniq_[id].hash == it.hash && uniq_[id] == it) return id;
        }
        return kNewShape;
    }

    std::uint32_t add_shape(const Item& it) {
        const auto id = static_cast<std::uint32_t>(uniq_.size());
        uniq_.push_back(it);
        succ_.emplace_back();
        if (uniq_.size() * 2 > shape_index_.size()) {
            shape_index_.assign(shape_index_.size() * 2, 0);
            for (std::uint32_t k = 0; k < uniq_.size(); ++k) index_shape(k);
        } else {
            index_shape(id);
        }
        return id;
    }
    void index_shape(std::uint32_t id) {
        const std::size_t mask = shape_index_.size() - 1;
        std::size_t i = static_cast<std::size_t>(uniq_[id].hash >> 20) & mask;
        while (shape_index_[i] != 0) i = (i + 1) & mask;
        shape_index_[i] = id + 1;
    }

    // Codes whether the segment is one that followed the previous segment
    // before (and which), else one of the recent segments (and which);
    // returns its index, or kNewShape. Encoder: `want` is the shape's id
    // (kNewShape: not known).
    std::uint32_t code_shape(std::uint32_t want) {
        const Successors& list = succ_[prev_shape_ + 1];
        if (list.size != 0) {
            std::size_t r = 0;
            if constexpr (!Io::kDecode)
                while (r < list.size && list.id[r] != want) ++r;
            const int size_class = cap(static_cast<int>(list.size) - 1, 3);
            if (io_.bit(ctx_->succ_in[size_class][prev_succ_], r < list.size)) {
                prev_succ_ = 1;
                r = code_uint(io_, ctx_->succ_rank[size_class], r);
                if (r >= list.size) {
                    io_.failed = true;
                    return kNewShape;
                }
                return list.id[r];
            }
        }
        prev_succ_ = 0;
        std::size_t r = 0;
        if constexpr (!Io::kDecode) r = want == kNewShape ? kNone : recent_.rank(want);
        const bool known = io_.bit(ctx_->known[prev_known_], r < recent_.size());
        prev_known_ = known;
        if (!known) return kNewShape;
        r = code_uint(io_, ctx_->rank[cap(bit_length(prev_rank_), 7)], r);
        if (r >= recent_.size()) {
            io_.failed = true;
            return kNewShape;
        }
        prev_rank_ = r;
        return recent_.at(r);
    }

    void note_shape(std::uint32_t id) {
        shape2_ = shape1_;
        shape1_ = id;
        recent_.use(id);
        succ_[prev_shape_ + 1].use(id);
        prev_shape_ = id;
    }

    Item item_of(const Segment& s) const {
        Item it;
        it.kind = kSeg;
        it.delta = s.delta;
        for (int j = 0; j < phase_count(p_, axes_); ++j) {
            const auto ab = *phase_arguments(p_, s, axes_, j);
            const PhaseRange r = phase_range(p_, ab.first, ab.second);
            if (r.hi - r.lo != 1) it.phase[j] = s.phase[j];
        }
        seal(it);
        return it;
    }

    // Segment of an item from the history (valid: it was checked when coded).
    void segment_of(const Item& it, Segment& seg) const {
        seg.delta = it.delta;
        for (int j = 0; j < phase_count(p_, axes_); ++j) {
            const auto ab = *phase_arguments(p_, seg, axes_, j);
            const PhaseRange r = phase_range(p_, ab.first, ab.second);
            seg.phase[j] = r.hi - r.lo == 1 ? r.lo : it.phase[j];
        }
    }

    bool code_hit(Kind predicted_kind, bool is_hit) {
        return io_.bit(ctx_->hit[len_bucket(len_)][predicted_kind], is_hit);
    }

    // The history entry the active match predicts at a chain start (`at` ==
    // kStart) or elsewhere, or kNoPrediction.
    std::uint32_t predicted(Kind at) const {
        if (ptr_ < 0) return kNoPrediction;
        const std::uint32_t id = hist_[static_cast<std::size_t>(ptr_)];
        if ((at == kStart) != is_start(id)) return kNoPrediction;
        return id;
    }

    static std::uint32_t context_id(std::uint32_t id) { return is_start(id) ? kStartTag : id; }

    // Appends an item to the history and moves the match: a verified match
    // goes on while its predictions come true (`as_predicted`); otherwise
    // the most recent earlier position preceded by the same two items (as
    // contexts) is taken.
    void push(std::uint32_t id, bool as_predicted) {
        if (ptr_ >= 0 && as_predicted) {
            ++len_;
            ++ptr_;
        } else {
            len_ = 0;
            ptr_ = -1;
        }
        hist_.push_back(id);
        const std::size_t n = hist_.size();
        if (n >= 2) {
            const std::uint64_t key = (std::uint64_t{context_id(hist_[n - 2])} << 32) | context_id(hist_[n - 1]);
            const std::uint32_t before = table_.exchange(key, static_cast<std::uint32_t>(n));
            if (before != 0 && ptr_ < 0) ptr_ = before;
        }
    }

    void note_segment(const Segment& seg) {
        if (timed_ == TimedPrediction::since) tphase_.advance(p_, seg, axes_);
        if (timed_ == TimedPrediction::rates) rates_.advance(p_, seg, axes_);
        const int lead = leading_axis(seg.delta, axes_);
        if (axes_ == 2) {
            unsigned neg = 0;
            for (int i = 0; i < 2; ++i)
                if (seg.delta[i] < 0) neg |= 1u << i;
            const int oct = kOctantOf[lead * 4 + static_cast<int>(neg)];
            prev_turn_ = (oct - prev_oct_) & 7;
            prev_oct_ = oct;
            turn_hist_ = (turn_hist_ << 3) | static_cast<unsigned>(prev_turn_);
        } else {
            unsigned neg = 0;
            for (int i = 0; i < axes_; ++i)
                if (seg.delta[i] < 0) neg |= 1u << i;
            prev_dir_ = (static_cast<unsigned>(lead) << 6) | neg;
            prev_turn_ = 0;
            turn_hist_ = (turn_hist_ << 9) | prev_dir_;
        }
        for (int i = 0; i < axes_; ++i) from_start_[i] += seg.delta[i];
        // The segment before this one (last_oct_: its octant until here).
        before_l_ = prev_l_;
        before_s_ = prev_s_[0];
        before_oct_ = last_oct_;
        last_oct_ = prev_oct_;
        prev_phase_ = seg.phase[0];
        l_hist_ = (l_hist_ << 4) | static_cast<unsigned>(cap(bit_length(static_cast<std::uint64_t>(std::llabs(seg.delta[lead]))), 15));
        prev_l_ = std::llabs(seg.delta[lead]);
        int j = 0;
        for (int i = 0; i < axes_; ++i)
            if (i != lead) prev_s_[j++] = std::llabs(seg.delta[i]);
    }

    // The hashed contexts of the mixed predictions for the item about to be
    // coded (docs/FORMAT.md "Segment-model contexts").
    void item_contexts(Kind kind, std::uint32_t pred, std::uint64_t in_chain) {
        const std::uint64_t k = kind;
        const std::uint64_t at = static_cast<std::uint64_t>(cap(static_cast<int>(std::min<std::uint64_t>(in_chain, 15)), 15));
        mix_context(io_, 0, ctx_join(ctx_join(k, prev_shape_), static_cast<std::uint64_t>(prev_turn_)));
        mix_context(io_, 1, ctx_join(ctx_join(ctx_join(k, shape1_), shape2_), prev_shape_ == kNone));
        mix_context(io_, 2, ctx_join(ctx_join(k, pred), static_cast<std::uint64_t>(len_bucket(len_))));
        mix_context(io_, 3, ctx_join(ctx_join(k, turn_hist_ & 0x1FFFFFu), l_hist_ & 0xFFu));
        // Closure: the segment that would end the chain where it started.
        std::uint64_t close = 0;
        if (axes_ == 2) {
            Point need{};
            need[0] = -from_start_[0];
            need[1] = -from_start_[1];
            if (need[0] != 0 || need[1] != 0) {
                const int lead = leading_axis(need, 2);
                unsigned neg = 0;
                for (int i = 0; i < 2; ++i)
                    if (need[i] < 0) neg |= 1u << i;
                const int oct = kOctantOf[lead * 4 + static_cast<int>(neg)];
                const std::int64_t big = std::llabs(need[lead]), small = std::llabs(need[1 - lead]);
                close = 1 + static_cast<std::uint64_t>((oct - prev_oct_) & 7) * 64 +
                        static_cast<std::uint64_t>(cap(bit_length(static_cast<std::uint64_t>(big)), 7)) * 8 +
                        static_cast<std::uint64_t>(cap(bit_length(static_cast<std::uint64_t>(small)), 7));
            }
        } else {
            std::uint64_t sum = 0;
            for (int i = 0; i < axes_; ++i) sum += stz::magnitude(from_start_[i]);
            close = 1 + static_cast<std::uint64_t>(bit_length(sum));
        }
        mix_context(io_, 4, ctx_join(ctx_join(k, close), at));
        mix_context(io_, 5, ctx_join(ctx_join(k, prev_shape_), at));
        if (curve_) {
            // The octants and slope classes of the last two segments; their
            // leading and minor totals.
            const std::uint64_t q1 = slope_class(prev_s_[0], prev_l_), q2 = slope_class(before_s_, before_l_);
            mix_context(io_, 6, ctx_join(ctx_join(ctx_join(k, static_cast<std::uint64_t>(prev_oct_) * 64 + q1),
                                                  static_cast<std::uint64_t>(before_oct_) * 64 + q2),
                                         static_cast<std::uint64_t>(prev_turn_)));
            mix_context(io_, 7, ctx_join(ctx_join(ctx_join(ctx_join(k, static_cast<std::uint64_t>(prev_l_)),
                                                           static_cast<std::uint64_t>(prev_s_[0])),
                                                  static_cast<std::uint64_t>(before_l_)),
                                         static_cast<std::uint64_t>(before_s_)));
        }
    }
    // A segment's slope minor / leading in 32nds, rounded (0..32).
    static std::uint64_t slope_class(std::int64_t s, std::int64_t l) {
        return l <= 0 ? 0 : static_cast<std::uint64_t>((s * 32 + l / 2) / l);
    }

    bool fail(const char* what) {
        if (error_.empty()) error_ = what;
        io_.failed = true;
        return false;
    }

    // Codes the fields of a segment (encoder: *want).
    bool code_segment(const Segment* want, Segment& seg) {
        int lead = 0;
        unsigned neg = 0;
        std::int64_t l = 1;
        if (!Io::kDecode) {
            lead = leading_axis(want->delta, axes_);
            for (int i = 0; i < axes_; ++i)
                if (want->delta[i] < 0) neg |= 1u << i;
            l = std::llabs(want->delta[lead]);
        }
        int turn = 0;
        const int lclass = cap(bit_length(static_cast<std::uint64_t>(prev_l_)) - 1, 3);
        if (axes_ == 2) {
            const int oct = Io::kDecode ? 0 : kOctantOf[lead * 4 + static_cast<int>(neg)];
            io_.field(4);
        turn = static_cast<int>(code_tree(io_, ctx_->turn[prev_turn_ + 8 * lclass], 3,
                                              static_cast<unsigned>((oct - prev_oct_) & 7)));
            const int code = kCodeOfOctant[(prev_oct_ + turn) & 7];
            lead = code >> 2;
            neg = static_cast<unsigned>(code & 3);
        } else {
            const unsigned dir = (static_cast<unsigned>(lead) << 6) | neg;
            unsigned got = prev_dir_;
            if (!io_.bit(ctx_->dir_same[0], dir == prev_dir_)) got = code_tree(io_, ctx_->dir_tree, 9, dir);
            lead = static_cast<int>(got >> 6);
            neg = got & 63u;
            turn = got == prev_dir_ ? 0 : 1;
            if (lead >= axes_ || (neg >> axes_) != 0) return fail("bad direction");
        }
        const int lctx = cap(bit_length(static_cast<std::uint64_t>(prev_l_)), 11) * 2 + (turn != 0);
        if constexpr (kMixedIo<Io>)
            mix_context(io_, 5, ctx_join(ctx_join(ctx_join(1, static_cast<std::uint64_t>(lead) << 8 | neg),
                                                  static_cast<std::uint64_t>(prev_l_)),
                                         static_cast<std::uint64_t>(prev_s_[0])));
        if (curve_ && axes_ == 2) {
            // The direction with the slopes of the two segments before, and
            // with their leading totals.
            const std::uint64_t dir = static_cast<std::uint64_t>(lead) << 8 | neg;
            const std::uint64_t slopes = slope_class(prev_s_[0], prev_l_) * 64 + slope_class(before_s_, before_l_);
            mix_context(io_, 6, ctx_join(ctx_join(ctx_join(3, dir), slopes), static_cast<std::uint64_t>(turn)));
            mix_context(io_, 7, ctx_join(ctx_join(ctx_join(4, dir), static_cast<std::uint64_t>(prev_l_)),
                                         static_cast<std::uint64_t>(before_l_) * 8 + static_cast<std::uint64_t>(turn)));
        }
        io_.field(5);
        const std::uint64_t l1 = code_uint(io_, ctx_->lead[lctx], static_cast<std::uint64_t>(l - 1));
        if (io_.failed || l1 >= static_cast<std::uint64_t>(kMaxSegmentTotal)) return fail("segment too long");
        l = static_cast<std::int64_t>(l1) + 1;
        const int bl = cap(bit_length(static_cast<std::uint64_t>(l)), 11);
        if constexpr (kMixedIo<Io>)
            mix_context(io_, 5, ctx_join(ctx_join(ctx_join(2, static_cast<std::uint64_t>(lead) << 8 | neg),
                                                  static_cast<std::uint64_t>(l)),
                                         static_cast<std::uint64_t>(prev_l_)));
        if (curve_ && axes_ == 2) {
            // Curvature continuity: the minor total of the slope the two
            // segments before extrapolate (in one octant, no turn), against
            // the coded prediction (the previous slope).
            const std::int64_t p1 = predict_minor(l, prev_s_[0], prev_l_);
            std::int64_t p2 = p1;
            if (turn == 0 && prev_oct_ == before_oct_)
                p2 = (l * (2 * prev_s_[0] * before_l_ - before_s_ * prev_l_) + prev_l_ * before_l_ / 2) /
                     (prev_l_ * before_l_);
            const auto dd = static_cast<std::uint64_t>(std::clamp<std::int64_t>(p2 - p1, -4, 4) + 4);
            const auto lb = static_cast<std::uint64_t>(cap(bit_length(static_cast<std::uint64_t>(l)), 11));
            mix_context(io_, 6, ctx_join(ctx_join(ctx_join(5, dd), static_cast<std::uint64_t>(turn)), lb));
            mix_context(io_, 7, ctx_join(ctx_join(ctx_join(6, static_cast<std::uint64_t>(l)),
                                                  static_cast<std::uint64_t>(prev_l_)),
                                         static_cast<std::uint64_t>(prev_s_[0])));
        }
        seg = Segment{};
        int j = 0;
        for (int i = 0; i < axes_; ++i) {
            std::int64_t v = l;
            if (i != lead) {
                const std::int64_t pred = predict_minor(l, prev_s_[j], prev_l_);
                io_.field(6);
                const std::int64_t d =
                    code_sint(io_, ctx_->minor[bl], Io::kDecode ? 0 : std::llabs(want->delta[i]) - pred);
                if (io_.failed) return fail("bad minor total");
                v = pred + d;
                if (!minor_in_range(v, l, i, lead)) return fail("minor total out of range");
                ++j;
            }
            if (!apply_sign(v, neg, i)) return fail("sign on a resting axis");
            seg.delta[i] = v;
        }
        for (int k = 0; k < phase_count(p_, axes_); ++k) {
            const auto ab = *phase_arguments(p_, seg, axes_, k);
            const PhaseRange r = phase_range(p_, ab.first, ab.second);
            const std::int64_t def = timed_ == TimedPrediction::since ? tphase_.predict(p_, seg, axes_, k)
                                     : timed_ == TimedPrediction::rates ? rates_.predict(p_, seg, axes_, k)
                                                                        : default_phase(p_, ab.first, ab.second);
            if (r.hi - r.lo == 1) {
                seg.phase[k] = r.lo;
                continue;
            }
            if (curve_ && axes_ == 2) {  // the phase by the segment's totals, and by the previous phase
                mix_context(io_, 6, ctx_join(ctx_join(7, static_cast<std::uint64_t>(seg.delta[0])),
                                             static_cast<std::uint64_t>(seg.delta[1])));
                mix_context(io_, 7, ctx_join(ctx_join(8, static_cast<std::uint64_t>(prev_phase_)),
                                             static_cast<std::uint64_t>(cap(bit_length(static_cast<std::uint64_t>(l)), 11))));
            }
            io_.field(7);
        const std::int64_t d = code_sint(io_, ctx_->phase[bl], Io::kDecode ? 0 : want->phase[k] - def);
            if (io_.failed || !r.contains(def + d)) return fail("phase out of range");
            seg.phase[k] = def + d;
        }
        return true;
    }

    Io& io_;
    Profile p_;
    int axes_;
    TimedPrediction timed_;  // timed frames: phases predicted (FORMAT.md 1.5.1, timed block)
    TimedPhase tphase_;
    TimedRates rates_;
    std::unique_ptr<Contexts> ctx_;
    FlatMap table_;  // context (two history entries) -> next position
    std::vector<std::uint32_t> hist_;
    std::vector<Point> starts_;
    std::int64_t ptr_ = -1;
    std::uint64_t len_ = 0;
    int prev_oct_ = 0, prev_turn_ = 0;
    unsigned prev_dir_ = 0;
    std::int64_t prev_l_ = 1;
    std::array<std::int64_t, kMaxAxes> prev_s_{};
    std::string error_;
    std::vector<Item> uniq_;                  // distinct segments seen, by shape id
    std::vector<std::uint32_t> shape_index_;  // open addressing by hash: shape id + 1, 0 empty
    RecentShapes recent_;
    std::vector<Successors> succ_;            // by previous shape id + 1 (0: none)
    std::uint32_t prev_shape_ = kNone;
    int prev_succ_ = 0;
    int prev_known_ = 0;
    std::uint64_t prev_rank_ = 0;
    std::int64_t grid_ = 1;
    std::int64_t prev_start0_ = 0;
    // Mixed predictions only (block type 6).
    std::unique_ptr<MixPredictor> mixer_;
    std::uint64_t turn_hist_ = 0;  // turns (2D, 3 bits each) or directions (N-D, 9 bits each), latest lowest
    std::uint64_t l_hist_ = 0;     // bit lengths of the leading totals, 4 bits each, latest lowest
    std::uint32_t shape1_ = kNone, shape2_ = kNone;  // the last two shapes, across chains
    Point from_start_{};           // the chain's position relative to its start
    // The curvature models (FORMAT.md 1.11.1).
    bool curve_ = false;
    std::int64_t before_l_ = 1, before_s_ = 0;  // the segment before the previous one: leading, first minor total
    int before_oct_ = 0, last_oct_ = 0;         // its octant; the previous segment's octant (kept by note_segment)
    std::int64_t prev_phase_ = 0;               // the previous segment's first phase
};

std::int64_t steps_of(Profile p, const Segment& s, int axes) {
    return segment_length(s.delta, axes, profile_eight_connected(p));
}

}  // namespace

namespace {
// Layouts shorter than this are compressed again each time (no copy kept).
constexpr std::size_t kLayoutMemoBytes = 256;

// The layout's stored size and bytes: `z` (its zstd frame) when not empty.
void put_stored_layout(std::string& out, std::string_view layout, const std::string& z) {
    if (z.empty()) {
        put_varint(out, layout.size());
        out += layout;
    } else {
        put_varint(out, z.size());
        out += z;
    }
}
}  // namespace

void put_layout(std::string& out, std::string_view layout) {
    put_varint(out, layout.size());
    // The encoder codes a block's layout once per model and cut it tries
    // (the profile ranking: every profile, every cut), always the same
    // bytes: zstd at level 19 of a large layout (a steps file's DIR bits)
    // was most of -L 19's time. The calling thread keeps its last layout
    // and what it came to.
    struct Last {
        std::string layout, z;
    };
    thread_local Last last;
    if (layout.size() < kLayoutMemoBytes || layout != last.layout) {
        std::string z;
        if (!layout.empty()) {
            z.resize(ZSTD_compressBound(layout.size()));
            const std::size_t n = ZSTD_compress(z.data(), z.size(), layout.data(), layout.size(), 19);
            if (ZSTD_isError(n) || n >= layout.size()) z.clear();
            else z.resize(n);
        }
        if (layout.size() < kLayoutMemoBytes) {
            put_stored_layout(out, layout, z);
            return;
        }
        last.layout.assign(layout);
        last.z = std::move(z);
    }
    put_stored_layout(out, layout, last.z);
}

void start_output(Block& out, bool expand, int axes, std::string&& layout) {
    if (!expand) return;
    out.axes = axes;
    out.chains.clear();
    out.layout = std::move(layout);
}

bool rebuild_start(const Point& ref, const Point& delta, int axes, Point& start) {
    for (int a = 0; a < axes; ++a) {
        start[a] = stz::wrap_add(ref[a], delta[a]);
        if (!stz::start_in_range(start[a])) return false;
    }
    return true;
}

Result<std::string> get_layout(Cursor& cur, const std::string& where) {
    const std::size_t at = cur.pos();
    std::uint64_t size, stored;
    if (!cur.varint(size) || !cur.varint(stored))
        return make_error(Errc::corrupt, where + " byte " + std::to_string(cur.pos()) + ": bad layout sizes");
    if (size > kMaxBlockPayload)
        return make_error(Errc::limit, where + " byte " + std::to_string(cur.pos()) + ": layout over the limit");
    std::string_view bytes;
    if (stored > size || !cur.bytes(static_cast<std::size_t>(stored), bytes))
        return make_error(Errc::corrupt, where + " byte " + std::to_string(cur.pos()) + ": bad layout");
    if (stored == size) return std::string(bytes);
    // A damaged zstd layout: at the layout field's first byte.
    return unzstd(bytes, static_cast<std::uint32_t>(size), where + " byte " + std::to_string(at) + ": layout");
}

namespace {

// The segment-model payload of `block` cut into `segs`, coded through `io`
// (EncIo; the bench hook's counting encoder).
template <class Io>
std::string segment_model_with(Io& io, const Block& block, Profile p,
                               const std::vector<std::vector<Segment>>& segs, const WindowView* window,
                               TimedPrediction timed) {
    Counts c;
    c.nchains = block.chains.size();
    for (std::size_t i = 0; i < segs.size(); ++i)
        for (const Segment& s : segs[i]) {
            ++c.nsegments;
            c.nsteps += static_cast<std::uint64_t>(steps_of(p, s, block.axes));
        }
    std::string out;
    if (timed == TimedPrediction::rates) {  // block type 7: subtype, coding
        put_u8(out, kTimedSubtype);
        put_u8(out, kMixedIo<Io> ? kTimedMixed : kTimedPlain);
    } else if constexpr (kMixedIo<Io>) {
        put_u8(out, kMixedSegment | (io.curvature ? kMixedCurvature : 0u));
    }
    put_varint(out, c.nchains);
    put_varint(out, c.nsegments);
    put_varint(out, c.nsteps);
    // Grid of the chain starts: the gcd of every start delta. A chain's end
    // is its start plus its segments' totals (the cut is exact).
    std::uint64_t grid = 0;
    {
        Point ref{};
        for (std::size_t i = 0; i < block.chains.size(); ++i) {
            const Chain& chain = block.chains[i];
            for (int a = 0; a < block.axes; ++a)
                grid = std::gcd(grid, stz::magnitude(stz::wrap_sub(chain.start[a], ref[a])));
            ref = chain.start;
            for (const Segment& s : segs[i])
                for (int a = 0; a < block.axes; ++a) ref[a] = stz::wrap_add(ref[a], s.delta[a]);
        }
        if (grid == 0 || grid > (std::uint64_t{1} << 62)) grid = 1;
    }
    put_varint(out, grid);
    put_layout(out, block.layout);
    SegmentCoder<Io> coder(io, p, block.axes, timed);
    coder.set_grid(static_cast<std::int64_t>(grid));
    if (window) coder.prime(*window);
    Point ref{};
    for (std::size_t i = 0; i < block.chains.size(); ++i) {
        const Chain& chain = block.chains[i];
        Point d{};
        for (int a = 0; a < block.axes; ++a) d[a] = stz::wrap_sub(chain.start[a], ref[a]);
        coder.start(d);
        Point pos = chain.start;
        Segment got;
        for (std::size_t k = 0;; ++k) {
            const Segment* want = k < segs[i].size() ? &segs[i][k] : nullptr;
            if (!coder.next(want, pos == chain.start, k, c, got)) break;
            for (int a = 0; a < block.axes; ++a) pos[a] += want->delta[a];
            ++c.seen_segments;
            c.seen_steps += static_cast<std::uint64_t>(steps_of(p, *want, block.axes));
        }
        ref = pos;
    }
    out += io.rc.finish();
    return out;
}

}  // namespace

std::string write_segment_model(const Block& block, Profile p,
                                const std::vector<std::vector<Segment>>& segs, const WindowView* window,
                                bool timed, bool mixed, bool rates, bool curvature) {
    const TimedPrediction t = rates ? TimedPrediction::rates : timed ? TimedPrediction::since : TimedPrediction::none;
    if (mixed) {
        MixEncIo io;
        io.curvature = curvature && !rates;
        return segment_model_with(io, block, p, segs, window, t);
    }
    EncIo io;
    return segment_model_with(io, block, p, segs, window, t);
}

std::array<double, kSegmentModelFields> segment_model_costs(const Block& block, Profile p,
                                                            const std::vector<std::vector<Segment>>& segs,
                                                            int timed) {
    CostEncIo io;
    segment_model_with(io, block, p, segs, nullptr, static_cast<TimedPrediction>(timed));
    std::array<double, kSegmentModelFields> out{};
    std::copy_n(io.cost, kSegmentModelFields, out.begin());
    return out;
}

namespace {

template <class Io>
Result<void> read_segment_model_with(std::string_view payload, Profile p, int axes, bool expand,
                                     Block& out, BlockCounts& counts, const std::string& where,
                                     const WindowView* window, SegmentItems* items, TimedPrediction timed) {
    Cursor cur(payload);
    Counts c;
    bool curvature = false;
    if (timed == TimedPrediction::rates) {
        unsigned subtype, coding;
        if (!cur.u8(subtype) || subtype != kTimedSubtype)
            return make_error(Errc::corrupt, where + " byte 0: unknown subtype of an extended block");
        if (p != Profile::eval8 && p != Profile::grbl && p != Profile::marlin)
            return make_error(Errc::corrupt, where + " byte 0: a timed block under a 4-connected profile");
        if (!cur.u8(coding) || coding != (kMixedIo<Io> ? kTimedMixed : kTimedPlain))
            return make_error(Errc::corrupt, where + " byte 1: unknown coding of a timed block");
    } else if constexpr (kMixedIo<Io>) {
        unsigned kind;
        if (!cur.u8(kind) || mixed_model_of(kind) != kSegmentModel)
            return make_error(Errc::corrupt, where + " byte 0: not a mixed segment model");
        curvature = (kind & kMixedCurvature) != 0;
    }
    if (!cur.varint(c.nchains) || !cur.varint(c.nsegments) || !cur.varint(c.nsteps))
        return make_error(Errc::corrupt, where + " byte " + std::to_string(cur.pos()) + ": bad payload header");
    if (c.nchains > kMaxBlockChains || c.nsegments > kMaxBlockSteps || c.nsteps > kMaxBlockSteps)
        return make_error(Errc::limit, where + " byte 0: payload declares more chains, segments or "
                                               "steps than the limits");
    std::uint64_t grid;
    const std::size_t grid_at = cur.pos();
    if (!cur.varint(grid) || grid == 0 || grid > (std::uint64_t{1} << 62))
        return make_error(Errc::corrupt, where + " byte " + std::to_string(grid_at) + ": bad start grid");
    auto layout = get_layout(cur, where);
    if (!layout) return std::move(layout).error();
    const std::size_t base = cur.pos();
    Io io = [&] {
        if constexpr (kMixedIo<Io>) return Io(payload.substr(base), nullptr);  // the coder sets the predictor
        else return Io(payload.substr(base));
    }();
    if constexpr (kMixedIo<Io>) io.curvature = curvature;
    SegmentCoder<Io> coder(io, p, axes, timed);
    coder.set_grid(static_cast<std::int64_t>(grid));
    if (window) coder.prime(*window);
    if (items) *items = SegmentItems{};
    start_output(out, expand, axes, std::move(*layout));
    auto fail = [&](const std::string& what) {
        return make_error(Errc::corrupt, where + " byte " + std::to_string(base + io.rc.pos()) + ": " +
                                             (coder.error().empty() ? what : coder.error()));
    };
    Point ref{};
    for (std::uint64_t i = 0; i < c.nchains; ++i) {
        Chain chain;
        Point d;
        if (const char* e = next_chain_start(coder, io, ref, axes, chain, d)) return fail(e);
        if (items) {
            items->starts.push_back(d);
            items->counts.push_back(0);
        }
        Point pos = chain.start;
        Segment seg;
        for (std::uint64_t k = 0;; ++k) {
            const bool more = coder.next(nullptr, pos == chain.start, k, c, seg);
            if (io.failed || io.rc.overrun()) return fail("bad segment");
            if (!more) break;
            const std::int64_t n = steps_of(p, seg, axes);
            if (c.seen_steps + static_cast<std::uint64_t>(n) > c.nsteps) return fail("more steps than declared");
            c.seen_steps += static_cast<std::uint64_t>(n);
            ++c.seen_segments;
            for (int a = 0; a < axes; ++a) pos[a] += seg.delta[a];
            if (expand) expand_segment(p, seg, axes, chain.steps);
            if (items) {
                items->segments.push_back(seg);
                ++items->counts.back();
            }
        }
        ref = pos;
        if (expand) out.chains.push_back(std::move(chain));
    }
    if (c.seen_segments != c.nsegments || c.seen_steps != c.nsteps)
        return fail("declared segment or step count does not match");
    if (!io.rc.finished()) return fail("range-coded stream does not end at the payload's end");
    counts.chains += c.nchains;
    counts.segments += c.nsegments;
    counts.steps += c.nsteps;
    return {};
}

}  // namespace

Result<void> read_segment_model(std::string_view payload, Profile p, int axes, bool expand,
                                Block& out, BlockCounts& counts, const std::string& where,
                                const WindowView* window, SegmentItems* items, bool timed, bool mixed, bool rates) {
    const TimedPrediction t = rates ? TimedPrediction::rates : timed ? TimedPrediction::since : TimedPrediction::none;
    // A timed block names its coding in its second byte (an unknown one is
    // reported by the plain reader).
    if (rates) mixed = payload.size() >= 2 && static_cast<unsigned char>(payload[1]) == kTimedMixed;
    if (mixed)
        return read_segment_model_with<MixDecIo>(payload, p, axes, expand, out, counts, where, window, items, t);
    return read_segment_model_with<DecIo>(payload, p, axes, expand, out, counts, where, window, items, t);
}

}  // namespace stepzip::stz
