// Table blocks (docs/FORMAT.md "Table block"): operations over the segment
// items, fields in static per-block rANS tables chosen by context.
// One template (TableCoder<Io>) runs both directions, so the encoder and
// the decoder cannot disagree on a context or a state update.
// Complexity: per segment one operation symbol, and for a shape coded in
// full a few field symbols; O(rank) list work; a match copies its items.
// Memory: O(items) plus the tables (at most 50 x 4096 slots).
#include "table_block.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <limits>
#include <memory>
#include <numeric>
#include <type_traits>
#include <utility>

#include "../common/bytes.hpp"
#include "arc_items.hpp"
#include "modeled_block.hpp"
#include "mtf_list.hpp"
#include "segment_fields.hpp"
#include "../interpolate/expand_into.hpp"
#include "stepzip/interpolate/segment.hpp"
#include "table_rans.hpp"

namespace stepzip::stz {

namespace {

using namespace table;

// Tables, in payload order (docs/FORMAT.md "Table block").
constexpr int kTOp = 0;       // 6: previous operation class
constexpr int kTLead = 6;     // 16: min(bit_length(prev L), 7) * 2 + (turn != 0)
constexpr int kTMinor = 22;   // 12: min(bit_length(L), 11)
constexpr int kTPhase = 34;   // 12: min(bit_length(L), 11)
constexpr int kTStart = 46;   // 2: axis 0, other axes
constexpr int kTOffset = 48;  // 1
constexpr int kTDir = 49;     // 1: N-D direction
// Arc blocks (docs/FORMAT.md 1.10.1): tables 50-52 code the arcs' fields,
// table-set bit 53 flags the block (no table).
constexpr int kTArcCentre = 50;  // 1: centre x, y
constexpr int kTArcSmall = 51;   // 1: the end's smaller coordinate about the centre
constexpr int kTArcLarge = 52;   // 1: the larger one: residual, axis, sign
constexpr int kTables = 53;
constexpr int kTArcFlag = 53;
constexpr int kLineTables = 50;  // the tables of a block without arcs

// Operation symbols.
constexpr unsigned kOpEnd = 0, kOpStart = 1, kOpSucc = 2, kOpRec = 6, kOpRecBucket = 14, kOpFull = 28,
                   kOpMatch = 36, kOps = 90;
// Arc blocks: two more operations, an arc clockwise and counter-clockwise.
constexpr unsigned kOpArc = 90, kArcOps = 92;
// Largest zigzag value of an arc field (coordinates up to 2^24).
constexpr std::uint64_t kMaxArcField = std::uint64_t{1} << 27;
constexpr unsigned kOffsetBuckets = 3;  // offset symbols: 0..2 repeat offsets, then bucket_of(offset - 1)

// Previous-operation classes (operation-table contexts).
enum OpClass : int { kAfterStart = 0, kAfterSucc, kAfterRec, kAfterFull, kAfterMatch, kAfterEnd };

constexpr std::size_t kRecent = 1024;  // recent-shapes ring
constexpr std::size_t kSucc = 4;       // successors per shape
constexpr std::uint32_t kNone = 0xFFFFFFFFu;

// History entries: kind in the top two bits, index below.
constexpr std::uint32_t kSegTag = 0u << 30, kStartTag = 1u << 30, kEndTag = 2u << 30, kIndexMask = (1u << 30) - 1;

unsigned alphabet(int t, bool arcs) {
    if (t < kTLead) return arcs ? kArcOps : kOps;
    if (t < kTOffset) return kBuckets;
    if (t == kTOffset) return kOffsetBuckets + kBuckets;
    if (t == kTDir) return 512;
    return kBuckets;
}

// round(sqrt(q)) for q >= 0, halves up, in exact integer arithmetic.
std::int64_t round_isqrt(std::int64_t q) {
    auto r = static_cast<std::int64_t>(std::sqrt(static_cast<double>(q)));
    while (r > 0 && r * r > q) --r;
    while ((r + 1) * (r + 1) <= q) ++r;
    return q - r * r > r ? r + 1 : r;
}

int cap(int v, int hi) { return v < hi ? v : hi; }

constexpr int kOctantOf[8] = {0, 3, 7, 4, 1, 2, 6, 5};  // lead * 4 + negmask -> octant
constexpr int kCodeOfOctant[8] = {0, 4, 5, 1, 3, 7, 6, 2};

std::uint64_t zig(std::int64_t v) { return (static_cast<std::uint64_t>(v) << 1) ^ static_cast<std::uint64_t>(v >> 63); }
std::int64_t unzig(std::uint64_t u) { return static_cast<std::int64_t>(u >> 1) ^ -static_cast<std::int64_t>(u & 1); }

// The value of bucket symbol `s` (< kBuckets) with its extra bits read by `bits`.
template <class Bits>
std::uint64_t bucket_value(unsigned s, Bits&& bits) {
    if (s < 8) return s;
    const int k = static_cast<int>((s - 8) / 2) + 3;
    const std::uint64_t top = (std::uint64_t{1} << k) | (std::uint64_t{(s - 8) & 1} << (k - 1));
    return top | bits(k - 1);
}

// Encoder side of the coder: records symbols (counted per table) and writes
// extra bits.
struct EncSide {
    static constexpr bool kDecode = false;
    std::vector<std::pair<std::uint8_t, std::uint16_t>> syms;
    std::array<std::vector<std::uint32_t>, kTables> count;
    BitWriter bits;
    bool failed = false;
    // The minor totals' symbols and extra bits in the other coding (raw
    // against predicted), by table context, for MinorCoding::smaller.
    std::array<std::array<std::uint32_t, kBuckets>, 12> alt_minor{};
    std::uint64_t alt_minor_bits = 0, minor_bits = 0;
    void note_minor(int ctx, std::uint64_t alt, std::uint64_t coded) {
        int nb = 0;
        std::uint64_t extra;
        ++alt_minor[static_cast<std::size_t>(ctx)][bucket_of(alt, nb, extra)];
        alt_minor_bits += static_cast<std::uint64_t>(nb);
        bucket_of(coded, nb, extra);
        minor_bits += static_cast<std::uint64_t>(nb);
    }
    EncSide() {
        for (int t = 0; t < kTables; ++t) count[static_cast<std::size_t>(t)].assign(alphabet(t, true), 0);
    }
    [[gnu::always_inline]] unsigned sym(int t, unsigned s) {
        syms.emplace_back(static_cast<std::uint8_t>(t), static_cast<std::uint16_t>(s));
        ++count[static_cast<std::size_t>(t)][s];
        return s;
    }
    std::uint64_t raw(int n, std::uint64_t v) {
        if (n > 0) bits.put(v, n);
        return v;
    }
};

// Decoder side: the block's tables, the rANS stream and the bit stream.
struct DecSide {
    static constexpr bool kDecode = true;
    std::array<DecodeTable, kTables> tables;
    RansDecoder rans;
    BitReader bits;
    bool failed = false;
    [[gnu::always_inline]] unsigned sym(int t, unsigned) {
        const DecodeTable& d = tables[static_cast<std::size_t>(t)];
        if (d.precision < 0) {
            failed = true;  // a table the payload left unused
            return 0;
        }
        return rans.get(d);
    }
    std::uint64_t raw(int n, std::uint64_t) { return n > 0 ? bits.get(n) : 0; }
};

// Move-to-front ring of shape ids, newest at rank 0.
class RecentRing {
public:
    std::size_t size() const { return size_; }
    std::uint32_t at(std::size_t r) const { return ring_[(head_ + r) & (kRecent - 1)]; }
    void push_front(std::uint32_t id) {
        head_ = (head_ + kRecent - 1) & (kRecent - 1);
        ring_[head_] = id;
        if (size_ < kRecent) ++size_;
    }
    void to_front(std::size_t r) {
        const std::uint32_t id = at(r);
        if (head_ + r < kRecent) {  // ranks 0..r-1 in one piece
            if (r >= 16) std::memmove(&ring_[head_ + 1], &ring_[head_], r * sizeof(std::uint32_t));
            else
                for (std::size_t i = head_ + r; i > head_; --i) ring_[i] = ring_[i - 1];
        } else {
            for (; r > 0; --r) ring_[(head_ + r) & (kRecent - 1)] = ring_[(head_ + r - 1) & (kRecent - 1)];
        }
        ring_[head_] = id;
    }

private:
    std::array<std::uint32_t, kRecent> ring_{};
    std::size_t head_ = 0, size_ = 0;
};

using SuccList = MtfList<kSucc>;

// An allocator whose resize() leaves the new elements uninitialized where
// they are trivial (the history's arrays are written right after).
template <class T>
struct UninitAlloc : std::allocator<T> {
    template <class U>
    struct rebind {
        using other = UninitAlloc<U>;
    };
    UninitAlloc() = default;
    template <class U>
    UninitAlloc(const UninitAlloc<U>&) noexcept {}
    template <class U>
    void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... A>
    void construct(U* p, A&&... a) {
        ::new (static_cast<void*>(p)) U(std::forward<A>(a)...);
    }
};

// Arrays of the items' history entries and of pointers to their segments
// and starts, written in place after a resize (no zeroing first).
using Entries = std::vector<std::uint32_t, UninitAlloc<std::uint32_t>>;
template <class T>
using Pointers = std::vector<const T*, UninitAlloc<const T*>>;

// The history entries of a window block's items at `h` (docs/FORMAT.md
// "Table block"): per chain its start, its segments and its end, the starts
// numbered from `first_start` and the segments from `first_seg` (both
// advanced). Returns the end of the entries.
std::uint32_t* window_entries(const SegmentItems& w, std::uint32_t& first_seg, std::uint32_t& first_start,
                              std::uint32_t* h) {
    std::uint32_t si = first_seg, ci = first_start;  // (in registers: `h` might alias the arguments)
    for (std::size_t k = 0; k < w.starts.size(); ++k) {
        *h++ = kStartTag | ci++;
        const std::uint32_t cnt = w.counts[k];
#pragma GCC unroll 4
        for (std::uint32_t q = 0; q < cnt; ++q) h[q] = kSegTag | (si + q);
        h += cnt;
        si += cnt;
        *h++ = kEndTag;
    }
    first_seg = si;
    first_start = ci;
    return h;
}

// Pointers to the `m` objects at `first`, at `to`.
template <class T>
void pointers_to(const T* first, std::size_t m, const T** to) {
#pragma GCC unroll 4
    for (std::size_t q = 0; q < m; ++q) to[q] = first + q;
}

// Segments that never move once stored, in chunks of 64, 128, ... 4096
// (a deque's nodes hold five segments each: an allocation per five).
class SegmentStore {
public:
    const Segment& push_back(const Segment& s) {
        Segment& at = slot();
        at = s;
        return at;
    }
    /// A new segment of zeros, written in place (a chunk is made of zeros
    /// and each of its segments handed out once: no second clearing).
    Segment& emplace() { return slot(); }

private:
    Segment& slot() {
        if (used_ == size_) {
            size_ = std::min<std::size_t>(kMaxChunk, std::size_t{64} << std::min<std::size_t>(chunks_.size(), 6));
            // Zeros: Segment's member initializers (emplace() relies on them).
            chunks_.push_back(std::make_unique_for_overwrite<Segment[]>(size_));
            used_ = 0;
        }
        return chunks_.back()[used_++];
    }

