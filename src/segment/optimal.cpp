// Optimal segmenter: fewest exact segments (shortest path). See segmenters.hpp.
#include <cassert>
#include <limits>

#include "internal.hpp"
#include "stepzip/segment/recognizer.hpp"
#include "stepzip/segment/segmenters.hpp"

namespace stepzip {

void OptimalSegmenter::run(std::span<const Step> steps, std::vector<Segment>& out) const {
    const std::size_t n = steps.size();
    if (n == 0) return;
    constexpr std::uint32_t kUnreached = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> dist(n + 1, kUnreached);
    std::vector<std::size_t> from(n + 1, 0);
    dist[0] = 0;
    auto relax = [&](std::size_t s, std::size_t e) {
        // Ties keep the earlier start, i.e. the longer last segment.
        if (dist[s] + 1 < dist[e]) {
            dist[e] = dist[s] + 1;
            from[e] = s;
        }
    };

    // The greedy cut's segments are edges as well: never worse than greedy.
    detail::ProfileCut cut(profile_, axes_);
    std::vector<std::size_t> greedy_end(n, 0);
    for (std::size_t pos = 0; pos < n;) {
        const auto m = static_cast<std::size_t>(cut.longest(steps.subspan(pos)));
        greedy_end[pos] = pos + m;
        pos += m;
    }

    // Every exact end from each start, up to the window.
    const auto window = static_cast<std::size_t>(cut.window());
    cut.prepare(steps);
    for (std::size_t s = 0; s < n; ++s) {
        assert(dist[s] != kUnreached);  // every single step is a segment
        if (greedy_end[s] != 0) relax(s, greedy_end[s]);
        cut.ends(s, std::min(n, s + window), [&](std::int64_t lo, std::int64_t hi) {
            for (std::int64_t m = lo; m <= hi; ++m) relax(s, s + static_cast<std::size_t>(m));
        });
    }

    std::vector<std::size_t> cuts;
    for (std::size_t e = n; e != 0; e = from[e]) cuts.push_back(e);
    std::size_t pos = 0;
    for (auto it = cuts.rbegin(); it != cuts.rend(); ++it) {
        const auto run = steps.subspan(pos, *it - pos);
        auto seg = fit_segment(profile_, run, axes_);
        assert(seg.has_value());
        if (seg) {
            out.push_back(*seg);
        } else {  // never reached when the recognizer is right
            count_segmenter_fallback();
            GreedySegmenter(profile_, axes_).run(run, out);
        }
        pos = *it;
    }
}

}  // namespace stepzip
