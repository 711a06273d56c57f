// Run-at-a-time two-letter word recognition. See run_word.hpp.
#include "run_word.hpp"

#include <algorithm>
#include <cassert>

namespace stepzip::detail {

using dss::floor_div;
using dss::wide;

namespace {
std::int64_t clamp64(wide v, std::int64_t lo, std::int64_t hi) { return std::clamp(v, lo, hi); }
}  // namespace

RunWord::Probe RunWord::probe(int letter, std::int64_t k) const noexcept {
    return letter == 0 ? probe_zeros(k) : probe_ones(k);
}

// Zeros at (p + j, q), j = 0..k-1; after j + 1 of them the word has
// P = p + j + 1 zeros and q ones.
RunWord::Probe RunWord::probe_zeros(std::int64_t k) const noexcept {
    const std::int64_t p = st_.p, q = st_.q;
    const std::int64_t alive = st_.zeros_alive(k);
    if (alive == 0) return {0, 1, 0};
    if (q == 0) return {alive, 1, alive};
    // Bounds on P: lo < q/P < hi (the bound before the run) and, for the
    // tangents added by the run, P * u.q < q * (u.p + 1) for every u.
    const dss::Frac lo = st_.lo, hi = st_.hi, r = st_.r;
    wide pmin = 1, pmax = wide(p) + alive;
    if (lo.n > 0) pmax = std::min(pmax, floor_div(wide(q) * lo.d - 1, lo.n));
    if (hi.d > 0) pmin = std::max(pmin, floor_div(wide(q) * hi.d, hi.n) + 1);
    if (r.n > 0) pmax = std::min(pmax, floor_div(wide(q) * r.d - 1, r.n));
    return {alive, clamp64(pmin - p, 1, k + 1), clamp64(pmax - p, 0, alive)};
}

// Ones at (p, q + j); after j + 1 of them: p zeros and Q = q + j + 1 ones.
RunWord::Probe RunWord::probe_ones(std::int64_t k) const noexcept {
    const std::int64_t p = st_.p, q = st_.q;
    const std::int64_t alive = st_.ones_alive(k);
    if (alive == 0) return {0, 1, 0};
    if (p == 0) return {alive, 1, alive};
    // Bounds on Q: lo < Q/p < hi and Q * z.p < p * (z.q + 1) for every z.
    const dss::Frac lo = st_.lo, hi = st_.hi, s = st_.s;
    wide qmin = 1, qmax = wide(q) + alive;
    if (hi.d > 0) qmax = std::min(qmax, floor_div(wide(hi.n) * p - 1, hi.d));
    if (lo.n >= 0) qmin = std::max(qmin, floor_div(wide(lo.n) * p, lo.d) + 1);
    if (s.d > 0) qmax = std::min(qmax, floor_div(wide(p) * s.n - 1, s.d));
    return {alive, clamp64(qmin - q, 1, k + 1), clamp64(qmax - q, 0, alive)};
}

void RunWord::commit(int letter, std::int64_t k) {
    assert(k >= 1);
    if (letter == 0) st_.commit_zeros(k);
    else st_.commit_ones(k);
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
