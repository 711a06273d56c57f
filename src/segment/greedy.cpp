// Greedy segmenter: the longest exact segment at each point. See segmenters.hpp.
#include <atomic>
#include <cassert>

#include "internal.hpp"
#include "stepzip/segment/recognizer.hpp"
#include "stepzip/segment/segmenters.hpp"

namespace stepzip {

namespace {
std::atomic<std::uint64_t> g_fallbacks{0};
}  // namespace

void count_segmenter_fallback() noexcept { g_fallbacks.fetch_add(1, std::memory_order_relaxed); }
std::uint64_t segmenter_fallbacks() noexcept { return g_fallbacks.load(std::memory_order_relaxed); }

std::int64_t GreedySegmenter::longest(std::span<const Step> steps) const {
    return detail::ProfileCut(profile_, axes_).longest(steps);
}

void GreedySegmenter::run(std::span<const Step> steps, std::vector<Segment>& out) const {
    detail::ProfileCut cut(profile_, axes_);
    for (std::size_t pos = 0; pos < steps.size();) {
        const auto rest = steps.subspan(pos);
        auto m = static_cast<std::size_t>(cut.longest(rest));
        auto seg = cut.fit(rest, static_cast<std::int64_t>(m));
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
