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

// A run of the letter at (x0 + j) in its own coordinate, j = 0..k-1: after
// j + 1 of them the letter's count is x = x0 + j + 1, and every validity
// condition on the word is a bound on x (dss::RunState::bounds).
RunWord::Probe RunWord::probe(int letter, std::int64_t k) const noexcept {
    const std::int64_t alive = st_.alive(letter, k);
    if (alive == 0) return {0, 1, 0};
    const std::int64_t x0 = letter == 0 ? st_.p : st_.q;
    if ((letter == 0 ? st_.q : st_.p) == 0) return {alive, 1, alive};
    const dss::RunState::Bounds b = st_.bounds(letter);
    wide xmin = 1, xmax = wide(x0) + alive;
    if (b.b1 > 0) xmax = std::min(xmax, floor_div(b.a1 - 1, b.b1));
    if (b.b2 > 0) xmax = std::min(xmax, floor_div(b.a2 - 1, b.b2));
    if (b.c > 0) xmin = std::max(xmin, floor_div(b.e, b.c) + 1);
    return {alive, clamp64(xmin - x0, 1, k + 1), clamp64(xmax - x0, 0, alive)};
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
// Bit 2i of s (axis i's STEP bit) becomes bit i of the mask of moving axes:
// the even bits gathered by three shifts.
unsigned moving_axes(Step s) {
    unsigned m = s & kStepMask;
    m = (m | (m >> 1)) & 0x333u;
    m = (m | (m >> 2)) & 0x30Fu;
    m = (m | (m >> 4)) & 0x03Fu;
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
