// Greedy cut of two-axis chains under a linear profile. See two_axis.hpp.
#include "two_axis.hpp"

#include <algorithm>
#include <cassert>
#include <limits>

namespace stepzip::detail {

using dss::floor_div;
using dss::wide;

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
}  // namespace

TwoAxisGreedy::TwoAxisGreedy(Profile p) : profile_(p), eight_(profile_eight_connected(p)) {
    assert(p != Profile::patent);
}

// A run of k letters (see RunWord::probe): the largest valid prefix is the
// largest count x within the upper bounds, if it passes the lower one; the
// whole run is tried first by multiplications, a division only if it fails.
STEPZIP_DSS_INLINE std::int64_t TwoAxisGreedy::read_run(int letter, std::int64_t k, std::int64_t& best) const noexcept {
    const std::int64_t alive = st_.alive(letter, k);
    best = 0;
    if (alive == 0) return 0;
    const std::int64_t x0 = letter == 0 ? st_.p : st_.q;
    if ((letter == 0 ? st_.q : st_.p) == 0) {
        best = alive;
        return alive;
    }
    const dss::RunState::Bounds b = st_.bounds(letter);
    wide x = x0 + alive;
    if (!(b.b1 * x < b.a1 && b.b2 * x < b.a2)) {
        if (b.b1 > 0) x = std::min(x, floor_div(b.a1 - 1, b.b1));
        if (b.b2 > 0) x = std::min(x, floor_div(b.a2 - 1, b.b2));
        if (x - x0 < 1) return alive;
    }
    if (x * b.c > b.e) best = x - x0;
    return alive;
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
    // A balanced word of kShortLetters letters: the state after its
    // leading runs (all but the last, which may go on past them) from the
    // table, then the runs from there.
    short_ = false;
    const Resume& r = resume_table()[bits];
    st_.assign(r.st);
    runs_.assign(r.runs.begin(), r.runs.end());
    first_letter_ = r.first_letter;
    std::int64_t best = r.best, length = r.length;
    best_count_[0] = r.best_count[0];
    best_count_[1] = r.best_count[1];
    auto pos = static_cast<std::size_t>(length);
    while (pos < n) {
        const Step s = st[pos];
        const int letter = letter_of(s, eight_);
        if (value_[letter] != s && !admit(value_, s, letter, eight_)) break;
        std::size_t e = pos + 1;
        while (e < n && st[e] == s) ++e;
        if (!take_run(letter, static_cast<std::int64_t>(e - pos), length, best)) break;
        pos = e;
    }
    return best;
}

void TwoAxisGreedy::start_runs(int first) {
    st_.reset();
    runs_.clear();
    first_letter_ = first;
    best_count_[first] = 1;
    best_count_[1 - first] = 0;
}

STEPZIP_DSS_INLINE bool TwoAxisGreedy::take_run(int letter, std::int64_t k, std::int64_t& length, std::int64_t& best) {
    runs_.push_back(k);
    const std::int64_t kk = std::min(k, kMaxSegmentTotal - length);
    if (kk <= 0) return false;
    std::int64_t in_run;
    const std::int64_t alive = read_run(letter, kk, in_run);
    if (in_run > 0) {
        best = length + in_run;
        best_count_[0] = st_.p + (letter == 0 ? in_run : 0);
        best_count_[1] = st_.q + (letter == 1 ? in_run : 0);
    }
    if (alive < k) return false;
    if (letter == 0) st_.commit_zeros(k);
    else st_.commit_ones(k);
    length += k;
    return true;
}

// The Resume of every balanced word of kShortLetters letters, made once by
// reading its leading runs as longest() reads them (the state depends on
// the letters only, not on the profile or the step values); other words'
// entries stay empty.
const std::vector<TwoAxisGreedy::Resume>& TwoAxisGreedy::resume_table() {
    static const std::vector<Resume> table = [] {
        std::vector<Resume> t(std::size_t{1} << kShortLetters);
        TwoAxisGreedy g(Profile::eval4);
        for (unsigned w = 0; w < (1u << kShortLetters); ++w) {
            if ((short_words().entry[w] & kBalanced) == 0) continue;
            g.start_runs(static_cast<int>(w & 1u));
            std::int64_t best = 1, length = 0;
            // Every run but the last: a balanced word is a DSS at every
            // prefix, so each run is read whole.
            int at = 0;
            while (true) {
                const int letter = static_cast<int>((w >> at) & 1u);
                int e = at + 1;
                while (e < kShortLetters && static_cast<int>((w >> e) & 1u) == letter) ++e;
                if (e == kShortLetters) break;
                const bool whole = g.take_run(letter, e - at, length, best);
                assert(whole);
                (void)whole;
                at = e;
            }
            Resume& r = t[w];
            r.st = g.st_;
            r.first_letter = g.first_letter_;
            r.runs = g.runs_;
            r.best = best;
            r.best_count[0] = g.best_count_[0];
            r.best_count[1] = g.best_count_[1];
            r.length = length;
        }
        return t;
    }();
    return table;
}

namespace {
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
    const auto f = dss::pick_phase(profile_, fa, b, lo, hi);
    if (!f) return std::nullopt;
    seg.phase[0] = *f;
    return seg;
}

}  // namespace stepzip::detail
