// Greedy cut of two-axis chains under a linear profile. See two_axis.hpp.
#include "two_axis.hpp"

#include <algorithm>
#include <cassert>
#include <limits>
#include <numeric>

namespace stepzip::detail {

namespace {
// Words of up to kShortLetters letters are decided by a table made once, on
// first use (about 10^6 simple operations: too many for some compilers'
// constant evaluation). A word with totals (A, B) is exact iff the values
// s = A*q - B*p over its positions (p, q), end point included, span at most
// A + B - 1 (with F0 = -(min s + B), a 0 at s_k >= min + B and a 1 below
// it reproduce the word; conversely every s lies in [-F0 - B, -F0 + A)).
// An exact word is a factor of the periodic word the rule draws, hence
// balanced; so once a prefix is unbalanced no longer prefix is exact.
// Entry: bit j (1..kShortLetters) set iff the prefix of length j is exact;
// bit 15 set iff the whole word is balanced (a longer prefix may be exact).
constexpr int kShortLetters = 12;
constexpr std::uint16_t kBalanced = 0x8000;

struct ShortWords {
    std::uint16_t entry[1u << kShortLetters];
};

ShortWords make_short_words() {
    ShortWords t{};
    constexpr int n = kShortLetters;
    for (unsigned w = 0; w < (1u << n); ++w) {
        int ones[n + 1] = {};  // ones[i]: ones among the first i letters
        for (int i = 0; i < n; ++i) ones[i + 1] = ones[i] + static_cast<int>((w >> i) & 1u);
        unsigned e = 0;
        for (int j = 1; j <= n; ++j) {
            const int b = ones[j], a = j - b;
            int lo = 0, hi = 0;
            for (int i = 1; i <= j; ++i) {
                const int v = a * ones[i] - b * (i - ones[i]);
                lo = v < lo ? v : lo;
                hi = v > hi ? v : hi;
            }
            if (hi - lo < a + b) e |= 1u << j;
        }
        bool balanced = true;
        for (int len = 1; len < n && balanced; ++len) {
            int lo = len, hi = 0;
            for (int start = 0; start + len <= n; ++start) {
                const int v = ones[start + len] - ones[start];
                lo = v < lo ? v : lo;
                hi = v > hi ? v : hi;
            }
            balanced = hi - lo <= 1;
        }
        t.entry[w] = static_cast<std::uint16_t>(e | (balanced ? kBalanced : 0u));
    }
    return t;
}

const ShortWords& short_words() {
    static const ShortWords table = make_short_words();  // thread-safe initialization
    return table;
}

// x-step of eval4 / axis step of the 8-connected profiles -> letter 0.
inline int letter_of(Step s, bool eight) {
    return eight ? ((s & 0x5u) == 0x5u ? 1 : 0) : ((s & 1u) != 0 ? 0 : 1);
}

// Debled-Rennesson's arithmetic recognition of a 4-connected digital
// straight segment (Debled-Rennesson & Reveilles 1995), on the lattice path
// whose letter 0 is a step in x and letter 1 a step in y. After each letter
// the path's points M_0..M_n lie in the strip mu <= a*x - b*y <= mu + a + b - 1
// of its minimal characteristics (a, b, mu); U_f, U_l (L_f, L_l) are the
// first and last points on its upper (lower) edge. A letter whose point
// leaves the strip by one turns the strip about the opposite first leaning
// point; by more, the word is no longer a digital straight segment.
//
// The prefix M_0..M_n is exact (the rule with counts (P, Q) = M_n draws it)
// iff the values f(M) = Q*x - P*y over its points span at most P + Q - 1
// (the short-word table's test). The strip's lines of that slope are bounded
// by the four leaning points alone (the preimage of a digital straight
// segment is the polygon they define: Dorst & Smeulders 1984; f is largest
// at a lower one, smallest at an upper one), so the span over them and
// M_0, M_n (where f is 0) decides it. The points of an edge are one period
// (b, a) apart: the last leaning points are kept as counts of periods past
// the first ones, whose f moves by one of their coordinates per letter.
// Complexity: O(1) per letter (two products for the test, a few more
// where the strip turns). Range: M_0 (r = 0) is in the strip, so |r| <= a + b
// at every point, and with at most kMaxSegmentTotal = 2^30 letters every
// coordinate, count of periods and f fits, products included, in 64 bits.
static_assert(kMaxSegmentTotal <= (std::int64_t{1} << 30));
struct Strip {
    std::int64_t mx, my;  // M_n
    std::int64_t a, b;    // the strip's direction (b, a)
    std::int64_t r, rel;  // r = a*mx - b*my at M_n, rel = r - mu
    // The first leaning points, the last ones as k * (b, a) past them (the
    // points of an edge are one period apart), and f at U_f, L_f for
    // (P, Q) = M_n; f at U_f + k * (b, a) is f(U_f) - k * r.
    std::int64_t ufx, ufy, lfx, lfy, ku, kl;
    std::int64_t fuf, flf;
    // What a letter adds to r (and rel), fuf and flf, by letter (a 0 moves
    // x: f falls by each point's y; a 1 moves y: f rises by x): one indexed
    // load each instead of a choice per letter. Set by moves().
    struct Move {
        std::int64_t r, fu, fl;
    } move[2];

