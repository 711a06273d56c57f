// The digital-straight-segment kernel under the two hull-based two-letter
// word recognizers (not installed): WordRecognizer (a letter at a time,
// 128-bit) and RunWord (a run at a time, 64-bit). Each keeps only what
// differs: how a letter or a run arrives and what it answers. (The greedy
// two-axis cut, two_axis.hpp, uses the arithmetic recognition instead.)
//
// A position (p, q) counts the zeros and ones read before a letter. The word
// is a DSS while some slope lies strictly between lo = the largest slope from
// a 0-position to a later 1-position and hi = the smallest slope from a
// 1-position to a later 0-position. The candidates are the vertices of the
// lower hull of the 0-positions and of the upper hull of the 1-positions
// (both arrive in increasing p, so each hull is a monotone-chain stack), and
// a tangent or a support point is found by binary search along a hull (the
// slope seen from an outside point is unimodal along a convex chain).
// Sources: Debled-Rennesson & Reveillès 1995 (here in its dual, hull form).
// Complexity: O(log h) per tangent or support query, amortized O(1) per hull
// push, h = hull vertices (O(log n) for a DSS of n letters).
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <vector>

#include "stepzip/profile.hpp"

// The run-at-a-time hot path (RunWord) keeps these inside its loop.
#if defined(__GNUC__)
#define STEPZIP_DSS_INLINE [[gnu::always_inline]] inline
#else
#define STEPZIP_DSS_INLINE inline
#endif

namespace stepzip::detail::dss {

/// A position: zeros (p) and ones (q) read before a letter. The functions
/// below take any point type P with members p and q.
struct Pt {
    std::int64_t p, q;
};

/// Cross product of (b - a) and (c - a), in W (std::int64_t when every
/// coordinate is at most 2^30 + 1, else a 128-bit type).
template <class W, class P>
W cross(const P& a, const P& b, const P& c) {
    return W(b.p - a.p) * (c.q - a.q) - W(b.q - a.q) * (c.p - a.p);
}

/// n1/d1 < n2/d2 for positive denominators.
template <class W>
bool less(std::int64_t n1, std::int64_t d1, std::int64_t n2, std::int64_t d2) {
    return W(n1) * d2 < W(n2) * d1;
}

/// Appends c to the lower hull of the 0-positions.
template <class W, class P>
STEPZIP_DSS_INLINE void push_lower(std::vector<P>& h, P c) {
    std::size_t z = h.size();
    while (z >= 2 && cross<W>(h[z - 2], h[z - 1], c) <= 0) --z;
    h.resize(z);
    h.push_back(c);
}

/// Appends c to the upper hull of the 1-positions (one point per column:
/// a later point in the same column replaces the earlier one).
template <class W, class P>
STEPZIP_DSS_INLINE void push_upper(std::vector<P>& h, P c) {
    std::size_t z = h.size();
    if (z > 0 && h[z - 1].p == c.p) --z;
    while (z >= 2 && cross<W>(h[z - 2], h[z - 1], c) >= 0) --z;
    h.resize(z);
    h.push_back(c);
}

/// The smallest slope n/d from a vertex of the upper hull `h` strictly left
/// of c to c (a new 0 at c: the bound hi). False when there is none.
template <class W, class P>
STEPZIP_DSS_INLINE bool min_slope_to(const std::vector<P>& h, P c, std::int64_t& n, std::int64_t& d) {
    std::size_t m = h.size();
    if (m > 0 && h[m - 1].p == c.p) --m;
    if (m == 0) return false;
    std::size_t a = 0, b = m - 1;
    while (a < b) {
        const std::size_t mid = (a + b) / 2;
        if (less<W>(c.q - h[mid + 1].q, c.p - h[mid + 1].p, c.q - h[mid].q, c.p - h[mid].p)) a = mid + 1;
        else b = mid;
    }
    n = c.q - h[a].q;
    d = c.p - h[a].p;
    return true;
}

/// The largest slope n/d from a vertex of the lower hull `h` (all strictly
/// left of c) to c (a new 1 at c: the bound lo). False when `h` is empty.
template <class W, class P>
STEPZIP_DSS_INLINE bool max_slope_to(const std::vector<P>& h, P c, std::int64_t& n, std::int64_t& d) {
    if (h.empty()) return false;
    std::size_t a = 0, b = h.size() - 1;
    while (a < b) {
        const std::size_t mid = (a + b) / 2;
        if (less<W>(c.q - h[mid].q, c.p - h[mid].p, c.q - h[mid + 1].q, c.p - h[mid + 1].p)) a = mid + 1;
        else b = mid;
    }
    n = c.q - h[a].q;
    d = c.p - h[a].p;
    return true;
}

// Run-at-a-time state (RunWord): 64-bit arithmetic. Every
// coordinate, numerator and denominator is at most the word length + 1 <=
// kMaxSegmentTotal + 1 = 2^30 + 1, so every product of two of them, and
// every sum or difference of two products, fits in 64 bits.
static_assert(kMaxSegmentTotal <= (std::int64_t{1} << 30));
using wide = std::int64_t;

inline wide floor_div(wide a, wide b) {  // b > 0
    return a >= 0 ? a / b : -((-a + b - 1) / b);
}
inline wide ceil_div(wide a, wide b) { return -floor_div(-a, b); }

/// A slope n/d. The bounds below hold sentinels instead of "unset" flags:
/// lo = -1/1 and r = 0/1 (no bound: numerator <= 0), hi = 1/0 and s = 1/0
/// (+infinity: denominator 0).
struct Frac {
    std::int64_t n, d;
};

/// The hulls and slope bounds of a word read run by run. Besides lo and hi,
/// r = max u.q / (u.p + 1) over the 1-positions u and s = min (z.q + 1) / z.p
/// over the 0-positions z with z.p > 0 bound the word's own slope inside a
/// run (see run_word.hpp for why runs suffice).
/// Invariant: (lo, hi) is exactly the set of slopes that admit a phase for
/// the word read so far; the hulls change only by a run's end points.
struct RunState {
    std::vector<Pt> zeros_hull;  // lower hull of the 0-positions
    std::vector<Pt> ones_hull;   // upper hull of the 1-positions (top point per column)
    Frac lo{-1, 1}, hi{1, 0}, r{0, 1}, s{1, 0};
    std::int64_t p = 0, q = 0;  // zeros and ones read