    static constexpr std::size_t kMaxChunk = 4096;
    std::vector<std::unique_ptr<Segment[]>> chunks_;
    std::size_t used_ = 0, size_ = 0;
};

// The steps of the chain being decoded: one buffer for every chain of a
// block, grown by doubling without initializing it; a chain's steps are
// copied out once, at its end.
class StepBuffer {
public:
    explicit StepBuffer(std::size_t first) : first_(first) {}
    /// Room for `n` more steps after the first `used`, which are kept.
    [[gnu::always_inline]] Step* room(std::size_t used, std::size_t n) {
        if (used + n > cap_) grow(used, n);
        return buf_.get() + used;
    }
    const Step* data() const { return buf_.get(); }

private:
    void grow(std::size_t used, std::size_t n) {
        const std::size_t cap = std::max({used + n, 2 * cap_, first_});
        auto b = std::make_unique_for_overwrite<Step[]>(cap);
        if (used > 0) std::memcpy(b.get(), buf_.get(), used * sizeof(Step));
        buf_ = std::move(b);
        cap_ = cap;
    }

    std::unique_ptr<Step[]> buf_;
    std::size_t cap_ = 0, first_;
};

// Canonical form of a segment into `c` (zero on entry): degenerate phases
// at their only value, unused phases zero (as the decoder rebuilds it).
inline void canonical_into(Profile p, const Segment& s, int axes, Segment& c) {
    if (is_arc(s, axes)) {
        c = s;
        return;
    }
    c.delta = s.delta;
    if (axes == 2) {
        // One phase, its arguments as phase_arguments gives them: (L, S) on
        // the leading-axis profiles, (|dx|, |dy|) on the others; degenerate
        // as phase_range says (its range is then [default, default + 1)).
        const std::int64_t x = std::llabs(s.delta[0]), y = std::llabs(s.delta[1]);
        const bool eight = profile_eight_connected(p);
        const std::int64_t a = eight ? std::max(x, y) : x, b = eight ? std::min(x, y) : y;
        const bool degenerate = eight ? (b == 0 || b == a) : (a == 0 || b == 0);
        c.phase[0] = degenerate ? default_phase(p, a, b) : s.phase[0];
        return;
    }
    for (int j = 0; j < phase_count(p, axes); ++j) {
        const auto ab = *phase_arguments(p, s, axes, j);
        const PhaseRange r = phase_range(p, ab.first, ab.second);
        c.phase[static_cast<std::size_t>(j)] = r.hi - r.lo == 1 ? r.lo : s.phase[static_cast<std::size_t>(j)];
    }
}

// Whether `s` is its own canonical form (the cuts' segments mostly are: the
// table coder then points at them instead of at a canonical copy).
inline bool is_canonical(Profile p, const Segment& s, int axes) {
    Segment c;
    canonical_into(p, s, axes, c);
    return c == s;
}

// kAxes: the axis count fixed at compile time (the decoder's loop for two
// axes), 0: given at run time. The per-item operations are flattened
// ([[gnu::flatten]]): GCC otherwise calls their vector pushes and small
// helpers out of line.
template <class Io, int kAxes = 0>
class TableCoder {
public:
    TableCoder(Io& io, Profile p, int axes) : io_(io), p_(p), axes_(kAxes ? kAxes : axes), phases_(phase_count(p, axes)) {
        succ_.resize(1);  // succ_[0]: after no shape
    }

    Io& io_;
    Profile p_;
    const int axes_;
    int phases_;
    const bool eight_ = profile_eight_connected(p_);
    // The axis count, a constant in the two-axis decoder.
    constexpr int ax() const { return kAxes ? kAxes : axes_; }
    // Phases a segment has: one on two axes under every profile.
    constexpr int phases() const { return kAxes == 2 ? 1 : phases_; }
    std::int64_t grid_ = 1;
    // Decoded content: every segment and chain start of the block, and the
    // history of items over them.
    Pointers<Segment> segs_;  // into own_ or the window's items
    SegmentStore own_;
    Pointers<Point> starts_;        // into own_starts_ or the window's items
    std::deque<Point> own_starts_;  // (its elements never move)
    Entries hist_;
    // Shapes: id -> index in segs_ of the segment coded in full.
    std::vector<std::uint32_t> shape_;
    std::vector<SuccList> succ_;  // by id + 1 (0: none)
    RecentRing recent_;
    std::uint32_t prev_shape_ = kNone;
    int prev_op_ = kAfterEnd;
    // Field contexts.
    int prev_oct_ = 0, prev_turn_ = 0;
    unsigned prev_dir_ = 0;
    std::int64_t prev_l_ = 1;
    std::array<std::int64_t, kMaxAxes> prev_s_{};
    std::array<std::uint64_t, 3> rep_{1, 2, 3};
    const char* error_ = nullptr;
    // Arc blocks: the method of the arcs the block codes (-1: none yet).
    int arc_method_ = -1;
    // Minor totals coded as they are (block type 7 subtype 4), not as the
    // residual of the previous segment's slope.
    bool raw_minors_ = false;

    // Starts the block from the window (docs/FORMAT.md "Table block"): the
    // items of the window's blocks, oldest first, enter the history (and
    // nothing else) so that matches may copy them.
    // `more_segs`, `more_items`, `more_starts`: room for the block's own,
    // reserved with the window's (the decoder's estimate; no copy of the
    // primed history).
    void prime(const WindowView& window, std::size_t more_segs = 0, std::size_t more_items = 0,
               std::size_t more_starts = 0) {
        std::size_t n = 0, c = 0;
        for (const auto& b : window) {
            n += b->items.segments.size();
            c += b->items.starts.size();
        }
        segs_.reserve(n + more_segs);
        hist_.reserve(n + 2 * c + more_items);
        starts_.reserve(c + more_starts);
        // Written in place (the coder is new: every array empty).
        segs_.resize(n);
        hist_.resize(n + 2 * c);
        starts_.resize(c);
        std::uint32_t* hp = hist_.data();
        std::uint32_t si = 0, ci = 0;
        for (const auto& b : window) {
            const SegmentItems& w = b->items;
            pointers_to(w.segments.data(), w.segments.size(), segs_.data() + si);
            pointers_to(w.starts.data(), w.starts.size(), starts_.data() + ci);
            hp = window_entries(w, si, ci, hp);
        }
    }

    // The encoder's prime(): the window's items as the encoder lists them
    // (the same history entries over the same segment and start indices),
    // with its segments in canonical form (its cuts may not be canonical).
    void prime_from(const Pointers<Segment>& segs, const Entries& items,
                    const std::vector<Point>& starts, std::size_t nsegs, std::size_t nitems, std::size_t nstarts,
                    std::size_t more_segs, std::size_t more_items) {
        segs_.reserve(nsegs + more_segs);
        hist_.reserve(nitems + more_items);
        segs_.assign(segs.begin(), segs.begin() + static_cast<std::ptrdiff_t>(nsegs));
        hist_.assign(items.begin(), items.begin() + static_cast<std::ptrdiff_t>(nitems));
        starts_.resize(nstarts);
        pointers_to(starts.data(), nstarts, starts_.data());
    }

    bool fail(const char* what) {
        if (!error_) error_ = what;
        io_.failed = true;
        return false;
    }

    std::uint64_t code_uint(int t, std::uint64_t want) {
        int nb = 0;
        std::uint64_t extra = 0;
        unsigned s = Io::kDecode ? 0 : bucket_of(want, nb, extra);
        s = io_.sym(t, s);
        if constexpr (Io::kDecode) {
            return bucket_value(s, [&](int n) { return io_.raw(n, 0); });
        } else {
            io_.raw(nb, extra);
            return want;
        }
    }

    unsigned code_op(unsigned want) { return io_.sym(kTOp + prev_op_, want); }

    // A chain start: the delta over the grid per axis.
    [[gnu::flatten]] bool code_start(const Point& want, Point& delta) {
        for (int i = 0; i < ax(); ++i) {
            const std::uint64_t v = code_uint(kTStart + (i != 0), Io::kDecode ? 0 : zig(want[i] / grid_));
            delta[i] = static_cast<std::int64_t>(static_cast<std::uint64_t>(unzig(v)) * static_cast<std::uint64_t>(grid_));
        }
        starts_.push_back(&own_starts_.emplace_back(delta));
        hist_.push_back(kStartTag | static_cast<std::uint32_t>(starts_.size() - 1));
        prev_shape_ = kNone;
        prev_op_ = kAfterStart;
        return !io_.failed;
    }

    [[gnu::flatten]] void code_end() {
        hist_.push_back(kEndTag);
        prev_op_ = kAfterEnd;
    }

