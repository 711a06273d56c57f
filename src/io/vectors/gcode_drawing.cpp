// stepzip — segmented chains as a vector drawing (what `stepzip segment`
// writes as G-code or HP-GL), and the shape of a segment.
#include <algorithm>
#include <cmath>
#include <string>

#include "drawing_internal.hpp"
#include "stepzip/vectors.hpp"

namespace stepzip {

Result<Drawing> segments_to_drawing(const std::vector<SegmentedChain>& chains) {
    Drawing drawing;
    for (std::size_t c = 0; c < chains.size(); ++c) {
        const SegmentedChain& sc = chains[c];
        if (sc.chain.axes != 2) return not_two_axis(c, sc.chain.axes);
        if (sc.segments.empty()) continue;
        VectorPath path{sc.chain.start[0], sc.chain.start[1], {}};
        std::int64_t x = path.x0, y = path.y0;
        for (const Segment& s : sc.segments) {
            x += s.delta[0];
            y += s.delta[1];
            VectorMove m;
            m.x = x;
            m.y = y;
            path.moves.push_back(m);
        }
        drawing.push_back(std::move(path));
    }
    return drawing;
}

Result<Drawing> segments_to_drawing(const std::vector<SegmentedChain>& chains,
                                    const FeedOptions& feed) {
    const double v = feed.steps_per_second;
    if (!(v > 0) || !std::isfinite(v))
        return make_error(Errc::invalid_argument, "the feed rate must be a positive number");
    auto drawing = segments_to_drawing(chains);
    if (!drawing) return drawing;
    // Millimetres per step, or 1 (F in steps per minute).
    const double unit = feed.step_size ? static_cast<double>(feed.step_size->mm_e12) * 1e-12 : 1.0;
    std::size_t p = 0;
    for (std::size_t c = 0; c < chains.size(); ++c) {
        const SegmentedChain& sc = chains[c];
        if (sc.segments.empty()) continue;
        auto times = feed_times(sc.chain.steps, 2, v, feed.factor);
        if (!times) return make_error(times.error().code, "chain " + std::to_string(c + 1) + ": " +
                                                              times.error().message);
        VectorPath& path = (*drawing)[p++];
        Point at = sc.chain.start;
        std::size_t i = 0;       // steps walked
        double t0 = 0;           // stamp of the step before the segment
        for (std::size_t k = 0; k < sc.segments.size(); ++k) {
            const Segment& s = sc.segments[k];
            const std::int64_t ex = at[0] + s.delta[0], ey = at[1] + s.delta[1];
            // Walk to the segment's end point (segments are monotone per axis).
            Point q = at;
            std::size_t j = i;
            while (j < sc.chain.steps.size() && (j == i || q[0] != ex || q[1] != ey))
                apply_step(q, sc.chain.steps[j++], 2);
            if (q[0] != ex || q[1] != ey || j == i)
                return make_error(Errc::invalid_argument,
                                  "chain " + std::to_string(c + 1) + ": segment " +
                                      std::to_string(k + 1) +
                                      " does not end on a point of the chain");
            const double t1 = (*times)[j - 1];
            const double length = std::hypot(static_cast<double>(s.delta[0]),
                                             static_cast<double>(s.delta[1])) * unit;
            path.moves[k].feed = t1 > t0 ? 60.0 * length / (t1 - t0) : 0.0;
            t0 = t1;
            at = q;
            i = j;
        }
    }
    return drawing;
}

SegmentShape segment_shape(const Segment& segment) noexcept {
    std::int64_t magnitude = 0;
    int moving = 0;
    bool equal = true;
    for (std::int64_t d : segment.delta) {
        if (d == 0) continue;
        const std::int64_t a = d < 0 ? -d : d;
        if (moving > 0 && a != magnitude) equal = false;
        magnitude = std::max(magnitude, a);
        ++moving;
    }
    if (moving <= 1) return SegmentShape::run;
    return equal ? SegmentShape::diagonal : SegmentShape::slope;
}

}  // namespace stepzip