    void reset() noexcept {
        zeros_hull.clear();
        ones_hull.clear();
        lo = {-1, 1};
        hi = {1, 0};
        r = {0, 1};
        s = {1, 0};
        p = q = 0;
    }

    /// Zeros at (p + j, q), j = 0..k-1: how many keep the word a DSS. Zero
    /// j kills it iff slope(u, (p + j, q)) <= lo for some 1-position u, i.e.
    /// lo.n * j >= (q - u.q) * lo.d - lo.n * (p - u.p): the smallest such j
    /// comes from the u maximizing lo.d * u.q - lo.n * u.p, a support point
    /// of the upper hull. A division only when the run is cut.
    std::int64_t zeros_alive(std::int64_t k) const noexcept {
        if (lo.n <= 0 || ones_hull.empty()) return k;
        const auto& h = ones_hull;
        std::size_t a = 0, b = h.size() - 1;
        while (a < b) {
            const std::size_t mid = (a + b) / 2;
            const wide rise = wide(lo.d) * (h[mid + 1].q - h[mid].q) - wide(lo.n) * (h[mid + 1].p - h[mid].p);
            if (rise > 0) a = mid + 1;
            else b = mid;
        }
        const wide val = wide(q - h[a].q) * lo.d - wide(lo.n) * (p - h[a].p);
        if (wide(lo.n) * (k - 1) < val) return k;
        return std::clamp<wide>(ceil_div(val, lo.n), 0, k);
    }

