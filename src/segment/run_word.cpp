// Run-at-a-time two-letter word recognition. See run_word.hpp.
#include "run_word.hpp"

#include <algorithm>
#include <cassert>

namespace stepzip::detail {

namespace {
// Every coordinate, numerator and denominator below is at most the word
// length + 1 <= kMaxSegmentTotal + 1 = 2^30 + 1, so every product of two of
// them, and every sum or difference of two products, fits in 64 bits.
using wide = std::int64_t;
static_assert(kMaxSegmentTotal <= (std::int64_t{1} << 30));

template <class P>
wide cross(const P& a, const P& b, const P& c) {
    return wide(b.p - a.p) * (c.q - a.q) - wide(b.q - a.q) * (c.p - a.p);
}
// n1/d1 < n2/d2 for positive denominators.
bool less(std::int64_t n1, std::int64_t d1, std::int64_t n2, std::int64_t d2) {
    return wide(n1) * d2 < wide(n2) * d1;
}
wide floor_div(wide a, wide b) {  // b > 0
    return a >= 0 ? a / b : -((-a + b - 1) / b);
}
wide ceil_div(wide a, wide b) { return -floor_div(-a, b); }
std::int64_t clamp64(wide v, std::int64_t lo, std::int64_t hi) { return std::clamp(v, lo, hi); }
}  // namespace

void RunWord::reset() noexcept {
    zeros_hull_.clear();
    ones_hull_.clear();
    lo_ = hi_ = r_ = s_ = {};
    p_ = q_ = 0;
}

RunWord::Probe RunWord::probe(int letter, std::int64_t k) const noexcept {
    return letter == 0 ? probe_zeros(k) : probe_ones(k);
}

// Zeros at (p + j, q), j = 0..k-1; after j + 1 of them the word has
// P = p + j + 1 zeros and q ones.
RunWord::Probe RunWord::probe_zeros(std::int64_t k) const noexcept {
    const std::int64_t p = p_, q = q_;
    std::int64_t alive = k;
    if (lo_.set && lo_.n > 0 && !ones_hull_.empty()) {
        // Zero j kills the word iff slope(u, (p + j, q)) <= lo for some
        // 1-position u, i.e. ln * j >= (q - u.q) * ld - ln * (p - u.p): the
        // smallest such j comes from the u maximizing ld * u.q - ln * u.p,
        // a support point of the upper hull (unimodal along it).
        const auto& h = ones_hull_;
        std::size_t a = 0, b = h.size() - 1;
        while (a < b) {
            const std::size_t mid = (a + b) / 2;
            const wide rise = wide(lo_.d) * (h[mid + 1].q - h[mid].q) -
                              wide(lo_.n) * (h[mid + 1].p - h[mid].p);
            if (rise > 0) a = mid + 1;
            else b = mid;
        }
        const wide val = wide(q - h[a].q) * lo_.d - wide(lo_.n) * (p - h[a].p);
        alive = clamp64(ceil_div(val, lo_.n), 0, k);
    }
    if (alive == 0) return {0, 1, 0};
    if (q == 0) return {alive, 1, alive};
    // Bounds on P: lo < q/P < hi (the bound before the run) and, for the
    // tangents added by the run, P * u.q < q * (u.p + 1) for every u.
    wide pmin = 1, pmax = wide(p) + alive;
    if (lo_.set && lo_.n > 0) pmax = std::min(pmax, floor_div(wide(q) * lo_.d - 1, lo_.n));
    if (hi_.set) pmin = std::max(pmin, floor_div(wide(q) * hi_.d, hi_.n) + 1);
    if (r_.set && r_.n > 0) pmax = std::min(pmax, floor_div(wide(q) * r_.d - 1, r_.n));
    return {alive, clamp64(pmin - p, 1, k + 1), clamp64(pmax - p, 0, alive)};
}

// Ones at (p, q + j); after j + 1 of them: p zeros and Q = q + j + 1 ones.
RunWord::Probe RunWord::probe_ones(std::int64_t k) const noexcept {
    const std::int64_t p = p_, q = q_;
    std::int64_t alive = k;
    if (hi_.set && !zeros_hull_.empty()) {
        // One j kills the word iff slope(z, (p, q + j)) >= hi for some
        // 0-position z: hd * j >= hn * (p - z.p) - hd * (q - z.q); the z
        // minimizing hd * z.q - hn * z.p is a support point of the lower hull.
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
        alive = clamp64(ceil_div(val, hi_.d), 0, k);
    }
    if (alive == 0) return {0, 1, 0};
    if (p == 0) return {alive, 1, alive};
    // Bounds on Q: lo < Q/p < hi and Q * z.p < p * (z.q + 1) for every z.
    wide qmin = 1, qmax = wide(q) + alive;
    if (hi_.set) qmax = std::min(qmax, floor_div(wide(hi_.n) * p - 1, hi_.d));
    if (lo_.set) qmin = std::max(qmin, floor_div(wide(lo_.n) * p, lo_.d) + 1);
    if (s_.set) qmax = std::min(qmax, floor_div(wide(p) * s_.n - 1, s_.d));
    return {alive, clamp64(qmin - q, 1, k + 1), clamp64(qmax - q, 0, alive)};
}

void RunWord::push_zero(Pt c) {
    // New upper bound: the smallest slope from a 1-position strictly left of c.
    std::size_t m = ones_hull_.size();
    if (m > 0 && ones_hull_[m - 1].p == c.p) --m;
    if (m > 0) {
        const auto& h = ones_hull_;
        auto num = [&](std::size_t i) { return c.q - h[i].q; };
        auto den = [&](std::size_t i) { return c.p - h[i].p; };
        std::size_t a = 0, b = m - 1;
        while (a < b) {
            const std::size_t mid = (a + b) / 2;
            if (less(num(mid + 1), den(mid + 1), num(mid), den(mid))) a = mid + 1;
            else b = mid;
        }
        if (!hi_.set || less(num(a), den(a), hi_.n, hi_.d)) hi_ = {num(a), den(a), true};
    }
    while (zeros_hull_.size() >= 2 &&
           cross(zeros_hull_[zeros_hull_.size() - 2], zeros_hull_.back(), c) <= 0)
        zeros_hull_.pop_back();
    zeros_hull_.push_back(c);
}

void RunWord::push_one(Pt c) {
    // New lower bound: the largest slope from a 0-position (all left of c).
    const std::size_t m = zeros_hull_.size();
    if (m > 0) {
        const auto& h = zeros_hull_;
        auto num = [&](std::size_t i) { return c.q - h[i].q; };
        auto den = [&](std::size_t i) { return c.p - h[i].p; };
        std::size_t a = 0, b = m - 1;
        while (a < b) {
            const std::size_t mid = (a + b) / 2;
            if (less(num(mid), den(mid), num(mid + 1), den(mid + 1))) a = mid + 1;
            else b = mid;
        }
        if (!lo_.set || less(lo_.n, lo_.d, num(a), den(a))) lo_ = {num(a), den(a), true};
    }
    if (!ones_hull_.empty() && ones_hull_.back().p == c.p) ones_hull_.pop_back();
    while (ones_hull_.size() >= 2 &&
           cross(ones_hull_[ones_hull_.size() - 2], ones_hull_.back(), c) >= 0)
        ones_hull_.pop_back();
    ones_hull_.push_back(c);
}

void RunWord::commit(int letter, std::int64_t k) {
    assert(k >= 1);
    if (letter == 0) {
        // The run's interior zeros are never hull vertices and never give an
        // extreme tangent; its first zero is kept on the hull as the
        // letter-by-letter hull keeps it.
        if (k >= 2) push_zero({p_, q_});
        push_zero({p_ + k - 1, q_});
        const std::int64_t last = p_ + k - 1;
        if (last > 0 && (!s_.set || less(q_ + 1, last, s_.n, s_.d))) s_ = {q_ + 1, last, true};
        p_ += k;
    } else {
        push_one({p_, q_ + k - 1});
        const std::int64_t top = q_ + k - 1;
        if (!r_.set || less(r_.n, r_.d, top, p_ + 1)) r_ = {top, p_ + 1, true};
        q_ += k;
    }
}

}  // namespace stepzip::detail

