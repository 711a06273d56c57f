// stepzip — segmented chains as a vector drawing (what `stepzip segment`
// writes as G-code or HP-GL), and the shape of a segment.
#include <algorithm>
#include <string>

#include "stepzip/vectors.hpp"

namespace stepzip {

Result<Drawing> segments_to_drawing(const std::vector<SegmentedChain>& chains) {
    Drawing drawing;
    for (std::size_t c = 0; c < chains.size(); ++c) {
        const SegmentedChain& sc = chains[c];
        if (sc.chain.axes != 2)
            return make_error(Errc::unsupported,
                              "chain " + std::to_string(c + 1) + " has " +
                                  std::to_string(sc.chain.axes) +
                                  " axes; vector output needs two-axis chains");
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