    /// Ones at (p, q + j): one j kills the word iff slope(z, (p, q + j)) >= hi
    /// for some 0-position z, i.e. hi.d * j >= hi.n * (p - z.p) - hi.d * (q - z.q);
    /// the z minimizing hi.d * z.q - hi.n * z.p is a support point of the lower hull.
    std::int64_t ones_alive(std::int64_t k) const noexcept {
        if (hi.d <= 0 || zeros_hull.empty()) return k;
        const auto& h = zeros_hull;
        std::size_t a = 0, b = h.size() - 1;
        while (a < b) {
            const std::size_t mid = (a + b) / 2;
            const wide fall = wide(hi.d) * (h[mid + 1].q - h[mid].q) - wide(hi.n) * (h[mid + 1].p - h[mid].p);
            if (fall < 0) a = mid + 1;
            else b = mid;
        }
        const wide val = wide(hi.n) * (p - h[a].p) - wide(hi.d) * (q - h[a].q);
        if (wide(hi.d) * (k - 1) < val) return k;
        return std::clamp<wide>(ceil_div(val, hi.d), 0, k);
    }

    /// A run of k letters `letter`: how many keep the word a DSS.
    std::int64_t alive(int letter, std::int64_t k) const noexcept {
        return letter == 0 ? zeros_alive(k) : ones_alive(k);
    }

    /// The bounds on x, the run letter's count after a prefix of the run,
    /// under which the word ends valid: x * b1 < a1 and x * b2 < a2 (upper
    /// bounds; none when b <= 0, and then a > 0) and x * c > e (lower bound).
    /// Zeros (x = P, q ones): lo < q/P, P * r < q, q/P < hi. Ones (x = Q, p
    /// zeros): Q/p < hi, Q * s < p, lo < Q/p. Precondition: the other
    /// letter's count is non-zero.
    struct Bounds {
        wide b1, a1, b2, a2, c, e;
    };
    Bounds bounds(int letter) const noexcept {
        if (letter == 0) return {lo.n, wide(q) * lo.d, r.n, wide(q) * r.d, hi.n, wide(q) * hi.d};
        return {hi.d, wide(hi.n) * p, s.d, wide(p) * s.n, lo.d, wide(lo.n) * p};
    }

    /// Appends a run of k >= 1 zeros. Its interior zeros are never hull
    /// vertices and never give an extreme tangent (every 1-position left of
    /// the run sees its last zero at a smaller slope); its first zero is kept
    /// on the hull as the letter-by-letter hull keeps it.
    STEPZIP_DSS_INLINE void commit_zeros(std::int64_t k) {
        if (k >= 2) push_lower<wide>(zeros_hull, {p, q});
        const Pt c{p + k - 1, q};
        std::int64_t n, d;
        if (min_slope_to<wide>(ones_hull, c, n, d) && wide(n) * hi.d < wide(hi.n) * d) hi = {n, d};
        push_lower<wide>(zeros_hull, c);
        if (c.p > 0 && wide(q + 1) * s.d < wide(s.n) * c.p) s = {q + 1, c.p};
        p += k;
    }

    /// Appends a run of k >= 1 ones (only its top point joins the hull).
    STEPZIP_DSS_INLINE void commit_ones(std::int64_t k) {
        const Pt c{p, q + k - 1};
        std::int64_t n, d;
        if (max_slope_to<wide>(zeros_hull, c, n, d) && wide(lo.n) * d < wide(n) * lo.d) lo = {n, d};
        push_upper<wide>(ones_hull, c);
        if (wide(r.n) * (p + 1) < wide(c.q) * r.d) r = {c.q, p + 1};
        q += k;
    }
};

/// The phase nearest the profile's default in [lo, hi) ∩ phase_range(p, a, b),
/// or nullopt when that is empty.
inline std::optional<std::int64_t> pick_phase(Profile p, std::int64_t a, std::int64_t b,
                                              std::int64_t lo, std::int64_t hi) {
    const PhaseRange range = phase_range(p, a, b);
    lo = std::max(lo, range.lo);
    hi = std::min(hi, range.hi);
    if (lo >= hi) return std::nullopt;
    return std::clamp(default_phase(p, a, b), lo, hi - 1);
}

}  // namespace stepzip::detail::dss
