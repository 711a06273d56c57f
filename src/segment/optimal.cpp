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
    const GreedySegmenter greedy(profile_, axes_);
    std::vector<std::size_t> greedy_end(n, 0);
    for (std::size_t pos = 0; pos < n;) {
        const auto m = static_cast<std::size_t>(greedy.longest(steps.subspan(pos)));
        greedy_end[pos] = pos + m;
        pos += m;
    }

    const bool patent = profile_ == Profile::patent;
    const std::size_t window =
        static_cast<std::size_t>(patent ? kPatentOptimalWindow : kOptimalWindow);
    SegmentRecognizer rec(patent ? Profile::eval4 : profile_, axes_);
    for (std::size_t s = 0; s < n; ++s) {
        assert(dist[s] != kUnreached);  // every single step is a segment
        if (greedy_end[s] != 0) relax(s, greedy_end[s]);
        const std::size_t lim = std::min(n, s + window);
        if (patent) {
            const auto rest = steps.subspan(s);
            const std::int64_t reach = patent_reach(rest, static_cast<std::int64_t>(lim - s));
            std::int64_t xs = 0;
            for (std::int64_t m = 1; m <= reach; ++m) {
                xs += step_axis(rest[static_cast<std::size_t>(m - 1)], 0) != 0;
                if (patent_prefix_exact(rest, m, xs, m - xs)) relax(s, s + static_cast<std::size_t>(m));
            }
            continue;
        }
        rec.reset();
        for (std::size_t e = s; e < lim; ++e) {
            if (!rec.can_extend(steps[e]) || !rec.extend(steps[e])) break;
            if (rec.valid()) relax(s, e + 1);
        }
    }

    std::vector<std::size_t> cuts;
    for (std::size_t e = n; e != 0; e = from[e]) cuts.push_back(e);
    std::size_t pos = 0;
    for (auto it = cuts.rbegin(); it != cuts.rend(); ++it) {
        const auto run = steps.subspan(pos, *it - pos);
        auto seg = fit_segment(profile_, run, axes_);
        assert(seg.has_value());
        if (seg) out.push_back(*seg);
        else greedy.run(run, out);  // never reached when the recognizer is right
        pos = *it;
    }
}

}  // namespace stepzip
