// A second cut of a chain for the segment model (docs/FORMAT.md, encoder
// behaviour): greedy, but preferring a segment that the profile's own
// interpolator draws at its default phase. A stream drawn by a controller
// (GRBL, Marlin, the seeds' interpolators) is cut at its original vector
// ends, so its segments repeat and cost no phase; the free-phase greedy cut
// may run a few steps past a vector end and shift every later cut.
// Complexity: O(n log n) for the recognizer plus O(64 · L) per segment for the
// default-phase check. Encoder only; the decoder does not depend on the cut.
#include <algorithm>

#include "aligned_cut.hpp"
#include "stepzip/segment/recognizer.hpp"

namespace stepzip::stz {

namespace {

constexpr std::int64_t kBackoff = 64;  // how far below the greedy length to look

bool default_exact(Profile p, std::span<const Step> run, int axes, std::vector<Step>& scratch,
                   Segment& seg) {
    Point delta{};
    for (Step s : run) apply_step(delta, s, axes);
    seg = default_segment(p, delta, axes);
    if (!check_segment(p, seg, axes)) return false;
    scratch.clear();
    expand_segment(p, seg, axes, scratch);
    return scratch.size() == run.size() && std::equal(scratch.begin(), scratch.end(), run.begin());
}

}  // namespace

bool cut_preferring_default(std::span<const Step> steps, int axes, Profile p,
                            std::vector<Segment>& out) {
    if (p == Profile::patent) return false;
    SegmentRecognizer rec(p, axes);
    std::vector<Step> scratch;
    std::size_t i = 0;
    while (i < steps.size()) {
        rec.reset();
        std::size_t m = 0, valid = 0;
        while (i + m < steps.size() && rec.can_extend(steps[i + m])) {
            const bool alive = rec.extend(steps[i + m]);
            ++m;
            if (rec.valid()) valid = m;
            if (!alive) break;
        }
        if (valid == 0) return false;
        Segment seg;
        std::size_t take = 0;
        const std::size_t floor = valid > static_cast<std::size_t>(kBackoff) ? valid - kBackoff : 1;
        for (std::size_t k = valid; k >= floor && k * 2 >= valid; --k)
            if (default_exact(p, steps.subspan(i, k), axes, scratch, seg)) {
                take = k;
                break;
            }
        if (take == 0) {
            auto fit = fit_segment(p, steps.subspan(i, valid), axes);
            if (!fit) return false;
            seg = *fit;
            take = valid;
        }
        out.push_back(seg);
        i += take;
    }
    return true;
}

}  // namespace stepzip::stz