    void moves() {
        move[0] = {a, -ufy, -lfy};
        move[1] = {-b, ufx, lfx};
    }

    // M_0 and the first letter.
    void start(int first) {
        mx = first == 0 ? 1 : 0;
        my = first;
        a = first;
        b = 1 - first;
        r = rel = 0;
        ufx = ufy = lfx = lfy = 0;
        ku = kl = 1;
        fuf = flf = 0;
        moves();
    }

    // A first leaning point (x, y, its f) moved to the last one, k periods on.
    void to_last(std::int64_t& f, std::int64_t& x, std::int64_t& y, std::int64_t k) const {
        f -= k * r;
        x += k * b;
        y += k * a;
    }

    // The strip turned about the first leaning point (x, y) to M_n.
    void turn(std::int64_t x, std::int64_t y) {
        a = my - y;
        b = mx - x;
        r = a * mx - b * my;
        moves();
    }

    // Appends a letter; false when the word stops being a digital straight
    // segment (the strip is then no longer meaningful).
    STEPZIP_DSS_INLINE bool add(int letter) {
        const Move& d = move[letter];
        mx += 1 - letter;
        my += letter;
        r += d.r;
        rel += d.r;
        fuf += d.fu;
        flf += d.fl;
        const std::int64_t w = a + b;
        if (rel > 0 && rel < w - 1) return true;  // strictly inside: most letters
        if (rel == 0 || rel == w - 1) {
            ku += rel == 0 ? 1 : 0;      // M_n is the next upper leaning point
            kl += rel == w - 1 ? 1 : 0;  // the next lower one
        } else if (rel == -1) {  // above by one: turn about U_f (U_l = M_n, L_f = old L_l)
            to_last(flf, lfx, lfy, kl);
            turn(ufx, ufy);
            rel = 0;
            ku = 1;
            kl = 0;
        } else if (rel == w) {  // below by one: turn about L_f (L_l = M_n, U_f = old U_l)
            to_last(fuf, ufx, ufy, ku);
            turn(lfx, lfy);
            rel = a + b - 1;
            ku = 0;
            kl = 1;
        } else {
            return false;
        }
        return true;
    }

    // The least f over the word's points (at an upper leaning point or 0).
    std::int64_t lowest() const { return std::min(fuf + std::min(-ku * r, std::int64_t{0}), std::int64_t{0}); }

