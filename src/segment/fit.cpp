// Fitting one exact segment to a run of steps, with the phase nearest the
// profile's default (SPEC §3, §4). Complexity: O(steps · axes).
#include <algorithm>
#include <bit>
#include <cstdlib>
#include <limits>

#include "dss.hpp"
#include "stepzip/segment/recognizer.hpp"

namespace stepzip {

namespace {

constexpr std::int64_t kInf = std::numeric_limits<std::int64_t>::max();

// Signs fixed per segment; fills delta. False on a sign change or an empty run.
bool totals(std::span<const Step> steps, int axes, Point& delta) {
    // Per axis: how many ticks moved it; the OR of all steps tells the signs
    // (both DIR values seen on a moving axis = a sign change).
    std::int64_t count[kMaxAxes] = {};
    unsigned neg_seen = 0, pos_seen = 0;
    const std::size_t n = steps.size();
    for (std::size_t k = 0; k < n;) {
        std::size_t e = k + 1;
        while (e < n && steps[e] == steps[k]) ++e;
        const unsigned s = steps[k];
        const auto len = static_cast<std::int64_t>(e - k);
        for (int i = 0; i < axes; ++i) count[i] += len * ((s >> (2 * i)) & 1u);
        neg_seen |= s & (s >> 1) & 0x555u;
        pos_seen |= s & ~(s >> 1) & 0x555u;
        k = e;
    }
    if (neg_seen & pos_seen) return false;
    delta = {};
    for (int i = 0; i < axes; ++i) delta[i] = ((neg_seen >> (2 * i)) & 1u) ? -count[i] : count[i];
    return n != 0;
}

// Interval [lo, hi) of phases that produce the word letter(0..n-1) under the
// two-letter rule with counts (a, b) = (#zeros, #ones); empty when lo >= hi.
// The letters come from runs of identical steps: inside a run of zeros the
// bound p·b - q·a grows with p, inside a run of ones it falls with q, so only
// a run's last letter matters (O(1) per run).
template <class Letter>
std::pair<std::int64_t, std::int64_t> word_phases(std::span<const Step> steps, Letter letter,
                                                  std::int64_t a, std::int64_t b) {
    std::int64_t lo = -kInf, hi = kInf, p = 0, q = 0;
    const std::size_t n = steps.size();
    for (std::size_t k = 0; k < n;) {
        std::size_t e = k + 1;
        while (e < n && steps[e] == steps[k]) ++e;
        const auto len = static_cast<std::int64_t>(e - k);
        if (letter(steps[k]) == 0) {
            lo = std::max(lo, (p + len - 1) * b - q * a);
            p += len;
        } else {
            hi = std::min(hi, p * b - (q + len - 1) * a);
            q += len;
        }
        if (lo >= hi) break;
        k = e;
    }
    return {lo, hi};
}

std::optional<Segment> fit_eval4(std::span<const Step> steps, const Point& delta) {
    for (Step s : steps)
        if (!step_moves_one_axis(s)) return std::nullopt;
    const std::int64_t a = std::llabs(delta[0]), b = std::llabs(delta[1]);
    Segment seg;
    seg.delta = delta;
    if (a == 0 || b == 0) {
        seg.phase[0] = default_phase(Profile::eval4, a, b);
        return seg;
    }
    auto [lo, hi] = word_phases(steps, [](Step s) { return (s & 1u) != 0 ? 0 : 1; }, a, b);
    const auto f = detail::dss::pick_phase(Profile::eval4, a, b, lo, hi);
    if (!f) return std::nullopt;
    seg.phase[0] = *f;
    return seg;
}

std::optional<Segment> fit_leading(Profile p, std::span<const Step> steps, int axes,
                                   const Point& delta) {
    const int lead = leading_axis(delta, axes);
    const std::int64_t l = std::llabs(delta[lead]);
    if (l != static_cast<std::int64_t>(steps.size())) return std::nullopt;  // lead must move every tick
    Segment seg;
    seg.delta = delta;
    int j = 0;
    for (int i = 0; i < axes; ++i) {
        if (i == lead) continue;
        const std::int64_t s = std::llabs(delta[i]);
        if (s == 0 || s == l) {
            seg.phase[j++] = default_phase(p, l, s);
            continue;
        }
        auto [lo, hi] = word_phases(
            steps, [i](Step t) { return static_cast<int>((t >> (2 * i)) & 1u); }, l - s, s);
        const auto f = detail::dss::pick_phase(p, l, s, lo, hi);
        if (!f) return std::nullopt;
        seg.phase[j++] = *f;
    }
    return seg;
}

// Patent forward mode (Fig. 4) with remaining counters x, y and adder F:
// F < 0 and x > 0: x-step, F += y; else y-step, F -= x; y == 0 forces x.
// With f the adder's change since the start, a free (unforced) x-step needs
// F0 < -f and a free y-step needs F0 >= -f: one linear constraint per step.
std::optional<Segment> fit_patent(std::span<const Step> steps, const Point& delta) {
    for (Step s : steps)
        if (!step_moves_one_axis(s)) return std::nullopt;
    const std::int64_t a = std::llabs(delta[0]), b = std::llabs(delta[1]);
    std::int64_t x = a, y = b, f = 0, lo = -kInf, hi = kInf;
    for (Step s : steps) {
        const bool xs = step_axis(s, 0) != 0;
        if (x > 0 && y > 0) {
            if (xs) hi = std::min(hi, -f);
            else lo = std::max(lo, -f);
            if (lo >= hi) return std::nullopt;
        }
        if (xs) { --x; f += y; }
        else { --y; f -= x; }
    }
    const auto ph = detail::dss::pick_phase(Profile::patent, a, b, lo, hi);
    if (!ph) return std::nullopt;
    Segment seg;
    seg.delta = delta;
    seg.phase[0] = *ph;
    return seg;
}

}  // namespace

std::optional<Segment> fit_segment(Profile p, std::span<const Step> steps, int axes) {
    if (axes < 2 || axes > profile_max_axes(p)) return std::nullopt;
    Point delta;
    if (!totals(steps, axes, delta)) return std::nullopt;
    for (int i = 0; i < axes; ++i)
        if (std::llabs(delta[i]) > kMaxSegmentTotal) return std::nullopt;
    switch (p) {
        case Profile::eval4: return fit_eval4(steps, delta);
        case Profile::patent: return fit_patent(steps, delta);
        case Profile::eval8:
        case Profile::grbl:
        case Profile::marlin: return fit_leading(p, steps, axes, delta);
    }
    return std::nullopt;
}

}  // namespace stepzip
