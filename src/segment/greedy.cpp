// Greedy segmenter: the longest exact segment at each point. See segmenters.hpp.
#include <algorithm>
#include <cassert>

#include "stepzip/segment/recognizer.hpp"
#include "stepzip/segment/segmenters.hpp"

namespace stepzip {

namespace {

// Steps from steps[0] that keep one sign per axis (and one axis per step),
// at most `cap`: the hard limit of a patent segment.
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

}  // namespace

std::int64_t GreedySegmenter::longest(std::span<const Step> steps) const {
    if (steps.empty()) return 0;
    if (profile_ == Profile::patent) {
        for (std::int64_t m = patent_reach(steps, kPatentMaxSegment); m > 1; --m)
            if (fit_segment(profile_, steps.first(static_cast<std::size_t>(m)), axes_)) return m;
        return 1;
    }
    SegmentRecognizer rec(profile_, axes_);
    std::int64_t best = 1;
    for (Step s : steps) {
        if (!rec.can_extend(s)) break;
        if (!rec.extend(s)) break;
        if (rec.valid()) best = rec.length();
    }
    return best;
}

void GreedySegmenter::run(std::span<const Step> steps, std::vector<Segment>& out) const {
    std::size_t pos = 0;
    while (pos < steps.size()) {
        const auto rest = steps.subspan(pos);
        const auto m = static_cast<std::size_t>(longest(rest));
        auto seg = fit_segment(profile_, rest.first(m), axes_);
        assert(seg.has_value());
        out.push_back(*seg);
        pos += m;
    }
}

}  // namespace stepzip
