// stepzip — a cut into circular arcs and default-phase lines: what
// `segment --arc-method` writes as G2/G3 and G1 (include/stepzip/segment/arc.hpp).
//
// Walk: at each position the arc recognizer is asked for the longest arc
// (longest_arc, at most kCutMaxDrawn centres drawn, ends near the circle,
// one direction per centre when its band turns clearly). An arc counts only when
// it bows by at least kArcMinBow steps from its chord (flatter runs are
// digital straight lines as far as the steps show) and the lines from the
// previous arc to its start plus the arc are at least two moves fewer than
// the lines from the previous arc to its end (a corner drawn round saves
// nothing once the lines next to it are split). Of the arc starts within
// the lookahead, the one whose arc ends farthest wins (a line that runs
// into an arc tangentially would otherwise start the arc a few steps early,
// on a point off its circle). At the arc's end, the end is moved back by up
// to `lookahead` steps when that lets the next arc (one ending more than
// `lookahead` steps past this arc's end) reach farther: an arc often draws
// a few steps of what follows. The steps between arcs go to
// segment_default_phase().
// Invariant: every arc move is drawn and compared when chosen; the line
// moves come from segment_default_phase, whose segments expand exactly.
// Cost: one longest_arc per position outside arcs, plus up to 2·lookahead
// per arc found; O(n) for the lines.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "stepzip/segment/arc.hpp"
#include "stepzip/vectors.hpp"

namespace stepzip {

namespace {

// Smallest bow (largest distance of an arc's points from its chord, or from
// its start when it closes) of an arc the cut takes.
constexpr double kArcMinBow = 2.0;
// Candidate centres drawn per search in the cut (ArcSearchOptions::max_drawn).
constexpr std::size_t kCutMaxDrawn = 64;

// The arc at the front of `steps`, if it bows enough.
ArcFit arc_at(ArcMethod method, std::span<const Step> steps, ArcSearchOptions o) {
    o.min_bow = std::max(o.min_bow, kArcMinBow);
    if (o.max_drawn == 0) o.max_drawn = kCutMaxDrawn;
    o.near_ends = true;
    o.one_direction = true;
    return longest_arc(method, steps, o);
}

// `fit` cut back to its first k steps, when the arc to that end reproduces them.
bool shortened(ArcMethod method, std::span<const Step> steps, const ArcFit& fit, std::size_t k,
               ArcFit& out, std::vector<Step>& scratch) {
    std::int64_t x = 0, y = 0;
    for (std::size_t i = 0; i < k; ++i) {
        x += step_axis(steps[i], 0);
        y += step_axis(steps[i], 1);
    }
    scratch.clear();
    if (!interpolate_arc(method, -fit.cx, -fit.cy, x - fit.cx, y - fit.cy, fit.ccw, scratch))
        return false;
    if (scratch.size() != k || !std::equal(scratch.begin(), scratch.end(), steps.begin()))
        return false;
    out = fit;
    out.ex = x;
    out.ey = y;
    out.length = k;
    return true;
}

}  // namespace

Result<void> cut_arcs_and_lines(std::span<const Step> steps, int axes, Profile profile,
                                ArcMethod method, const ArcCutOptions& options,
                                std::vector<ArcCutMove>& out) {
    if (axes != 2)
        return make_error(Errc::invalid_argument,
                          "arcs: two-axis chains only (this one has " + std::to_string(axes) +
                              " axes)");
    if (auto r = profile_accepts(profile, steps, axes); !r) return r;
    const ArcSearchOptions& o = options.search;
    const std::size_t n = steps.size();
    std::vector<Step> scratch;
    std::vector<Segment> lines;
    // Default-phase lines for steps[from, to).
    auto count_lines = [&](std::size_t from, std::size_t to) -> std::size_t {
        if (from >= to) return 0;
        lines.clear();
        if (!segment_default_phase(steps.subspan(from, to - from), axes, profile, lines,
                                   options.lines))
            return SIZE_MAX / 4;
        return lines.size();
    };
    auto flush_lines = [&](std::size_t from, std::size_t to) -> Result<void> {
        if (from >= to) return {};
        lines.clear();
        if (auto r = segment_default_phase(steps.subspan(from, to - from), axes, profile, lines,
                                           options.lines);
            !r)
            return r;
        for (const Segment& s : lines) {
            ArcCutMove m;
            m.line = s;
            m.steps = static_cast<std::size_t>(
                segment_length(s.delta, axes, profile_eight_connected(profile)));
            out.push_back(m);
        }
        return {};
    };

    std::size_t gap = 0, pos = 0;
    while (pos < n) {
        ArcFit fit = arc_at(method, steps.subspan(pos), o);
        if (fit.length == 0) {
            ++pos;
            continue;
        }
        // The start, among the next few, whose arc ends farthest.
        std::size_t start = pos;
        for (std::size_t d = 1; d <= options.lookahead && pos + d < start + fit.length; ++d) {
            const ArcFit f = arc_at(method, steps.subspan(pos + d), o);
            if (f.length > 0 && pos + d + f.length > start + fit.length) {
                start = pos + d;
                fit = f;
            }
        }
        // The end, among the last few, after which the next arc reaches farthest.
        std::size_t end = start + fit.length, reach = 0;
        ArcFit chosen = fit;
        for (std::size_t back = 0; back <= options.lookahead; ++back) {
            if (fit.length < back + std::max<std::size_t>(1, o.min_length)) break;
            ArcFit cut = fit;
            if (back > 0 && !shortened(method, steps.subspan(start), fit, fit.length - back, cut,
                                       scratch))
                continue;
            const std::size_t e = start + cut.length;
            if (e >= n) {
                if (back == 0) reach = n;
                break;
            }
            const ArcFit next = arc_at(method, steps.subspan(e), o);
            // A next arc counts when it ends more than `lookahead` steps
            // past this arc's own end and stands for three lines or more
            // (an arc's tail and a line's head drawn round do not).
            const bool counts = next.length > 0 &&
                                e + next.length > start + fit.length + options.lookahead &&
                                count_lines(e, e + next.length) > 2;
            const std::size_t r = counts ? e + next.length : 0;
            if (r > reach) {
                reach = r;
                chosen = cut;
                end = e;
            }
        }
        // The arc must save a move over the lines from the last arc to its
        // end, one more move counted for the line it may split after it.
        if (count_lines(gap, start) + 2 >= count_lines(gap, end)) {
            pos = start + 1;
            continue;
        }
        if (auto r = flush_lines(gap, start); !r) return r;
        ArcCutMove m;
        m.is_arc = true;
        m.arc = chosen;
        m.steps = chosen.length;
        out.push_back(m);
        pos = gap = end;
    }
    return flush_lines(gap, n);
}

}  // namespace stepzip
