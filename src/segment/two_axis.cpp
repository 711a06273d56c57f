// Greedy cut of two-axis chains under a linear profile. See two_axis.hpp.
#include "two_axis.hpp"

#include <algorithm>
#include <cassert>
#include <limits>

namespace stepzip::detail {

namespace {
// As in run_word.cpp: every coordinate, numerator and denominator is at most
// kMaxSegmentTotal + 1 <= 2^30 + 1, so products of two and sums of two
// products fit in 64 bits.
static_assert(kMaxSegmentTotal <= (std::int64_t{1} << 30));
using wide = std::int64_t;

wide floor_div(wide a, wide b) {  // b > 0
    return a >= 0 ? a / b : -((-a + b - 1) / b);
}
wide ceil_div(wide a, wide b) { return -floor_div(-a, b); }

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
}  // namespace

TwoAxisGreedy::TwoAxisGreedy(Profile p) : profile_(p), eight_(profile_eight_connected(p)) {
    assert(p != Profile::patent);
    reset();
}

void TwoAxisGreedy::reset() noexcept {
    zeros_hull_.clear();
    ones_hull_.clear();
    lo_ = {-1, 1};
    hi_ = {1, 0};
    r_ = {0, 1};
    s_ = {1, 0};
    p_ = q_ = 0;
}

// Zeros at (p + j, q), j = 0..k-1 (see RunWord::probe_zeros). The valid
// prefixes of the run are the P = p + m with lo < q/P < hi and
// P * r < q: upper bounds on P from lo and r, a lower bound from hi.
inline std::int64_t TwoAxisGreedy::zeros(std::int64_t k, std::int64_t& best) const noexcept {
    const std::int64_t p = p_, q = q_;
    std::int64_t alive = k;
    if (lo_.n > 0 && !ones_hull_.empty()) {
        const auto& h = ones_hull_;
        std::size_t a = 0, b = h.size() - 1;
        while (a < b) {
            const std::size_t mid = (a + b) / 2;
            const wide rise = wide(lo_.d) * (h[mid + 1].q - h[mid].q) -
                              wide(lo_.n) * (h[mid + 1].p - h[mid].p);
            if (rise > 0) a = mid + 1;
            else b = mid;
        }
        // Zero j kills the word iff lo.n * j >= val.
        const wide val = wide(q - h[a].q) * lo_.d - wide(lo_.n) * (p - h[a].p);
        if (wide(lo_.n) * (k - 1) >= val) alive = std::clamp<wide>(ceil_div(val, lo_.n), 0, k);
    }
    best = 0;
    if (alive == 0) return 0;
    if (q == 0) {
        best = alive;
        return alive;
    }
    std::int64_t m = alive;
    const wide P = p + m;
    if (!(lo_.n * P < q * lo_.d && r_.n * P < q * r_.d)) {
        wide pmax = P;
        if (lo_.n > 0) pmax = std::min(pmax, floor_div(q * lo_.d - 1, lo_.n));
        if (r_.n > 0) pmax = std::min(pmax, floor_div(q * r_.d - 1, r_.n));
        m = pmax - p;
        if (m < 1) return alive;
    }
    if ((p + m) * hi_.n > q * hi_.d) best = m;
    return alive;
}

// Ones at (p, q + j) (see RunWord::probe_ones): Q = q + m with
// lo < Q/p < hi and Q * s < p.
inline std::int64_t TwoAxisGreedy::ones(std::int64_t k, std::int64_t& best) const noexcept {
    const std::int64_t p = p_, q = q_;
    std::int64_t alive = k;
    if (hi_.d > 0 && !zeros_hull_.empty()) {
        const auto& h = zeros_hull_;
        std::size_t a = 0, b = h.size() - 1;
        while (a < b) {
            const std::size_t mid = (a + b) / 2;
            const wide fall = wide(hi_.d) * (h[mid + 1].q - h[mid].q) -
                              wide(hi_.n) * (h[mid + 1].p - h[mid].p);
            if (fall < 0) a = mid + 1;
            else b = mid;
        }
        const wide val = wide(hi_.n) * (p - h[a].p) - wide(hi_.d) * (q - h[a].q);
        if (wide(hi_.d) * (k - 1) >= val) alive = std::clamp<wide>(ceil_div(val, hi_.d), 0, k);
    }
    best = 0;
    if (alive == 0) return 0;
    if (p == 0) {
        best = alive;
        return alive;
    }
    std::int64_t m = alive;
    const wide Q = q + m;
    if (!(Q * hi_.d < hi_.n * p && Q * s_.d < p * s_.n)) {
        wide qmax = Q;
        if (hi_.d > 0) qmax = std::min(qmax, floor_div(hi_.n * p - 1, hi_.d));
        if (s_.d > 0) qmax = std::min(qmax, floor_div(p * s_.n - 1, s_.d));
        m = qmax - q;
        if (m < 1) return alive;
    }
    if (lo_.n * p < (q + m) * lo_.d) best = m;
    return alive;
}

inline void TwoAxisGreedy::push_zero(Pt c) {
    // The new upper bound: the smallest slope from a 1-position strictly
    // left of c (tangent to the upper hull).
    std::size_t m = ones_hull_.size();
    if (m > 0 && ones_hull_[m - 1].p == c.p) --m;
    if (m > 0) {
        const Pt* h = ones_hull_.data();
        std::size_t a = 0, b = m - 1;
        while (a < b) {
            const std::size_t mid = (a + b) / 2;
            // slope(h[mid+1], c) < slope(h[mid], c)
            if (wide(c.q - h[mid + 1].q) * (c.p - h[mid].p) <
                wide(c.q - h[mid].q) * (c.p - h[mid + 1].p))
                a = mid + 1;
            else
                b = mid;
        }
        const std::int64_t n = c.q - h[a].q, d = c.p - h[a].p;
        if (wide(n) * hi_.d < wide(hi_.n) * d) hi_ = {n, d};
    }
    std::size_t z = zeros_hull_.size();
    while (z >= 2) {
        const Pt& u = zeros_hull_[z - 2];
        const Pt& v = zeros_hull_[z - 1];
        if (wide(v.p - u.p) * (c.q - u.q) - wide(v.q - u.q) * (c.p - u.p) > 0) break;
        --z;
    }
    zeros_hull_.resize(z);
    zeros_hull_.push_back(c);
}

inline void TwoAxisGreedy::push_one(Pt c) {
    // The new lower bound: the largest slope from a 0-position (all left of c).
    const std::size_t m = zeros_hull_.size();
    if (m > 0) {
        const Pt* h = zeros_hull_.data();
        std::size_t a = 0, b = m - 1;
        while (a < b) {
            const std::size_t mid = (a + b) / 2;
            // slope(h[mid], c) < slope(h[mid+1], c)
            if (wide(c.q - h[mid].q) * (c.p - h[mid + 1].p) <
                wide(c.q - h[mid + 1].q) * (c.p - h[mid].p))
                a = mid + 1;
            else
                b = mid;
        }
        const std::int64_t n = c.q - h[a].q, d = c.p - h[a].p;
        if (wide(lo_.n) * d < wide(n) * lo_.d) lo_ = {n, d};
    }
    std::size_t z = ones_hull_.size();
    if (z > 0 && ones_hull_[z - 1].p == c.p) --z;
    while (z >= 2) {
        const Pt& u = ones_hull_[z - 2];
        const Pt& v = ones_hull_[z - 1];
        if (wide(v.p - u.p) * (c.q - u.q) - wide(v.q - u.q) * (c.p - u.p) < 0) break;
        --z;
    }
    ones_hull_.resize(z);
    ones_hull_.push_back(c);
}

inline void TwoAxisGreedy::commit_zeros(std::int64_t k) {
    if (k >= 2) {
        // The run's first zero joins the hull, but its tangent is never the
        // smallest: every 1-position left of it sees the run's last zero
        // at a smaller slope (same rise, longer run).
        std::size_t z = zeros_hull_.size();
        const Pt c{p_, q_};
        while (z >= 2) {
            const Pt& u = zeros_hull_[z - 2];
            const Pt& v = zeros_hull_[z - 1];
            if (wide(v.p - u.p) * (c.q - u.q) - wide(v.q - u.q) * (c.p - u.p) > 0) break;
            --z;
        }
        zeros_hull_.resize(z);
        zeros_hull_.push_back(c);
    }
    const std::int64_t last = p_ + k - 1;
    push_zero({last, q_});
    if (last > 0 && wide(q_ + 1) * s_.d < wide(s_.n) * last) s_ = {q_ + 1, last};
    p_ += k;
}

inline void TwoAxisGreedy::commit_ones(std::int64_t k) {
    const std::int64_t top = q_ + k - 1;
    push_one({p_, top});
    if (wide(r_.n) * (p_ + 1) < wide(top) * r_.d) r_ = {top, p_ + 1};
    q_ += k;
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

std::int64_t TwoAxisGreedy::longest(std::span<const Step> steps) {
    const std::size_t n = steps.size();
    if (n == 0) return 0;
    const Step* st = steps.data();
    // Short segments (the common case on noisy contours): the letters of up
    // to kShortLetters steps index the table.
    {
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
            const unsigned low = bits & ((1u << m) - 1u);
            short_bits_ = bits;
            short_ = true;
            best_count_[1] = __builtin_popcount(low);
            best_count_[0] = m - best_count_[1];
            return m;
        }
    }
    short_ = false;
    reset();
    runs_.clear();
    value_[0] = value_[1] = 0;
    std::int64_t best = 1, length = 0;
    first_letter_ = letter_of(st[0], eight_);
    best_count_[first_letter_] = 1;
    best_count_[1 - first_letter_] = 0;
    for (std::size_t pos = 0; pos < n;) {
        const Step s = st[pos];
        const int letter = letter_of(s, eight_);
        if (value_[letter] != s && !admit(value_, s, letter, eight_)) break;
        std::size_t e = pos + 1;
        while (e < n && st[e] == s) ++e;
        const auto k = static_cast<std::int64_t>(e - pos);
        runs_.push_back(k);
        const std::int64_t kk = std::min(k, kMaxSegmentTotal - length);
        if (kk <= 0) break;
        std::int64_t in_run;
        const std::int64_t alive = letter == 0 ? zeros(kk, in_run) : ones(kk, in_run);
        if (in_run > 0) {
            best = length + in_run;
            best_count_[0] = p_ + (letter == 0 ? in_run : 0);
            best_count_[1] = q_ + (letter == 1 ? in_run : 0);
        }
        if (alive < k) break;
        if (letter == 0) commit_zeros(k);
        else commit_ones(k);
        length += k;
        pos = e;
    }
    return best;
}

namespace {
std::optional<std::int64_t> pick(Profile p, std::int64_t a, std::int64_t b, std::int64_t lo,
                                 std::int64_t hi) {
    const PhaseRange r = phase_range(p, a, b);
    lo = std::max(lo, r.lo);
    hi = std::min(hi, r.hi);
    if (lo >= hi) return std::nullopt;
    return std::clamp(default_phase(p, a, b), lo, hi - 1);
}
// The signed move of each axis in step s, times n.
void add_moves(Point& d, Step s, std::int64_t n) {
    d[0] += n * step_axis(s, 0);
    d[1] += n * step_axis(s, 1);
}
}  // namespace

std::optional<Segment> TwoAxisGreedy::fit(std::int64_t m) const {
    // Letter counts of the prefix (a, b) = (#zeros, #ones): the rule's
    // counts both for eval4 (|dx|, |dy|) and for the minor axis of the
    // 8-connected profiles (L - S, S).
    std::int64_t cnt[2] = {best_count_[0], best_count_[1]};
    if (m != cnt[0] + cnt[1]) {
        if (short_) return std::nullopt;
        cnt[0] = cnt[1] = 0;
        std::int64_t left = m;
        int letter = first_letter_;
        for (std::size_t i = 0; left > 0 && i < runs_.size(); ++i, letter ^= 1) {
            const std::int64_t k = std::min(left, runs_[i]);
            cnt[letter] += k;
            left -= k;
        }
        if (left > 0) return std::nullopt;
    }
    const std::int64_t a = cnt[0], b = cnt[1];
    Segment seg;
    if (a > 0) add_moves(seg.delta, value_[0], a);
    if (b > 0) add_moves(seg.delta, value_[1], b);
    // The phase arguments of the profile: eval4 (a, b); 8-connected (L, S).
    const std::int64_t fa = eight_ ? a + b : a;
    if (a == 0 || b == 0) {
        seg.phase[0] = default_phase(profile_, fa, b);
        return seg;
    }
    // F0 in [max over 0-positions of p*b - q*a, min over 1-positions); only
    // a run's last letter bounds it (see fit.cpp, word_phases).
    constexpr std::int64_t kInf = std::numeric_limits<std::int64_t>::max();
    std::int64_t lo = -kInf, hi = kInf, p = 0, q = 0, left = m;
    if (short_) {
        for (std::int64_t i = 0; i < m; ++i) {
            if ((short_bits_ >> i) & 1u) {
                hi = std::min(hi, p * b - q * a);
                ++q;
            } else {
                lo = std::max(lo, p * b - q * a);
                ++p;
            }
        }
        left = 0;
    }
    int letter = first_letter_;
    for (std::size_t i = 0; left > 0; ++i, letter ^= 1) {
        const std::int64_t k = std::min(left, runs_[i]);
        left -= k;
        if (letter == 0) {
            lo = std::max(lo, (p + k - 1) * b - q * a);
            p += k;
        } else {
            hi = std::min(hi, p * b - (q + k - 1) * a);
            q += k;
        }
    }
    const auto f = pick(profile_, fa, b, lo, hi);
    if (!f) return std::nullopt;
    seg.phase[0] = *f;
    return seg;
}

}  // namespace stepzip::detail
