// Optimal segmenter: fewest exact segments (shortest path). See segmenters.hpp.
#include <cassert>
#include <limits>

#include "internal.hpp"
#include "run_word.hpp"
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
    // End of the run of identical steps containing each position.
    std::vector<std::uint32_t> run_end;
    if (!patent) {
        run_end.resize(n);
        for (std::size_t i = n; i-- > 0;)
            run_end[i] = static_cast<std::uint32_t>(
                i + 1 < n && steps[i + 1] == steps[i] ? run_end[i + 1] : i + 1);
    }
    detail::RunSegment rec(patent ? Profile::eval4 : profile_, axes_);
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
        // Every exact end from s, run by run: each run contributes an
        // interval of ends.
        rec.reset();
        const std::uint32_t next = dist[s] + 1;
        for (std::size_t pos = s; pos < lim;) {
            const std::size_t e = std::min<std::size_t>(run_end[pos], lim);
            const auto k = static_cast<std::int64_t>(e - pos);
            const auto r = rec.probe(steps[pos], k);
            for (std::int64_t m = r.lo; m <= r.hi; ++m) {
                const std::size_t end = pos + static_cast<std::size_t>(m);
                if (next < dist[end]) {
                    dist[end] = next;
                    from[end] = s;
                }
            }
            if (r.alive < k) break;
            rec.commit(steps[pos], k);
            pos = e;
        }
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
            greedy.run(run, out);
        }
        pos = *it;
    }
}

}  // namespace stepzip