    // The word read so far is exact.
    bool exact() const {
        const std::int64_t hi = std::max(flf + std::max(-kl * r, std::int64_t{0}), std::int64_t{0});
        return hi - lowest() < mx + my;
    }
};

// The strip after each balanced word of kShortLetters letters (the words
// that longest() reads on from): an index by word, the strips.
struct Resume {
    std::uint8_t index[1u << kShortLetters];
    std::vector<Strip> strip;
};

const Resume& resume_table() {
    static const Resume table = [] {
        Resume t{};
        const ShortWords& sw = short_words();
        for (unsigned w = 0; w < (1u << kShortLetters); ++w) {
            if ((sw.entry[w] & kBalanced) == 0) continue;
            Strip st;
            st.start(static_cast<int>(w & 1u));
            for (int k = 1; k < kShortLetters; ++k) {
                const bool dss = st.add(static_cast<int>((w >> k) & 1u));
                assert(dss);  // a balanced word is a digital straight segment
                (void)dss;
            }
            assert(t.strip.size() < 256);
            t.index[w] = static_cast<std::uint8_t>(t.strip.size());
            t.strip.push_back(st);
        }
        return t;
    }();
    return table;
}
}  // namespace

TwoAxisGreedy::TwoAxisGreedy(Profile p) : profile_(p), eight_(profile_eight_connected(p)) {
    assert(p != Profile::patent);
}

// The first step of a letter in a segment: signs are fixed per letter, and
// for the 8-connected profiles the axis step must be a projection of the
// diagonal. Records the value; false when the step cannot join.
inline bool admit(Step (&value)[2], Step s, int letter, bool eight) {
    if (value[letter] != 0) return false;
    const Step other = value[1 - letter];
    if (eight && other != 0) {
        const Step d = letter == 1 ? s : other, x = letter == 1 ? other : s;
        const unsigned mask = (x & 0x3u) != 0 ? 0x3u : 0xCu;
        if ((d & mask) != x) return false;
    }
    value[letter] = s;
    return true;
}

namespace {
// An exact prefix: its length (0: none), its ones and the least f over its
// points (Strip::lowest).
struct Exact {
    std::int64_t length = 0, ones = 0, lowest = 0;
};

// The last exact prefix among the first begin + 1 .. end letters: from
// `strip`, the strip after the first `begin`, the letters of steps
// [begin, end), all admitted with letter 1's value v1 and together a
// digital straight segment.
Exact last_exact(Strip strip, const Step* st, std::size_t begin, std::size_t end, Step v1) {
    Exact best;
    for (std::size_t i = begin; i < end; ++i) {
        strip.add(st[i] == v1 ? 1 : 0);
        if (strip.exact()) best = {static_cast<std::int64_t>(i + 1), strip.my, strip.lowest()};
    }
    return best;
}

// The longest exact prefix of the first n > kShortLetters steps longer than
// kShortLetters (length 0: none), whose first kShortLetters letters left
// `from`; `value` holds the letters' step values (admit). kEight: the
// profile is 8-connected.
//
// Only the last exact prefix counts, so the letters are read to the end of
// the digital straight segment without the exactness test (about half the
// work per letter), keeping the strip every kMarkEvery letters for the last
// kMarks such stretches; then the stretches are read again with the test,
// newest first, until one holds an exact prefix. Exact prefixes are dense
// on drawn lines: mostly the last stretch alone is read again. When none of
// the kept stretches holds one, the letters before them are read again from
// `from`.
template <bool kEight>
Exact read_letters(Step (&value)[2], const Step* st, std::size_t n, const Strip& from) {
    constexpr std::size_t kMarkEvery = 16, kMarks = 8;
    // mark[c % kMarks]: the strip after kShortLetters + c * kMarkEvery letters.
    Strip mark[kMarks];
    std::size_t marks = 0;
    // The step values in locals, the strip in registers.
    Step v0 = value[0], v1 = value[1];
    Strip strip = from;
    std::size_t i = kShortLetters;
    for (bool dss = true; dss && i < n;) {
        mark[marks++ % kMarks] = strip;
        for (const std::size_t end = std::min(i + kMarkEvery, n); i < end; ++i) {
            const Step s = st[i];
            // A step is 0 (unset) in neither value: those it equals give its letter.
            int letter = s == v1 ? 1 : 0;
            if (letter == 0 && s != v0) {
                letter = letter_of(s, kEight);
                dss = admit(value, s, letter, kEight);
                if (!dss) break;
                v0 = value[0];
                v1 = value[1];
            }
            dss = strip.add(letter);
            if (!dss) break;
        }
    }
    // The first i letters are a digital straight segment.
    const std::size_t kept = std::min(marks, kMarks);
    for (std::size_t c = marks; c > marks - kept; --c) {
        const std::size_t begin = kShortLetters + (c - 1) * kMarkEvery;
        const Exact e = last_exact(mark[(c - 1) % kMarks], st, begin, std::min(begin + kMarkEvery, i), v1);
        if (e.length > 0) return e;
    }
    return last_exact(from, st, kShortLetters, kShortLetters + (marks - kept) * kMarkEvery, v1);
}
}  // namespace

std::int64_t TwoAxisGreedy::longest(std::span<const Step> steps) {
    const std::size_t n = steps.size();
    if (n == 0) return 0;
    const Step* st = steps.data();
    // Short segments (the common case on noisy contours): the letters of up
    // to kShortLetters steps index the table.
    value_[0] = value_[1] = 0;
    const std::size_t lim = std::min<std::size_t>(n, kShortLetters);
    unsigned bits = 0;
    std::size_t i = 0;
    for (; i < lim; ++i) {
        const Step s = st[i];
        const int letter = letter_of(s, eight_);
        if (value_[letter] != s && !admit(value_, s, letter, eight_)) break;
        bits |= static_cast<unsigned>(letter) << i;
    }
    const unsigned e = short_words().entry[bits];
    if (i < static_cast<std::size_t>(kShortLetters) || (e & kBalanced) == 0) {
        const unsigned valid = e & ((2u << i) - 1u) & ~1u;
        const int m = 31 - __builtin_clz(valid);  // bit 1 is always set
        best_length_ = m;
        best_ones_ = __builtin_popcount(bits & ((1u << m) - 1u));
        best_lowest_.reset();
        return m;
    }
    // Longer words: the arithmetic recognition (Strip) from the strip of
    // the first kShortLetters letters, a letter at a time.
    const std::size_t lim_all = std::min<std::size_t>(n, static_cast<std::size_t>(kMaxSegmentTotal));
    const Resume& t = resume_table();
    const Strip& from = t.strip[t.index[bits]];
    const Exact x =
        eight_ ? read_letters<true>(value_, st, lim_all, from) : read_letters<false>(value_, st, lim_all, from);
    if (x.length > 0) {
        best_length_ = x.length;
        best_ones_ = x.ones;
        best_lowest_ = x.lowest;
    } else {  // the table's answer
        const int m = 31 - __builtin_clz(e & ((2u << kShortLetters) - 2u));
        best_length_ = m;
        best_ones_ = __builtin_popcount(bits & ((1u << m) - 1u));
        best_lowest_.reset();
    }
    return best_length_;
}

namespace {
// The signed move of each axis in step s, times n.
void add_moves(Point& d, Step s, std::int64_t n) {
    d[0] += n * step_axis(s, 0);
    d[1] += n * step_axis(s, 1);
}
}  // namespace

std::optional<Segment> TwoAxisGreedy::fit(std::span<const Step> steps, std::int64_t m) const {
    if (m < 1 || static_cast<std::size_t>(m) > steps.size()) return std::nullopt;
    const Step* st = steps.data();
    // Letter counts of the prefix (a, b) = (#zeros, #ones): the rule's
    // counts both for eval4 (|dx|, |dy|) and for the minor axis of the
    // 8-connected profiles (L - S, S).
    // Every step of the prefix is one of the two values longest() admitted.
    const Step one = value_[1];
    std::int64_t b = best_ones_;
    if (m != best_length_) {
        b = 0;
        for (std::int64_t i = 0; i < m; ++i) b += st[i] == one ? 1 : 0;
    }
    const std::int64_t a = m - b;
    Segment seg;
    if (a > 0) add_moves(seg.delta, value_[0], a);
    if (b > 0) add_moves(seg.delta, value_[1], b);
    // The phase arguments of the profile: eval4 (a, b); 8-connected (L, S).
    const std::int64_t fa = eight_ ? a + b : a;
    if (a == 0 || b == 0) {
        seg.phase[0] = default_phase(profile_, fa, b);
        return seg;
    }
    // F0 in [max over 0-positions of p*b - q*a, min over 1-positions) (see
    // fit.cpp, word_phases); v = p*b - q*a moves by b at a 0, by -a at a 1.
    // v is Strip's f for (P, Q) = (a, b). When longest() found the prefix by
    // the arithmetic recognition it knows the least v, and that decides both
    // bounds: an exact prefix is the rule's word, periodic with period m / g
    // (g = gcd(a, b)); its values of v at positions 0..m-1 are
    // v_i = i*b - q_i*m (mod m: multiples of g), span less than m, so they
    // are the m / g values least, least + g, ..., each g times; the a zeros
    // take the a / g least ones.
    std::int64_t lo, hi;
    if (m == best_length_ && best_lowest_) {
        const std::int64_t g = std::gcd(a, b);
        lo = *best_lowest_ + a - g;
        hi = *best_lowest_ + a;
    } else {
        constexpr std::int64_t kInf = std::numeric_limits<std::int64_t>::max();
        lo = -kInf;
        hi = kInf;
        std::int64_t v = 0;
        for (std::int64_t i = 0; i < m; ++i) {
            if (st[i] == one) {
                hi = std::min(hi, v);
                v -= a;
            } else {
                lo = std::max(lo, v);
                v += b;
            }
        }
    }
    const auto f = dss::pick_phase(profile_, fa, b, lo, hi);
    if (!f) return std::nullopt;
    seg.phase[0] = *f;
    return seg;
}

}  // namespace stepzip::detail
