// Greedy segmenter: the longest exact segment at each point. See segmenters.hpp.
#include <algorithm>
#include <atomic>
#include <cassert>

#include "stepzip/segment/recognizer.hpp"
#include "internal.hpp"
#include "run_word.hpp"
#include "two_axis.hpp"
#include "stepzip/segment/segmenters.hpp"

namespace stepzip {

std::int64_t patent_reach(std::span<const Step> steps, std::int64_t cap) {
    int sx = 0, sy = 0;
    std::int64_t n = 0;
    for (Step s : steps) {
        if (n >= cap || step_weight(s) != 1) break;
        const int dx = step_axis(s, 0), dy = step_axis(s, 1);
        if (dx != 0) {
            if (sx != 0 && sx != dx) break;
            sx = dx;
        } else {
            if (sy != 0 && sy != dy) break;
            sy = dy;
        }
        ++n;
    }
    return n;
}

bool patent_prefix_exact(std::span<const Step> steps, std::int64_t m, std::int64_t a,
                         std::int64_t b) {
    if (a == 0 || b == 0) return true;
    const PhaseRange r = phase_range(Profile::patent, a, b);
    std::int64_t x = a, y = b, f = 0, lo = r.lo, hi = r.hi;
    for (std::int64_t k = 0; k < m && x > 0 && y > 0; ++k) {
        if (step_axis(steps[static_cast<std::size_t>(k)], 0) != 0) {
            hi = std::min(hi, -f);
            --x;
            f += y;
        } else {
            lo = std::max(lo, -f);
            --y;
            f -= x;
        }
        if (lo >= hi) return false;
    }
    return true;
}

namespace {
std::atomic<std::uint64_t> g_fallbacks{0};
}  // namespace

void count_segmenter_fallback() noexcept { g_fallbacks.fetch_add(1, std::memory_order_relaxed); }
std::uint64_t segmenter_fallbacks() noexcept { return g_fallbacks.load(std::memory_order_relaxed); }

namespace {

std::int64_t longest_patent(std::span<const Step> steps) {
    const std::int64_t reach = patent_reach(steps, kPatentMaxSegment);
    std::vector<std::int64_t> xs(static_cast<std::size_t>(reach) + 1, 0);
    for (std::int64_t k = 0; k < reach; ++k)
        xs[k + 1] = xs[k] + (step_axis(steps[static_cast<std::size_t>(k)], 0) != 0);
    for (std::int64_t m = reach; m > 1; --m)
        if (patent_prefix_exact(steps, m, xs[m], m - xs[m])) return m;
    return 1;
}

}  // namespace

std::int64_t GreedySegmenter::longest(std::span<const Step> steps) const {
    if (steps.empty()) return 0;
    if (profile_ == Profile::patent) return longest_patent(steps);
    if (axes_ == 2) return detail::TwoAxisGreedy(profile_).longest(steps);
    detail::RunSegment rec(profile_, axes_);
    return detail::longest_exact_prefix(rec, steps);
}

void GreedySegmenter::run(std::span<const Step> steps, std::vector<Segment>& out) const {
    const bool patent = profile_ == Profile::patent;
    if (!patent && axes_ == 2) {
        detail::TwoAxisGreedy rec(profile_);
        for (std::size_t pos = 0; pos < steps.size();) {
            const auto rest = steps.subspan(pos);
            auto m = static_cast<std::size_t>(rec.longest(rest));
            auto seg = rec.fit(static_cast<std::int64_t>(m));
            assert(seg.has_value());
            // As below: never reached when the recognizer is right.
            if (!seg) count_segmenter_fallback();
            while (!seg && m > 1) seg = fit_segment(profile_, rest.first(--m), axes_);
            out.push_back(*seg);
            pos += m;
        }
        return;
    }
    detail::RunSegment rec(patent ? Profile::eval4 : profile_, axes_);
    std::size_t pos = 0;
    while (pos < steps.size()) {
        const auto rest = steps.subspan(pos);
        auto m = static_cast<std::size_t>(patent ? longest_patent(rest) : detail::longest_exact_prefix(rec, rest));
        auto seg = fit_segment(profile_, rest.first(m), axes_);
        assert(seg.has_value());
        // Never reached when the recognizer is right (the tests check it):
        // a shorter cut keeps the output exact; one step always fits.
        if (!seg) count_segmenter_fallback();
        while (!seg && m > 1) seg = fit_segment(profile_, rest.first(--m), axes_);
        out.push_back(*seg);
        pos += m;
    }
}

}  // namespace stepzip
