// SU 1089551 approximation mode (seed 001, Fig. 3 and Fig. 5) and the patent
// segmenter built on it. See segmenter.hpp and segmenters.hpp.
#include <algorithm>
#include <cstdlib>
#include <string>

#include "stepzip/interpolate/segment.hpp"
#include "stepzip/segment/recognizer.hpp"
#include "stepzip/segment/segmenters.hpp"

namespace stepzip {

// Counters X, Y count up from 0 and the adder F starts at 0. An x-step
// belongs to the segment if F <= 0 (then F += Y), a y-step if F >= 0 (then
// F -= X). A violating step still updates the counters and the adder, the
// counters are read out as the segment's end point ("Конец отрезка") and
// everything resets. At the end of the input ("Конец сообщения") whatever the
// counters hold is read out too. The patent works in the first quadrant; here
// the first move on each axis fixes that axis's sign for the segment, and a
// move against a fixed sign reads the counters out before it (the step then
// starts the next segment), since counters that only count up cannot hold it.
// Invariant: the pieces read out cover the input in order.
// Complexity: O(1) per step.
Result<void> patent_approximate(std::span<const Step> steps, std::vector<Point>& ends,
                                std::vector<std::int64_t>* trace) {
    std::int64_t x = 0, y = 0, f = 0;
    int sx = 0, sy = 0;
    auto read_out = [&] {
        Point e{};
        e[0] = sx < 0 ? -x : x;
        e[1] = sy < 0 ? -y : y;
        ends.push_back(e);
        x = y = f = 0;
        sx = sy = 0;
    };
    for (std::size_t i = 0; i < steps.size(); ++i) {
        const Step s = steps[i];
        if ((s >> 4) != 0)
            return make_error(Errc::invalid_argument,
                              "step " + std::to_string(i + 1) +
                                  ": the approximation mode reads two axes only");
        if (step_weight(s) != 1)
            return make_error(Errc::connectivity,
                              "step " + std::to_string(i + 1) +
                                  ": the approximation mode reads 4-connected chains only");
        const int dx = step_axis(s, 0), dy = step_axis(s, 1);
        if ((dx != 0 && sx != 0 && dx != sx) || (dy != 0 && sy != 0 && dy != sy)) read_out();
        bool ends_here;
        if (dx != 0) {
            sx = dx;
            ends_here = f > 0;
            ++x;
            f += y;
        } else {
            sy = dy;
            ends_here = f < 0;
            ++y;
            f -= x;
        }
        if (trace) trace->push_back(f);
        if (ends_here) read_out();
    }
    if (x != 0 || y != 0) read_out();
    return {};
}

Result<void> PatentSegmenter::run(std::span<const Step> steps, std::vector<Segment>& out,
                                  SegmentStats* stats) const {
    std::vector<Point> ends;
    if (axes_ != 2)
        return make_error(Errc::unsupported, "the patent segmenter reads two-axis chains only");
    if (auto r = patent_approximate(steps, ends); !r) {
        auto e = std::move(r).error();
        e.code = Errc::unsupported;
        e.message = "patent segmenter: " + e.message;
        return e;
    }
    const GreedySegmenter greedy(profile_, axes_);
    SegmentStats st;
    std::size_t pos = 0;
    std::vector<Step> fwd;
    for (const Point& e : ends) {
        const auto len = static_cast<std::size_t>(std::llabs(e[0]) + std::llabs(e[1]));
        const auto piece = steps.subspan(pos, len);
        ++st.patent_segments;

        // Deviation of the read-out end point at the profile's default phase.
        const Segment guess = default_segment(profile_, e, axes_);
        if (check_segment(profile_, guess, axes_)) {
            fwd.clear();
            expand_segment(profile_, guess, axes_, fwd);
            const std::size_t ticks = std::max(fwd.size(), piece.size());
            Point a{}, b{};
            std::int64_t dev = 0;
            for (std::size_t t = 0; t < ticks; ++t) {
                if (t < piece.size()) apply_step(a, piece[t], axes_);
                if (t < fwd.size()) apply_step(b, fwd[t], axes_);
                dev = std::max<std::int64_t>({dev, std::llabs(a[0] - b[0]), std::llabs(a[1] - b[1])});
            }
            if (fwd.size() == piece.size() && std::equal(fwd.begin(), fwd.end(), piece.begin()))
                ++st.patent_exact;
            st.patent_max_deviation = std::max(st.patent_max_deviation, dev);
        }
        greedy.run(piece, out);
        pos += len;
    }
    if (stats) *stats += st;
    return {};
}

}  // namespace stepzip