    // Rank of a recent shape: 0..7 in the operation, above in buckets.
    unsigned rec_op(std::size_t r, int& nb, std::uint64_t& extra) const {
        nb = 0;
        extra = 0;
        if (r < 8) return kOpRec + static_cast<unsigned>(r);
        const int k = std::bit_width(r) - 1;
        nb = k - 1;
        extra = r & ((std::size_t{1} << (k - 1)) - 1);
        return kOpRecBucket + 2 * static_cast<unsigned>(k - 3) + static_cast<unsigned>((r >> (k - 1)) & 1);
    }

    // A segment given by shape id `id` (coded by successor or recent rank).
    // The item refers to the shape's stored segment (segments never move).
    [[gnu::flatten]] void take_shape(std::uint32_t id, bool from_recent_rank, std::size_t r) {
        const Segment* seg = segs_[shape_[id]];
        if (from_recent_rank) recent_.to_front(r);
        else recent_.push_front(id);
        succ_[prev_shape_ + 1].use(id);
        prev_shape_ = id;
        segs_.push_back(seg);
        hist_.push_back(kSegTag | static_cast<std::uint32_t>(segs_.size() - 1));
        note_fields(*seg);
        prev_op_ = from_recent_rank ? kAfterRec : kAfterSucc;
    }

    // Enters a segment of own_ (stored in place), of leading axis `lead`
    // and sign mask `neg`, into the history.
    [[gnu::flatten]] void push_seg(const Segment& seg, int lead, unsigned neg) {
        segs_.push_back(&seg);
        hist_.push_back(kSegTag | static_cast<std::uint32_t>(segs_.size() - 1));
        note_fields(seg, lead, neg);
    }

    void note_fields(const Segment& seg) {
        unsigned neg = 0;
        for (int i = 0; i < ax(); ++i)
            if (seg.delta[i] < 0) neg |= 1u << i;
        note_fields(seg, leading_axis(seg.delta, ax()), neg);
    }
    // The field contexts after `seg`, whose leading axis and sign mask the
    // caller knows.
    void note_fields(const Segment& seg, int lead, unsigned neg) {
        if (ax() == 2) {
            const int oct = kOctantOf[lead * 4 + static_cast<int>(neg)];
            prev_turn_ = (oct - prev_oct_) & 7;
            prev_oct_ = oct;
        } else {
            prev_dir_ = (static_cast<unsigned>(lead) << 6) | neg;
            prev_turn_ = 0;
        }
        prev_l_ = std::llabs(seg.delta[lead]);
        int j = 0;
        for (int i = 0; i < ax(); ++i)
            if (i != lead) prev_s_[static_cast<std::size_t>(j++)] = std::llabs(seg.delta[i]);
    }

    // A segment coded in full after its operation (2D: the operation gave
    // the turn; N-D: whether the direction is the previous one).
    [[gnu::flatten]] bool code_full(unsigned op, const Segment* want) {
        int lead = 0;
        unsigned neg = 0;
        int turn = 0;
        if (ax() == 2) {
            turn = static_cast<int>(op - kOpFull);
            const int code = kCodeOfOctant[(prev_oct_ + turn) & 7];
            lead = code >> 2;
            neg = static_cast<unsigned>(code & 3);
        } else {
            if (op - kOpFull > 1) return fail("bad operation");
            unsigned dir = prev_dir_;
            if (op == kOpFull + 1) {
                unsigned w = 0;
                if constexpr (!Io::kDecode) {
                    const int wl = leading_axis(want->delta, ax());
                    for (int i = 0; i < ax(); ++i)
                        if (want->delta[i] < 0) w |= 1u << i;
                    w |= static_cast<unsigned>(wl) << 6;
                }
                dir = io_.sym(kTDir, w);
                turn = 1;
            }
            lead = static_cast<int>(dir >> 6);
            neg = dir & 63u;
            if (lead >= ax() || (neg >> ax()) != 0) return fail("bad direction");
        }
        const int lctx = cap(std::bit_width(static_cast<std::uint64_t>(prev_l_)), 7) * 2 + (turn != 0);
        const std::uint64_t l1 =
            code_uint(kTLead + lctx, Io::kDecode ? 0 : static_cast<std::uint64_t>(std::llabs(want->delta[lead]) - 1));
        if (io_.failed || l1 >= static_cast<std::uint64_t>(kMaxSegmentTotal)) return fail("segment too long");
        const std::int64_t l = static_cast<std::int64_t>(l1) + 1;
        const int bl = cap(std::bit_width(static_cast<std::uint64_t>(l)), 11);
        Segment& seg = own_.emplace();  // in place (a failed segment stays unused)
        int j = 0;
        for (int i = 0; i < ax(); ++i) {
            std::int64_t v = l;
            if (i != lead) {
                const std::int64_t pred =
                    raw_minors_ ? 0 : predict_minor(l, prev_s_[static_cast<std::size_t>(j)], prev_l_);
                std::uint64_t want_z = 0;
                if constexpr (!Io::kDecode) {
                    const std::int64_t s = std::llabs(want->delta[i]);
                    const std::uint64_t predicted = zig(s - predict_minor(l, prev_s_[static_cast<std::size_t>(j)], prev_l_));
                    const auto raw = static_cast<std::uint64_t>(s);
                    want_z = raw_minors_ ? raw : predicted;
                    io_.note_minor(bl, raw_minors_ ? predicted : raw, want_z);
                }
                const std::uint64_t z = code_uint(kTMinor + bl, want_z);
                if (io_.failed || z > (std::uint64_t{1} << 32)) return fail("bad minor total");
                v = raw_minors_ ? static_cast<std::int64_t>(z) : pred + unzig(z);
                if (!minor_in_range(v, l, i, lead)) return fail("minor total out of range");
                ++j;
            }
            if (!apply_sign(v, neg, i)) return fail("sign on a resting axis");
            seg.delta[i] = v;
        }
        for (int k = 0; k < phases(); ++k) {
            // Two axes: the arguments from the totals just decoded (the
            // leading axis is `lead`), as phase_arguments gives them.
            const auto ab = kAxes == 2 ? (eight_ ? std::pair<std::int64_t, std::int64_t>{l, std::llabs(seg.delta[1 - lead])}
                                                 : std::pair<std::int64_t, std::int64_t>{std::llabs(seg.delta[0]), std::llabs(seg.delta[1])})
                                       : *phase_arguments(p_, seg, ax(), k);
            const PhaseRange r = phase_range(p_, ab.first, ab.second);
            if (r.hi - r.lo == 1) {
                seg.phase[static_cast<std::size_t>(k)] = r.lo;
                continue;
            }
            const std::int64_t def = default_phase(p_, ab.first, ab.second);
            const std::uint64_t z =
                code_uint(kTPhase + bl, Io::kDecode ? 0 : zig(want->phase[static_cast<std::size_t>(k)] - def));
            if (io_.failed || z > (std::uint64_t{1} << 62)) return fail("phase out of range");
            const std::int64_t f = def + unzig(z);
            if (!r.contains(f)) return fail("phase out of range");
            seg.phase[static_cast<std::size_t>(k)] = f;
        }
        const auto id = static_cast<std::uint32_t>(shape_.size());
        shape_.push_back(static_cast<std::uint32_t>(segs_.size()));
        succ_.emplace_back();
        recent_.push_front(id);
        succ_[prev_shape_ + 1].use(id);
        prev_shape_ = id;
        push_seg(seg, lead, neg);  // (the lead and signs the totals have: checked above)
        prev_op_ = kAfterFull;
        return true;
    }

    // An arc after its operation (docs/FORMAT.md 1.10.1): the centre from
    // the start, then the end about the centre, its smaller coordinate in
    // full and its larger one as the residual from the circle through the
    // start. Arcs are not shapes; the field contexts stay.
    bool code_arc(unsigned op, const Segment* want) {
        Segment arc{};
        arc.delta[4] = op == kOpArc ? 1 : 2;
        arc.delta[5] = arc_method_;
        for (int a = 0; a < 2; ++a) {
            const std::uint64_t z = code_uint(kTArcCentre, Io::kDecode ? 0 : zig(want->delta[2 + a]));
            if (io_.failed || z > kMaxArcField) return fail("arc centre out of range");
            arc.delta[2 + a] = unzig(z);
        }
        const std::int64_t cx = arc.delta[2], cy = arc.delta[3];
        if ((cx == 0 && cy == 0) || std::llabs(cx) > kMaxInterpolateCoord || std::llabs(cy) > kMaxInterpolateCoord)
            return fail("arc centre out of range");
        std::int64_t ux = 0, uy = 0;  // the end about the centre (encoder)
        if constexpr (!Io::kDecode) {
            ux = want->delta[0] - cx;
            uy = want->delta[1] - cy;
        }
        const bool y_large = std::llabs(uy) > std::llabs(ux);
        const std::uint64_t zs = code_uint(kTArcSmall, Io::kDecode ? 0 : zig(y_large ? ux : uy));
        if (io_.failed || zs > kMaxArcField) return fail("arc end out of range");
        const std::int64_t small = unzig(zs);
        const std::int64_t pred = round_isqrt(std::max<std::int64_t>(0, cx * cx + cy * cy - small * small));
        std::uint64_t v = 0;
        if constexpr (!Io::kDecode) {
            const std::int64_t large = y_large ? uy : ux;
            v = (zig(std::llabs(large) - pred) << 2) | (std::uint64_t{y_large} << 1) | std::uint64_t{large < 0};
        }
        v = code_uint(kTArcLarge, v);
        if (io_.failed || (v >> 2) > kMaxArcField) return fail("arc end out of range");
        const std::int64_t mag = pred + unzig(v >> 2);
        if (mag < 0 || std::llabs(small) > kMaxInterpolateCoord || mag > kMaxInterpolateCoord)
            return fail("arc end out of range");
        const std::int64_t large = (v & 1) ? -mag : mag;
        if ((v >> 1) & 1) {
            ux = small;
            uy = large;
        } else {
            ux = large;
            uy = small;
        }
        arc.delta[0] = cx + ux;
        arc.delta[1] = cy + uy;
        segs_.push_back(&own_.push_back(arc));
        hist_.push_back(kSegTag | static_cast<std::uint32_t>(segs_.size() - 1));
        prev_shape_ = kNone;
        prev_op_ = kAfterFull;
        return true;
    }