namespace stepzip::detail {

RunSegment::RunSegment(Profile p, int axes) : eight_(profile_eight_connected(p)), axes_(axes) {
    assert(p != Profile::patent);
    assert(axes >= 2 && axes <= profile_max_axes(p));
}

void RunSegment::reset() noexcept {
    length_ = 0;
    signs_ = 0;
    always_ = 0;
    for (int i = 0; i < (eight_ ? axes_ : 1); ++i) words_[i].reset();
}

namespace {
constexpr unsigned kStepMask = 0x555;  // STEP bits of the six axes
// Bits 2i, 2i+1 of s become bit i of the mask of moving axes.
unsigned moving_axes(Step s) {
    unsigned m = 0;
    for (int i = 0; i < kMaxAxes; ++i) m |= ((s >> (2 * i)) & 1u) << i;
    return m;
}
}  // namespace

RunWord::Probe RunSegment::probe(Step s, std::int64_t k) const noexcept {
    // One sign per axis: a moving axis must repeat the DIR bit it had.
    const unsigned step_bits = s & kStepMask;
    const unsigned seen_axes = signs_ & kStepMask;
    if (((s ^ signs_) & ((step_bits & seen_axes) << 1)) != 0) return {0, 1, 0};
    k = std::min(k, kMaxSegmentTotal - length_);
    if (k <= 0) return {0, 1, 0};
    RunWord::Probe r{k, 1, k};
    auto meet = [&](const RunWord::Probe& w) {
        r.alive = std::min(r.alive, w.alive);
        r.lo = std::max(r.lo, w.lo);
        r.hi = std::min(r.hi, w.hi);
    };
    if (!eight_) {
        meet(words_[0].probe((s & 1u) != 0 ? 0 : 1, k));
    } else {
        const unsigned moving = moving_axes(s);
        if (length_ > 0 && (always_ & moving) == 0) return {0, 1, 0};
        for (int i = 0; i < axes_; ++i) meet(words_[i].probe(static_cast<int>((moving >> i) & 1u), k));
    }
    r.hi = std::min(r.hi, r.alive);
    return r;
}

void RunSegment::commit(Step s, std::int64_t k) {
    signs_ |= s;
    if (!eight_) {
        words_[0].commit((s & 1u) != 0 ? 0 : 1, k);
    } else {
        const unsigned moving = moving_axes(s);
        always_ = length_ == 0 ? moving : (always_ & moving);
        for (int i = 0; i < axes_; ++i) words_[i].commit(static_cast<int>((moving >> i) & 1u), k);
    }
    length_ += k;
}

std::int64_t longest_exact_prefix(RunSegment& rec, std::span<const Step> steps) {
    rec.reset();
    const std::size_t n = steps.size();
    std::int64_t best = 0;
    std::size_t pos = 0;
    while (pos < n) {
        const Step s = steps[pos];
        std::size_t e = pos + 1;
        while (e < n && steps[e] == s) ++e;
        const auto k = static_cast<std::int64_t>(e - pos);
        const auto r = rec.probe(s, k);
        if (r.lo <= r.hi) best = rec.length() + r.hi;
        if (r.alive < k) break;
        rec.commit(s, k);
        pos = e;
    }
    return best;
}

}  // namespace stepzip::detail