    // A match's offset (1 = the item just before), by repeat offset or in full.
    std::uint64_t code_offset(std::uint64_t want) {
        unsigned s = 0;
        int nb = 0;
        std::uint64_t extra = 0;
        if constexpr (!Io::kDecode) {
            s = 3;
            for (unsigned k = 0; k < 3; ++k)
                if (rep_[k] == want) {
                    s = k;
                    break;
                }
            if (s == 3) s = kOffsetBuckets + bucket_of(want - 1, nb, extra);
        }
        s = io_.sym(kTOffset, s);
        std::uint64_t off;
        if (s < kOffsetBuckets) {
            off = rep_[s];
            for (unsigned k = s; k > 0; --k) rep_[k] = rep_[k - 1];
        } else {
            if constexpr (Io::kDecode) off = 1 + bucket_value(s - kOffsetBuckets, [&](int n) { return io_.raw(n, 0); });
            else {
                io_.raw(nb, extra);
                off = want;
            }
            rep_[2] = rep_[1];
            rep_[1] = rep_[0];
        }
        rep_[0] = off;
        return off;
    }

    // Copies `len` items from `off` items back, one by one (they may overlap).
    // (out of line: inlined into read_table() it made the decoder's copies
    // of window items 5 % more instructions on rep.fc at -L 1)
    [[gnu::flatten, gnu::noinline]] void copy(std::uint64_t off, std::uint64_t len) {
        const std::size_t at = hist_.size(), from = at - static_cast<std::size_t>(off);
        hist_.resize(at + static_cast<std::size_t>(len));
        std::uint32_t* h = hist_.data();
        if (off >= len) std::memcpy(h + at, h + from, static_cast<std::size_t>(len) * sizeof *h);
        else
            for (std::size_t k = 0; k < len; ++k) h[at + k] = h[from + k];  // in order: they overlap
        // The fields' context: the last line segment copied.
        for (std::size_t k = at + static_cast<std::size_t>(len); k > at; --k) {
            const std::uint32_t e = h[k - 1];
            if ((e & ~kIndexMask) == kSegTag && !is_arc(*segs_[e & kIndexMask], ax())) {
                note_fields(*segs_[e & kIndexMask]);
                break;
            }
        }
        prev_shape_ = kNone;
        prev_op_ = kAfterMatch;
    }
};

[[gnu::always_inline]] inline std::uint64_t mix(std::uint64_t h, std::uint64_t v) {
    h ^= v + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    return h * 0xBF58476D1CE4E5B9ull;
}

// The match finder's hash of the keys of three items in a row.
[[gnu::always_inline]] inline std::uint64_t hash_of_three(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
    return mix(mix(a, b), c);
}

// Match key of an item: the tag, then every total and (a segment's) every
// phase mixed in, unused ones included (written out, and inline).
[[gnu::always_inline]] inline std::uint64_t key_of(std::uint32_t tag, const Point& d, const std::array<std::int64_t, kMaxAxes - 1>* ph) {
    static_assert(kMaxAxes == 6);
    auto u = [](std::int64_t v) { return static_cast<std::uint64_t>(v); };
    std::uint64_t h = mix(mix(mix(mix(mix(mix(tag, u(d[0])), u(d[1])), u(d[2])), u(d[3])), u(d[4])), u(d[5]));
    if (ph) {
        const auto& f = *ph;
        h = mix(mix(mix(mix(mix(h, u(f[0])), u(f[1])), u(f[2])), u(f[3])), u(f[4]));
    }
    return h;
}

// Keys of two-axis line segments in canonical form, kept by their totals
// and phase (the only fields such a segment sets) in a direct-mapped table:
// a key is eleven mixes, and most of a block's segments are shapes seen
// shortly before. Gives key_of(0, c.delta, &c.phase).
class LineKeys {
public:
    LineKeys() : e_(std::make_unique<Entry[]>(kSize)) {}
    std::uint64_t operator()(const Segment& c) {
        if ((c.delta[2] | c.delta[3] | c.delta[4] | c.delta[5]) != 0) return key_of(0, c.delta, &c.phase);
        auto u = [](std::int64_t v) { return static_cast<std::uint64_t>(v); };
        const std::uint64_t h = u(c.delta[0]) * 0x9E3779B97F4A7C15ull ^ u(c.delta[1]) * 0xC2B2AE3D27D4EB4Full ^
                                u(c.phase[0]) * 0x165667B19E3779F9ull;
        Entry& e = e_[h >> (64 - kBits)];
        if (e.dx != c.delta[0] || e.dy != c.delta[1] || e.phase != c.phase[0]) {
            e = Entry{c.delta[0], c.delta[1], c.phase[0], key_of(0, c.delta, &c.phase)};
        }
        return e.key;
    }

private:
    static constexpr int kBits = 12;
    static constexpr std::size_t kSize = std::size_t{1} << kBits;
    struct Entry {
        std::int64_t dx = std::numeric_limits<std::int64_t>::min(), dy = 0, phase = 0;  // no segment's totals
        std::uint64_t key = 0;
    };
    std::unique_ptr<Entry[]> e_;
};

// The keys of the shapes at the recent ranks the encoder searches (below
// `search`), counted by their top bits. A segment coded in full is first
// looked for among those ranks, and at the fast levels that search is
// almost always in vain (glyphs-big.fc at -L 1: 2 % found): an item whose
// key has no count there is not among them, without the search.
class SearchedKeys {
public:
    explicit SearchedKeys(std::size_t search)
        : search_(search), bits_(std::clamp(static_cast<int>(std::bit_width(16 * search)), 8, 16)),
          count_(std::size_t{1} << bits_, 0) {}
    bool may_hold(std::uint64_t key) const { return count_[slot(key)] != 0; }
    /// Before `recent` takes a shape at its front (push_front): the shape at
    /// rank search - 1 leaves the searched ranks.
    void before_push(const RecentRing& recent, const std::vector<std::uint64_t>& shape_key) {
        if (search_ > 0 && recent.size() >= search_) --count_[slot(shape_key[recent.at(search_ - 1)])];
    }
    /// After it: the shape of key `key` at rank 0.
    void after_push(std::uint64_t key) {
        if (search_ > 0) ++count_[slot(key)];
    }

private:
    std::size_t slot(std::uint64_t key) const { return static_cast<std::size_t>(key >> (64 - bits_)); }
    std::size_t search_;
    int bits_;
    std::vector<std::uint16_t> count_;  // at most kRecent shapes searched
};

// Segment equality as operator== (every total and phase), without its two
// memcmp calls.
inline bool same_segment(const Segment& a, const Segment& b) {
    static_assert(kMaxAxes == 6);
    auto d = [](std::int64_t x, std::int64_t y) { return static_cast<std::uint64_t>(x ^ y); };
    return (d(a.delta[0], b.delta[0]) | d(a.delta[1], b.delta[1]) | d(a.delta[2], b.delta[2]) |
            d(a.delta[3], b.delta[3]) | d(a.delta[4], b.delta[4]) | d(a.delta[5], b.delta[5]) |
            d(a.phase[0], b.phase[0]) | d(a.phase[1], b.phase[1]) | d(a.phase[2], b.phase[2]) |
            d(a.phase[3], b.phase[3]) | d(a.phase[4], b.phase[4])) == 0;
}

// Normalized frequencies of `count` for precision `prec` (every used symbol
// at least 1, summing to 2^prec) into `f`, at the used symbols `used` (in
// increasing order; the others' entries are left as they are).
void normalize(const std::vector<std::uint32_t>& count, const std::vector<std::uint16_t>& used, std::uint64_t total,
               int prec, std::vector<std::uint32_t>& f) {
    const std::uint32_t want = 1u << prec;
    std::uint32_t sum = 0;
    std::size_t big = 0;
    for (const std::size_t s : used) {
        f[s] = std::max<std::uint32_t>(1, static_cast<std::uint32_t>((std::uint64_t{count[s]} * want) / total));
        sum += f[s];
        if (count[s] > count[big] || count[big] == 0) big = s;
    }
    // Fix the sum: take from or give to the largest symbols first.
    while (sum != want) {
        if (sum < want) {
            f[big] += want - sum;
            sum = want;
        } else {
            std::size_t best = count.size();
            for (const std::size_t s : used)
                if (f[s] > 1 && (best == count.size() || f[s] > f[best])) best = s;
            const std::uint32_t take = std::min(sum - want, f[best] - 1);
            f[best] -= take;
            sum -= take;
        }
    }
}

std::size_t varint_size(std::uint64_t v) {
    std::size_t n = 1;
    while (v >= 0x80) {
        v >>= 7;
        ++n;
    }
    return n;
}

// The table header of `count` at the cheapest precision (header bytes +
// coded bits), appended to `out`; fills the encode table.
void put_table(std::string& out, const std::vector<std::uint32_t>& count, EncodeTable& enc) {
    std::uint64_t total = 0;
    // The used symbols, in increasing order: the loops below go over them
    // only (a table uses a few of its 130 or more symbols).
    std::vector<std::uint16_t> syms;
    for (std::size_t s = 0; s < count.size(); ++s)
        if (count[s] != 0) {
            total += count[s];
            syms.push_back(static_cast<std::uint16_t>(s));
        }
    const auto used = static_cast<unsigned>(syms.size());
    enc.freq.assign(count.size(), 0);
    enc.start.assign(count.size(), 0);
    put_varint(out, used - 1);
    if (used == 1) {
        put_varint(out, syms[0]);
        enc.freq[syms[0]] = 1;
        enc.precision = 0;
        return;
    }
    int best_p = 0;
    double best_cost = 0;
    std::vector<std::uint32_t> f(count.size()), best_f;
    for (int prec = std::bit_width(used - 1); prec <= kMaxPrecision; ++prec) {
        normalize(count, syms, total, prec, f);
        double bits = 0;
        std::size_t header = 0;
        for (const std::size_t s : syms) {
            bits += count[s] * (prec - std::log2(static_cast<double>(f[s])));
            header += varint_size(f[s] - 1);
        }
        const double cost = bits / 8 + static_cast<double>(header);
        if (best_f.empty() || cost < best_cost) {
            best_cost = cost;
            best_p = prec;
            best_f = f;
        }
    }
    out.push_back(static_cast<char>(best_p));
    std::uint32_t start = 0;
    std::size_t prev = 0;
    bool first = true;
    for (const std::size_t s : syms) {
        put_varint(out, first ? s : s - prev - 1);
        put_varint(out, best_f[s] - 1);
        first = false;
        prev = s;
        enc.freq[s] = best_f[s];
        enc.start[s] = start;
        start += best_f[s];
    }
    enc.precision = best_p;
}

// Bytes a table of `count` costs: its header and the symbols' entropy.
double table_bytes(const std::vector<std::uint32_t>& count) {
    std::uint64_t total = 0;
    for (auto c : count) total += c;
    if (total == 0) return 0;
    std::string head;
    EncodeTable enc;
    put_table(head, count, enc);
    double bits = 0;
    for (auto c : count)
        if (c != 0) bits += static_cast<double>(c) * std::log2(static_cast<double>(total) / c);
    return static_cast<double>(head.size()) + bits / 8;
}

// Reads one table header into `d` (the decode table). Errors name the byte.
bool get_table(Cursor& cur, unsigned size, DecodeTable& d) {
    std::uint64_t used;
    if (!cur.varint(used) || used >= size) return false;
    ++used;
    if (used == 1) {
        std::uint64_t s;
        if (!cur.varint(s) || s >= size) return false;
        d.precision = 0;
        d.mask = 0;
        d.slots.assign(1, Slot{static_cast<std::uint16_t>(s), 1, 0});
        return true;
    }
    std::uint8_t prec;
    if (!cur.u8(prec) || prec < 1 || prec > kMaxPrecision || (std::uint64_t{1} << prec) < used) return false;
    d.precision = prec;
    d.mask = (1u << prec) - 1;
    d.slots.resize(std::size_t{1} << prec);
    std::uint64_t s = 0, start = 0;
    for (std::uint64_t k = 0; k < used; ++k) {
        std::uint64_t gap, f1;
        if (!cur.varint(gap) || !cur.varint(f1)) return false;
        s = k == 0 ? gap : s + gap + 1;
        if (gap >= size || s >= size || f1 >= (std::uint64_t{1} << prec) || start + f1 + 1 > (std::uint64_t{1} << prec))
            return false;
        for (std::uint64_t i = 0; i <= f1; ++i)
            d.slots[start + i] = Slot{static_cast<std::uint16_t>(s), static_cast<std::uint16_t>(f1 + 1),
                                      static_cast<std::uint16_t>(i)};
        start += f1 + 1;
    }
    return start == (std::uint64_t{1} << prec);
}

struct BlockHead {
    std::uint64_t nchains = 0, nsegments = 0, nsteps = 0, grid = 1;
};

}  // namespace

const TableItemKeys& window_keys(const WindowBlock& b, Profile p, int axes, TableItemKeys* made) {
    std::call_once(b.table_keys_once, [&] {
        const SegmentItems& w = b.items;
        TableItemKeys& t = b.table_keys;
        if (made && (made->canon_is_items || made->canon.size() == w.segments.size()) &&
            made->keys.size() == w.segments.size() + 2 * w.starts.size()) {
            t = std::move(*made);
        } else {
            t.canon_is_items = std::all_of(w.segments.begin(), w.segments.end(),
                                           [&](const Segment& s) { return is_canonical(p, s, axes); });
            if (!t.canon_is_items) t.canon.reserve(w.segments.size());
            t.keys.reserve(w.segments.size() + 2 * w.starts.size());
            LineKeys line_keys;
            std::size_t k = 0;
            for (std::size_t c = 0; c < w.starts.size(); ++c) {
                t.keys.push_back(key_of(1, w.starts[c], nullptr));
                for (std::uint32_t q = 0; q < w.counts[c]; ++q, ++k) {
                    const Segment* cs = &w.segments[k];
                    if (!t.canon_is_items) {
                        canonical_into(p, w.segments[k], axes, t.canon.emplace_back());
                        cs = &t.canon.back();
                    }
                    t.keys.push_back(axes == 2 ? line_keys(*cs) : key_of(0, cs->delta, &cs->phase));
                }
                t.keys.push_back(2);
            }
        }
        // Made once here, not by every block whose window holds this one.
        const std::vector<std::uint64_t>& keys = t.keys;
        t.hashes.resize(keys.size() < 2 ? 0 : keys.size() - 2);
        for (std::size_t i = 0; i < t.hashes.size(); ++i) t.hashes[i] = hash_of_three(keys[i], keys[i + 1], keys[i + 2]);
    });
    return b.table_keys;
}

std::string write_table_block(const Block& block, Profile p, const std::vector<std::vector<Segment>>& segs,
                              const TableEffort& effort, const WindowView* window, const TableItemKeys* own,
                              TableItemKeys* made, unsigned* type) {
    const int axes = block.axes;
    BlockHead h;
    h.nchains = block.chains.size();
    // The items with their keys.
    Entries items;         // as history entries: index into cs / deltas
    Pointers<Segment> cs;  // canonical segments: the window's (kept with it), then the block's
    std::vector<Point> deltas;
    std::vector<std::uint64_t> keys;
    std::size_t own_segs = 0;
    for (const auto& v : segs) own_segs += v.size();
    const std::size_t own_items = own_segs + 2 * block.chains.size();
    // The window's items first (matches may reach them), then the block's.
    {
        std::size_t nw = 0, ns = 0, nc = 0;
        if (window)
            for (const auto& b : *window) {
                nw += b->items.segments.size() + 2 * b->items.starts.size();
                ns += b->items.segments.size();
                nc += b->items.starts.size();
            }
        items.reserve(nw + own_items);
        keys.reserve(nw + own_items);
        cs.reserve(ns + own_segs);
        deltas.reserve(nc + block.chains.size());
        // The window's entries and segment pointers written in place.
        items.resize(nw);
        cs.resize(ns);
    }
    if (window) {
        std::uint32_t* hp = items.data();
        std::uint32_t si = 0, di = 0;
        for (const auto& b : *window) {
            const SegmentItems& w = b->items;
            const TableItemKeys& t = window_keys(*b, p, axes);
            pointers_to(t.canon_is_items ? w.segments.data() : t.canon.data(), w.segments.size(), cs.data() + si);
            deltas.insert(deltas.end(), w.starts.begin(), w.starts.end());
            keys.insert(keys.end(), t.keys.begin(), t.keys.end());
            hp = window_entries(w, si, di, hp);
        }
    }
    const std::size_t first = items.size(), first_seg = cs.size(), first_start = deltas.size();
    // The block's own keys and canonical segments: from `own` (made by an
    // earlier coding of the same items) when it has their count, else
    // computed here.
    const TableItemKeys* mine = nullptr;
    if (own && (own->canon_is_items || own->canon.size() == own_segs) &&
        own->keys.size() == own_segs + 2 * block.chains.size())
        mine = own;
    // The canonical forms of the block's segments that are not canonical
    // already (the others are pointed at in `segs`), when not from `own`.
    std::vector<Segment> fresh;
    bool own_canonical = true;  // every segment of `segs` is canonical
    {
        auto si = static_cast<std::uint32_t>(cs.size());  // the block's first segment
        if (mine && mine->canon_is_items) {
            for (const auto& v : segs)
                for (const Segment& s : v) cs.push_back(&s);
            keys.insert(keys.end(), mine->keys.begin(), mine->keys.end());
        } else if (mine) {
            cs.resize(si + mine->canon.size());
            pointers_to(mine->canon.data(), mine->canon.size(), cs.data() + si);
            keys.insert(keys.end(), mine->keys.begin(), mine->keys.end());
        } else {
            // Never grows past: cs points into it (only the pages written
            // to are touched).
            fresh.reserve(own_segs);
        }
        LineKeys line_keys;
        const bool eight = profile_eight_connected(p);
        std::uint64_t grid = 0;  // gcd of the start deltas: the grid (1 when none or too large)
        Point ref{};
        for (std::size_t i = 0; i < block.chains.size(); ++i) {
            const Chain& chain = block.chains[i];
            Point d{};
            for (int a = 0; a < axes; ++a) {
                d[a] = wrap_sub(chain.start[a], ref[a]);
                grid = std::gcd(grid, magnitude(d[a]));
            }
            deltas.push_back(d);
            items.push_back(kStartTag | static_cast<std::uint32_t>(deltas.size() - 1));
            if (!mine) keys.push_back(key_of(1, d, nullptr));
            ref = chain.start;
            for (const Segment& s : segs[i]) {
                if (!mine) {
                    const Segment* c = &s;
                    Segment canon;
                    canonical_into(p, s, axes, canon);
                    if (!(canon == s)) {
                        c = &fresh.emplace_back(canon);
                        own_canonical = false;
                    }
                    cs.push_back(c);
                    keys.push_back(axes == 2 ? line_keys(*c) : key_of(0, c->delta, &c->phase));
                }
                items.push_back(kSegTag | si++);
                if (axes == 2 && s.delta[4] == 0) {  // a two-axis line: segment_length() written out
                    const std::uint64_t x = magnitude(s.delta[0]), y = magnitude(s.delta[1]);
                    h.nsteps += eight ? std::max(x, y) : x + y;
                } else {
                    h.nsteps += is_arc(s, axes) ? item_steps(s, p, axes)
                                                : static_cast<std::uint64_t>(segment_length(s.delta, axes, eight));
                }
                if (axes == 2) {
                    ref[0] = wrap_add(ref[0], s.delta[0]);
                    ref[1] = wrap_add(ref[1], s.delta[1]);
                } else {
                    for (int a = 0; a < axes; ++a) ref[a] = wrap_add(ref[a], s.delta[a]);
                }
            }
            items.push_back(kEndTag);
            if (!mine) keys.push_back(2);
        }
        h.nsegments = own_segs;
        h.grid = grid == 0 || grid > (std::uint64_t{1} << 62) ? 1 : grid;
    }
    auto same = [&](std::size_t a, std::size_t b) {
        if (keys[a] != keys[b]) return false;
        const std::uint32_t x = items[a], y = items[b];
        if ((x & ~kIndexMask) != (y & ~kIndexMask)) return false;
        if ((x & ~kIndexMask) == kSegTag) return same_segment(*cs[x & kIndexMask], *cs[y & kIndexMask]);
        if ((x & ~kIndexMask) == kStartTag) return deltas[x & kIndexMask] == deltas[y & kIndexMask];
        return true;
    };
    const std::size_t n = items.size();
    auto match_len = [&](std::size_t i, std::size_t j) {
        std::size_t l = 0;
        while (i + l < n && same(i + l, j + l)) ++l;
        return l;
    };

    // One coding of the items, with minor totals raw or predicted: its
    // symbols and extra bits, and the method of its arcs (-1: none).
    struct Pass {
        EncSide io;
        bool raw_minors = false;
        int arc_method = -1;
    };
    // `axes_tag`: the coder's kAxes, 2 on two axes (the decoder's coder there).
    auto run = [&](bool raw_minors, auto axes_tag) {
    auto pass = std::make_unique<Pass>();
    pass->raw_minors = raw_minors;
    EncSide& io = pass->io;
    TableCoder<EncSide, decltype(axes_tag)::value> coder(io, p, axes);
    coder.raw_minors_ = raw_minors;
    coder.grid_ = static_cast<std::int64_t>(h.grid);
    if (window) {
        coder.prime_from(cs, items, deltas, first_seg, first, first_start, own_segs, n - first);
    } else {
        coder.segs_.reserve(own_segs);
        coder.hist_.reserve(n);
    }
    // A few symbols an item (a segment in full: its operation, lead, minor
    // totals and phases): room for them, not grown (and copied) on the way.
    io.syms.reserve((n - first) * static_cast<std::size_t>(2 + axes));
    // Shape keys by id, for the encoder's searches.
    std::vector<std::uint64_t> shape_key;
    shape_key.reserve(own_segs);
    coder.shape_.reserve(own_segs);
    coder.succ_.reserve(own_segs + 1);
    auto shape_is = [&](std::uint32_t id, std::size_t item) {
        return shape_key[id] == keys[item] && same_segment(*coder.segs_[coder.shape_[id]], *cs[items[item] & kIndexMask]);
    };

    const int hash_bits = std::clamp(static_cast<int>(std::bit_width(n)) + 1, 10, 22);
    std::vector<std::uint32_t> table(std::size_t{1} << hash_bits, 0);
    // The block's own entries' hashes when `mine` holds them (window_keys()
    // made them for the block's contribution: the same three keys), else
    // computed.
    const std::uint64_t* own_hashes = mine && mine->hashes.size() + 2 == n - first ? mine->hashes.data() : nullptr;
    auto hash3 = [&](std::size_t i) {
        const std::uint64_t v =
            own_hashes && i >= first ? own_hashes[i - first] : hash_of_three(keys[i], keys[i + 1], keys[i + 2]);
        return static_cast<std::size_t>(v >> (64 - hash_bits));
    };
    auto insert = [&](std::size_t i) {
        if (i + 3 <= n) table[hash3(i)] = static_cast<std::uint32_t>(i + 1);
    };
    const std::size_t min_match = static_cast<std::size_t>(std::max(3, effort.min_match));
    const std::size_t min_rep = static_cast<std::size_t>(std::max(1, effort.min_rep_match));
    const std::size_t search = static_cast<std::size_t>(std::clamp(effort.recent_search, 0, static_cast<int>(kRecent)));
    SearchedKeys searched(search);

    if (window) {
        // The window's entries in order, by the hashes kept with their
        // blocks; the last two of a block read the next block's keys.
        std::size_t i = 0;
        for (const auto& b : *window) {
            const TableItemKeys& t = window_keys(*b, p, axes);
            for (const std::uint64_t v : t.hashes)
                table[static_cast<std::size_t>(v >> (64 - hash_bits))] = static_cast<std::uint32_t>(++i);
            for (const std::size_t end = i + t.keys.size() - t.hashes.size(); i < end; ++i) insert(i);
        }
    }
    for (std::size_t i = first; i < n;) {
        // A match: a repeat offset first, then the hash candidate.
        std::size_t len = 0, off = 0;
        std::size_t rep_len[3] = {0, 0, 0};  // (0 for a repeat offset past the start)
        for (int r = 0; r < 3; ++r) {
            const std::uint64_t o = coder.rep_[static_cast<std::size_t>(r)];
            if (o > i) continue;
            const std::size_t l = rep_len[r] = match_len(i, i - o);
            if (l > len) {
                len = l;
                off = o;
            }
        }
        if (len < min_rep) len = 0;
        if (i + 3 <= n) {
            const std::size_t hh = hash3(i);
            const std::uint32_t cand = table[hh];
            table[hh] = static_cast<std::uint32_t>(i + 1);
            if (cand != 0) {
                const std::size_t j = cand - 1;
                // At a repeat offset the length is the one just measured.
                const int r = i - j == coder.rep_[0] ? 0 : i - j == coder.rep_[1] ? 1 : i - j == coder.rep_[2] ? 2 : -1;
                const std::size_t l = r >= 0 ? rep_len[r] : match_len(i, j);
                if (l >= min_match && l > len + 2) {
                    len = l;
                    off = i - j;
                }
            }
        }
        if (len > 0) {
            unsigned s = 0;
            int nb;
            std::uint64_t extra;
            s = bucket_of(len - 1, nb, extra);
            coder.code_op(kOpMatch + s);
            io.raw(nb, extra);
            coder.code_offset(off);
            coder.copy(off, len);
            for (std::size_t k = 1; k < len; ++k) insert(i + k);
            i += len;
            continue;
        }
        const std::uint32_t e = items[i];
        const std::uint32_t kind = e & ~kIndexMask;
        if (kind == kStartTag) {
            coder.code_op(kOpStart);
            Point d{};
            coder.code_start(deltas[e & kIndexMask], d);
        } else if (kind == kEndTag) {
            coder.code_op(kOpEnd);
            coder.code_end();
        } else if (is_arc(*cs[e & kIndexMask], axes)) {
            const Segment& want = *cs[e & kIndexMask];
            if (coder.arc_method_ < 0) coder.arc_method_ = static_cast<int>(want.delta[5]);
            const unsigned op = arc_ccw(want) ? kOpArc + 1 : kOpArc;
            coder.code_op(op);
            coder.code_arc(op, &want);
        } else {
            const SuccList& sl = coder.succ_[coder.prev_shape_ + 1];
            std::uint32_t r = 0;
            while (r < sl.size && !shape_is(sl.id[r], i)) ++r;
            if (r < sl.size) {
                const std::uint32_t id = sl.id[r];
                coder.code_op(kOpSucc + r);
                searched.before_push(coder.recent_, shape_key);
                coder.take_shape(id, false, 0);
                searched.after_push(shape_key[id]);
            } else {
                const std::size_t lim = std::min(search, coder.recent_.size());
                std::size_t q = searched.may_hold(keys[i]) ? 0 : lim;
                while (q < lim && !shape_is(coder.recent_.at(q), i)) ++q;
                if (q < lim) {
                    int nb;
                    std::uint64_t extra;
                    coder.code_op(coder.rec_op(q, nb, extra));
                    io.raw(nb, extra);
                    coder.take_shape(coder.recent_.at(q), true, q);
                } else {
                    const Segment& want = *cs[e & kIndexMask];
                    unsigned op = kOpFull;
                    if (axes == 2) {
                        const int lead = leading_axis(want.delta, 2);
                        unsigned neg = 0;
                        for (int a = 0; a < 2; ++a)
                            if (want.delta[a] < 0) neg |= 1u << a;
                        op = kOpFull + static_cast<unsigned>((kOctantOf[lead * 4 + static_cast<int>(neg)] - coder.prev_oct_) & 7);
                    } else {
                        const int lead = leading_axis(want.delta, axes);
                        unsigned dir = static_cast<unsigned>(lead) << 6;
                        for (int a = 0; a < axes; ++a)
                            if (want.delta[a] < 0) dir |= 1u << a;
                        op = kOpFull + (dir != coder.prev_dir_);
                    }
                    coder.code_op(op);
                    searched.before_push(coder.recent_, shape_key);
                    coder.code_full(op, &want);
                    shape_key.push_back(keys[i]);
                    searched.after_push(keys[i]);
                }
            }
        }
        ++i;
    }
    pass->arc_method = coder.arc_method_;
    return pass;
    };
    auto code = [&](bool raw_minors) {
        return axes == 2 ? run(raw_minors, std::integral_constant<int, 2>{})
                         : run(raw_minors, std::integral_constant<int, 0>{});
    };
    const bool try_raw = effort.minors != MinorCoding::predicted;
    auto pass = code(try_raw);
    if (effort.minors == MinorCoding::smaller) {
        // The other coding's minor tables and extra bits, estimated from the
        // symbols this pass saw, against this pass's.
        const EncSide& io = pass->io;
        double coded = static_cast<double>(io.minor_bits) / 8, other = static_cast<double>(io.alt_minor_bits) / 8;
        for (int c = 0; c < 12; ++c) {
            coded += table_bytes(io.count[static_cast<std::size_t>(kTMinor + c)]);
            const auto& a = io.alt_minor[static_cast<std::size_t>(c)];
            other += table_bytes(std::vector<std::uint32_t>(a.begin(), a.end()));
        }
        if (other < coded) pass = code(!try_raw);
    }
    EncSide& io = pass->io;

    std::string out;
    if (pass->raw_minors) {
        put_u8(out, kTableSubtype);
        put_u8(out, kTableRawMinors);
    }
    if (type) *type = pass->raw_minors ? kExtended : kTable;
    put_varint(out, h.nchains);
    put_varint(out, h.nsegments);
    put_varint(out, h.nsteps);
    put_varint(out, h.grid);
    put_layout(out, block.layout);
    std::array<EncodeTable, kTables> enc;
    std::uint64_t used = 0;
    for (int t = 0; t < kTables; ++t)
        for (auto c : io.count[static_cast<std::size_t>(t)]) used |= std::uint64_t{c != 0} << t;
    // A block that codes arcs: the flag, the method byte, and operation
    // tables of 92 symbols; any other block is written as before arcs were.
    const bool arcs = pass->arc_method >= 0;
    if (arcs) used |= std::uint64_t{1} << kTArcFlag;
    put_varint(out, used);
    if (arcs) put_u8(out, static_cast<unsigned>(pass->arc_method));
    for (int t = 0; t < kTables; ++t)
        if ((used >> t) & 1) {
            std::vector<std::uint32_t>& count = io.count[static_cast<std::size_t>(t)];
            if (!arcs) count.resize(alphabet(t, false));
            put_table(out, count, enc[static_cast<std::size_t>(t)]);
        }
    const std::string stream = rans_encode(io.syms, enc);
    const std::string extra_bits = io.bits.finish();
    out.reserve(out.size() + 10 + stream.size() + extra_bits.size());
    put_varint(out, stream.size());
    out += stream;
    out += extra_bits;
    if (made && !mine) {
        made->canon_is_items = own_canonical;
        made->canon.clear();
        if (!own_canonical) {  // the window's copy: every segment's canonical form
            made->canon.reserve(own_segs);
            for (std::size_t k = first_seg; k < cs.size(); ++k) made->canon.push_back(*cs[k]);
        }
        if (first == 0) made->keys = std::move(keys);
        else made->keys.assign(keys.begin() + static_cast<std::ptrdiff_t>(first), keys.end());
    }
    return out;
}

namespace {

// The decoder's loop; kAxes: the axis count fixed at compile time (2), or
// 0 for any count.
template <int kAxes>
Result<void> read_table(std::string_view payload, Profile p, int axes_in, bool expand, Block& out, BlockCounts& counts,
                        const std::string& where, const WindowView* window, SegmentItems* items, bool raw_minors) {
    const int axes = kAxes ? kAxes : axes_in;
    Cursor cur(payload);
    auto error = [&](Errc code, std::size_t at, const std::string& what) {
        return make_error(code, where + " byte " + std::to_string(at) + ": " + what);
    };
    // Block type 7: the subtype and its flags come first.
    std::uint8_t skip;
    if (raw_minors && (!cur.u8(skip) || !cur.u8(skip))) return error(Errc::corrupt, cur.pos(), "bad payload header");
    BlockHead h;
    if (!cur.varint(h.nchains) || !cur.varint(h.nsegments) || !cur.varint(h.nsteps))
        return error(Errc::corrupt, cur.pos(), "bad payload header");
    if (h.nchains > kMaxBlockChains || h.nsegments > kMaxBlockSteps || h.nsteps > kMaxBlockSteps)
        return error(Errc::limit, raw_minors ? 2 : 0, "payload declares more chains, segments or steps than the limits");
    const std::size_t grid_at = cur.pos();
    if (!cur.varint(h.grid) || h.grid == 0 || h.grid > (std::uint64_t{1} << 62))
        return error(Errc::corrupt, grid_at, "bad start grid");
    auto layout = get_layout(cur, where);
    if (!layout) return std::move(layout).error();
    std::array<DecodeTable, kTables> tables;
    std::uint64_t used;
    const std::size_t used_at = cur.pos();
    if (!cur.varint(used) || (used >> (kTArcFlag + 1)) != 0) return error(Errc::corrupt, used_at, "bad table set");
    const bool arcs = (used >> kTArcFlag) & 1;
    if (!arcs && (used >> kLineTables) != 0) return error(Errc::corrupt, used_at, "bad table set");
    if (arcs && axes != 2) return error(Errc::corrupt, used_at, "arcs in a frame of " + std::to_string(axes) + " axes");
    std::uint8_t method = 0;
    const std::size_t method_at = cur.pos();
    if (arcs && (!cur.u8(method) || method >= kArcMethods)) return error(Errc::corrupt, method_at, "bad arc method");
    for (int t = 0; t < kTables; ++t) {
        const std::size_t at = cur.pos();
        if (((used >> t) & 1) && !get_table(cur, alphabet(t, arcs), tables[static_cast<std::size_t>(t)]))
            return error(Errc::corrupt, at, "bad table " + std::to_string(t));
    }
    std::uint64_t rans_size;
    const std::size_t size_at = cur.pos();
    std::string_view rans_bytes;
    if (!cur.varint(rans_size) || rans_size > cur.left() || !cur.bytes(static_cast<std::size_t>(rans_size), rans_bytes))
        return error(Errc::corrupt, size_at, "bad rANS stream size");
    const std::size_t rans_at = cur.pos() - rans_bytes.size();
    const std::size_t bits_at = cur.pos();
    DecSide io{std::move(tables), RansDecoder(rans_bytes), BitReader(payload.substr(bits_at))};
    TableCoder<DecSide, kAxes> coder(io, p, axes);
    coder.grid_ = static_cast<std::int64_t>(h.grid);
    if (arcs) coder.arc_method_ = method;
    coder.raw_minors_ = raw_minors;
    start_output(out, expand, axes, std::move(*layout));
    // Chains decoded before (the window's table blocks' and this block's),
    // by the history position of their start item, oldest first: a match
    // that copies one whole copies its steps instead of expanding its
    // segments again (the same items give the same steps).
    struct WholeChain {
        std::size_t at, items;          // the start item's position; start, segments and end
        bool arcs;                      // holds an arc item (those go through take)
        const Step* steps;              // its steps (a chain's vector keeps its buffer when moved)
        std::size_t n;
        const Segment* segs;            // a window chain's segments, in order (its block's items); else null
    };
    std::vector<WholeChain> whole;
    // The declared chains, within what the payload's size can plausibly hold.
    const auto starts = static_cast<std::size_t>(std::min<std::uint64_t>(h.nchains, 8 * payload.size() + 64));
    {
        // Room for the declared items, within what the payload's size can
        // plausibly hold (a match of a few bits may copy many items).
        const std::size_t plausible = 64 * payload.size() + 1024;
        const auto segs = static_cast<std::size_t>(std::min<std::uint64_t>(h.nsegments, plausible));
        const std::size_t hist = segs + static_cast<std::size_t>(std::min<std::uint64_t>(2 * h.nchains, plausible));
        if (window) {
            coder.prime(*window, segs, hist, starts);
            if (expand) {
                // The window's chains that a match may copy whole, at the
                // history positions prime() gave their items.
                std::size_t at = 0, n = 0;
                for (const auto& b : *window) n += b->chains.size();
                whole.reserve(n + starts);
                for (const auto& b : *window) {
                    const SegmentItems& w = b->items;
                    const bool kept = b->chains.size() == w.starts.size();
                    const Segment* segs = w.segments.data();
                    for (std::size_t k = 0; k < w.starts.size(); ++k) {
                        const std::size_t items_k = std::size_t{w.counts[k]} + 2;
                        if (kept) whole.push_back(WholeChain{at, items_k, w.arcs, b->chains[k].steps.data(), b->chains[k].steps.size(), segs});
                        at += items_k;
                        segs += w.counts[k];
                    }
                }
            }
        } else {
            coder.segs_.reserve(segs);
            coder.hist_.reserve(hist);
        }
        coder.shape_.reserve(std::min<std::size_t>(segs, 8 * payload.size()));
        coder.succ_.reserve(std::min<std::size_t>(segs, 8 * payload.size()) + 1);
        if (expand) out.chains.reserve(starts);
    }
    if (items) {
        std::vector<Segment> room = std::move(items->segments);  // a caller's spare memory, kept
        room.clear();
        *items = SegmentItems{};
        items->segments = std::move(room);
        // As declared, within what the payload's size can plausibly hold
        // plus what its matches may copy from the window (whose segments the
        // decoder holds already): a block that repeats its window is a few
        // bytes, and growing the array by doubling took twice its size at
        // the peak (rep.fc at -L 1: 100 of the decoder's 145 MB).
        const std::uint64_t plausible_segs = 8 * payload.size() + coder.segs_.size();
        items->segments.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(h.nsegments, plausible_segs)));
        items->starts.reserve(starts);
        items->counts.reserve(starts);
    }
    // Items the block may add after the window's.
    const std::uint64_t max_items = coder.hist_.size() + h.nsegments + 2 * h.nchains;
    auto fail = [&](const char* what) {
        if (coder.error_) what = coder.error_;
        if (io.bits.failed) return error(Errc::corrupt, bits_at + io.bits.pos(), std::string(what) + " (extra bits)");
        return error(Errc::corrupt, rans_at + io.rans.pos(), what);
    };
    const bool eight = profile_eight_connected(p);
    std::uint64_t chains = 0, seen_segments = 0, seen_steps = 0;
    bool in_chain = false;
    Chain chain;
    Point ref{}, pos{};
    std::vector<Step> arc_scratch, spill;
    std::size_t chain_steps = 0;  // steps of the chain, in `steps` or at `chain_from`
    // A whole-chain copy's steps: the earlier chain's, copied into the chain
    // at its end (not through `steps`); else null.
    const Step* chain_from = nullptr;
    std::size_t chain_at = 0;     // the history position of its start item
    bool chain_arcs = false;      // it holds an arc item
    // The buffer's first size: the block's mean chain length.
    StepBuffer steps(static_cast<std::size_t>(
        std::clamp<std::uint64_t>(h.nsteps / std::max<std::uint64_t>(h.nchains, 1), 16, 1 << 16)));
    // Takes a line segment (not an arc) into the output (inline at both
    // calls).
    auto take_line = [&](const Segment& seg) __attribute__((always_inline)) -> const char* {
        if (!in_chain) return "segment outside a chain";
        const auto n = static_cast<std::uint64_t>(segment_length(seg.delta, axes, eight));
        if (seen_segments == h.nsegments || seen_steps + n > h.nsteps) return "more segments or steps than declared";
        ++seen_segments;
        seen_steps += n;
        for (int a = 0; a < axes; ++a) pos[a] += seg.delta[a];
        if (expand) {
            const std::size_t need = chain_steps + static_cast<std::size_t>(n);
            Step* o = steps.room(chain_steps, static_cast<std::size_t>(n));
            const bool fast = kAxes == 2 ? detail::expand_two_axis_into(p, seg, o)
                                         : detail::expand_segment_into(p, seg, axes, o);
            if (!fast) {
                spill.clear();
                expand_segment(p, seg, axes, spill);
                if (spill.size() != n) return "segment expands to another step count";
                std::copy(spill.begin(), spill.end(), o);
            }
            chain_steps = need;
        }
        if (items) {
            items->segments.push_back(seg);
            ++items->counts.back();
        }
        return nullptr;
    };
    // Takes history entry `e` (a decoded or copied item, at history position
    // `at`) into the output.
    auto take = [&](std::uint32_t e, std::size_t at) __attribute__((flatten)) -> const char* {
        const std::uint32_t kind = e & ~kIndexMask;
        if (kind == kStartTag) {
            if (in_chain) return "chain start inside a chain";
            if (chains == h.nchains) return "more chains than declared";
            ++chains;
            in_chain = true;
            chain = Chain{};
            chain.axes = axes;
            chain_steps = 0;
            chain_from = nullptr;
            chain_at = at;
            chain_arcs = false;
            const Point& d = *coder.starts_[e & kIndexMask];
            if (!rebuild_start(ref, d, axes, chain.start)) return "chain start out of range";
            pos = chain.start;
            if (items) {
                items->starts.push_back(d);
                items->counts.push_back(0);
            }
        } else if (kind == kEndTag) {
            if (!in_chain) return "chain end outside a chain";
            in_chain = false;
            ref = pos;
            if (expand) {
                const Step* from = chain_from ? chain_from : steps.data();
                chain.steps.assign(from, from + chain_steps);
                out.chains.push_back(std::move(chain));
                const std::vector<Step>& done = out.chains.back().steps;
                whole.push_back(WholeChain{chain_at, at - chain_at + 1, chain_arcs, done.data(), done.size(), nullptr});
            }
        } else {
            if (!in_chain) return "segment outside a chain";
            const Segment& seg = *coder.segs_[e & kIndexMask];
            if (is_arc(seg, axes)) {
                // Drawn to count its steps; its bound first, so that no arc
                // draws more than the block declares.
                if (seen_segments == h.nsegments || arc_step_bound(seg.delta[2], seg.delta[3]) > h.nsteps)
                    return "arc may draw more steps than declared";
                arc_scratch.clear();
                if (!draw_arc_item(seg, arc_scratch)) return "arc the interpolator refuses";
                const auto n = static_cast<std::uint64_t>(arc_scratch.size());
                if (seen_steps + n > h.nsteps) return "more segments or steps than declared";
                if (expand) {
                    std::copy(arc_scratch.begin(), arc_scratch.end(), steps.room(chain_steps, arc_scratch.size()));
                    chain_steps += arc_scratch.size();
                }
                ++seen_segments;
                seen_steps += n;
                chain_arcs = true;
                pos[0] += seg.delta[0];
                pos[1] += seg.delta[1];
                if (items) {
                    items->segments.push_back(seg);
                    ++items->counts.back();
                    items->arcs = true;
                }
                return nullptr;
            }
            return take_line(seg);
        }
        return nullptr;
    };
    // Takes the copied chain at history position `at`, the same items as the
    // earlier chain `c` (no arc among them): its start and end as take()
    // does, its segments counted and entered into the block's items (a
    // window chain's as one range, without a look-up each), its steps
    // copied from `c`'s.
    auto take_whole = [&](std::size_t at, const WholeChain& c) __attribute__((flatten)) -> const char* {
        if (const char* bad = take(coder.hist_[at], at)) return bad;
        const std::size_t nseg = c.items - 2;
        if (seen_segments + nseg > h.nsegments || seen_steps + c.n > h.nsteps)
            return "more segments or steps than declared";
        seen_segments += nseg;
        seen_steps += c.n;
        if (c.segs) {
            // A window chain's segments: in one piece in its block's items.
            for (std::size_t q = 0; q < nseg; ++q)
                for (int a = 0; a < axes; ++a) pos[a] += c.segs[q].delta[a];
            if (items) items->segments.insert(items->segments.end(), c.segs, c.segs + nseg);
        } else {
            // One of the block's: its segments through the history.
            const std::uint32_t* e = coder.hist_.data() + at + 1;
            for (std::size_t q = 0; q < nseg; ++q) {
                const Segment& seg = *coder.segs_[e[q] & kIndexMask];
                for (int a = 0; a < axes; ++a) pos[a] += seg.delta[a];
                if (items) items->segments.push_back(seg);
            }
        }
        if (items) items->counts.back() += static_cast<std::uint32_t>(nseg);
        chain_from = c.steps;
        chain_steps = c.n;
        return take(coder.hist_[at + c.items - 1], at + c.items - 1);
    };
    while (in_chain || chains < h.nchains) {
        const unsigned op = coder.code_op(0);
        if (io.failed || io.rans.failed) return fail("bad operation");
        if (op == kOpEnd) {
            coder.code_end();
        } else if (op == kOpStart) {
            Point d{};
            coder.code_start(Point{}, d);
        } else if (op < kOpRec) {
            const SuccList& sl = coder.succ_[coder.prev_shape_ + 1];
            if (op - kOpSucc >= sl.size) return fail("successor rank beyond the list");
            coder.take_shape(sl.id[op - kOpSucc], false, 0);
        } else if (op < kOpFull) {
            std::size_t r = op - kOpRec;
            if (op >= kOpRecBucket) {
                const int k = static_cast<int>((op - kOpRecBucket) / 2) + 3;
                r = (std::size_t{1} << k) | (std::size_t{(op - kOpRecBucket) & 1} << (k - 1)) |
                    static_cast<std::size_t>(io.raw(k - 1, 0));
            }
            if (r >= coder.recent_.size()) return fail("recent rank beyond the list");
            coder.take_shape(coder.recent_.at(r), true, r);
        } else if (op < kOpMatch) {
            if (!coder.code_full(op, nullptr)) return fail("bad segment");
        } else if (op >= kOpArc) {
            if (!coder.code_arc(op, nullptr)) return fail("bad arc");
        } else {
            const std::uint64_t len = 1 + bucket_value(op - kOpMatch, [&](int n) { return io.raw(n, 0); });
            const std::uint64_t off = coder.code_offset(0);
            if (io.failed || io.rans.failed || io.bits.failed) return fail("bad match");
            if (off > coder.hist_.size()) return fail("match offset before the window");
            if (len > max_items - coder.hist_.size()) return fail("match longer than the block");
            const std::size_t from = coder.hist_.size();
            coder.copy(off, len);
            for (std::size_t k = from; k < coder.hist_.size(); ++k) {
                const std::uint32_t e = coder.hist_[k];
                if (expand && (e & ~kIndexMask) == kStartTag) {
                    // A whole chain copied from one decoded before: its steps.
                    const std::size_t src = k - static_cast<std::size_t>(off);
                    const auto c = std::lower_bound(whole.begin(), whole.end(), src,
                                                    [](const WholeChain& w, std::size_t v) { return w.at < v; });
                    if (c != whole.end() && c->at == src && !c->arcs && c->items <= coder.hist_.size() - k) {
                        const WholeChain w = *c;  // take_whole adds to `whole`
                        if (const char* bad = take_whole(k, w)) return fail(bad);
                        k += w.items - 1;
                        continue;
                    }
                }
                // A copied line segment straight to take_line (as take does).
                const Segment* seg = (e & ~kIndexMask) == kSegTag ? coder.segs_[e & kIndexMask] : nullptr;
                const char* bad = seg && !is_arc(*seg, axes) ? take_line(*seg) : take(e, k);
                if (bad) return fail(bad);
            }
            continue;
        }
        if (io.failed || io.rans.failed || io.bits.failed) return fail("bad item");
        if (coder.hist_.size() > max_items) return fail("more items than declared");
        // A shape's segment is a line; start, end and arc items go through take.
        const char* e = op >= kOpSucc && op < kOpMatch ? take_line(*coder.segs_.back())
                                                       : take(coder.hist_.back(), coder.hist_.size() - 1);
        if (e) return fail(e);
    }
    if (seen_segments != h.nsegments || seen_steps != h.nsteps) return fail("declared segment or step count does not match");
    if (!io.rans.finished()) return fail("rANS stream does not end at its size");
    if (!io.bits.finished()) return error(Errc::corrupt, bits_at + io.bits.pos(), "extra bits do not end at the payload's end");
    counts.chains += h.nchains;
    counts.segments += h.nsegments;
    counts.steps += h.nsteps;
    return {};
}

}  // namespace

Result<void> read_table_block(std::string_view payload, Profile p, int axes, bool expand, Block& out,
                              BlockCounts& counts, const std::string& where, const WindowView* window,
                              SegmentItems* items, unsigned type) {
    bool raw = false;
    if (type == kExtended) {
        // docs/FORMAT.md 1.10.2: the subtype, then its flags.
        if (payload.empty() || static_cast<unsigned char>(payload[0]) != kTableSubtype)
            return make_error(Errc::corrupt, where + " byte 0: unknown subtype of an extended block");
        if (payload.size() < 2 || static_cast<unsigned char>(payload[1]) != kTableRawMinors)
            return make_error(Errc::corrupt, where + " byte 1: bad table flags");
        raw = true;
    }
    if (axes == 2) return read_table<2>(payload, p, axes, expand, out, counts, where, window, items, raw);
    return read_table<0>(payload, p, axes, expand, out, counts, where, window, items, raw);
}

}  // namespace stepzip::stz
