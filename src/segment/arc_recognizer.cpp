// stepzip — the arc recognizer: the longest prefix of a step sequence that a
// circular interpolator of the library reproduces from (start, end, centre,
// direction) (include/stepzip/segment/arc.hpp).
//
// For one centre c and direction the answer is a k such that
// interpolate_arc(method, −c, p_k − c, ccw) == steps[0, k), p_k the point
// after k steps; it is found by drawing candidates, longest first, so it is
// exact by construction. What keeps the candidates few:
//  - the band: every interpolator keeps its points within about one step of
//    the circle through the start (their documented invariants) until the
//    end of its last piece; so the points of a reproduced prefix stay within
//    arc_band(method) of the circle but for the end: a run of one axis after
//    an end counter runs out, then at most the end allowance (the correction
//    run; interpolate_arc refuses an end farther than max(2, R/8) from the
//    circle): ceil(max(2, R/8)) + kArcTail, or for evaluation, accelerated
//    and double_recursion 2·ceil(| |end| − R |) + kArcTail per end tried;
//  - the agreement (all methods but double_recursion): an arc's path is the
//    full circle's path from the same start until an end counter of the last
//    quadrant piece runs out near the end, so a reproduced prefix agrees with
//    the full circle but for the same tail (after a counter runs out, one
//    axis moves alone, then the correction run). For an arc shorter than
//    2R steps a quarter-turn longer arc stands in for the full circle
//    (cheaper).
// Invariant: longest_arc_about returns 0 or a verified length; every length
// it skips lies beyond one of the two bounds (tested against a brute-force
// search over every end, tests/segment_arc_test.cpp).
// Cost: O(band) + O(R) + O(k) per candidate drawn.
//
// Centres: least-squares circles through the start (x² + y² − 2a·x − 2b·y = 0,
// linear in (a, b)) fitted to the first m points for m = 4, 8, 16, ... (not
// while the points bow by less than a step: no circle is told from a line
// then). Candidates: the integer points within max(centre_box, min(8,
// 3R²/m²)) of each fitted centre (the wider box only when R <= 4m), and the
// centres that the chord from the start to p_m allows (chord_centres) within
// min(64, 2R²/m² + 8) of the fitted centre along the chord's bisector (a
// short arc's radius is uncertain, and the methods' points lie more on one
// side of the circle than the other). For m <= 16 every centre the chord
// allows up to 4 chord lengths away is tried (short arcs, whose fit may be
// far off). m doubles while the points bow little or some candidate's band
// reaches m/2, so the work follows the arc's length. The candidates are
// then drawn in order of decreasing band until none can beat the best (or
// ArcSearchOptions::max_drawn have been drawn).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <unordered_map>
#include <utility>

#include "stepzip/segment/arc.hpp"

namespace stepzip {

namespace {

// Points of the prefix relative to the start: pts[k] after k steps. Stops at
// the first step that is not a two-axis step.
std::size_t prefix_points(std::span<const Step> steps, std::size_t limit,
                          std::vector<std::pair<std::int64_t, std::int64_t>>& pts) {
    pts.assign(1, {0, 0});
    const std::size_t n = std::min(steps.size(), limit);
    for (std::size_t k = 0; k < n; ++k) {
        const Step s = steps[k];
        if (!step_valid(s, 2)) break;
        pts.emplace_back(pts.back().first + step_axis(s, 0), pts.back().second + step_axis(s, 1));
    }
    return pts.size() - 1;
}

std::int64_t tail_allowance(double r) {
    return static_cast<std::int64_t>(std::ceil(std::max(2.0, r / 8))) + kArcTail;
}

// Number of leading points (after the start) within `band` of the circle of
// radius r about c.
std::size_t band_length(const std::vector<std::pair<std::int64_t, std::int64_t>>& pts,
                        std::int64_t cx, std::int64_t cy, double r, double band) {
    // Squared distances against squared bounds a little inside and outside
    // the band decide all but the points within 1e-6 of its edges, which
    // take the square root as before (the same answer, fewer roots).
    constexpr double kEdge = 1e-6;
    const double hi = r + band, lo = std::max(0.0, r - band);
    const double in_hi = (hi - kEdge) * (hi - kEdge), out_hi = (hi + kEdge) * (hi + kEdge);
    const double in_lo = (lo + kEdge) * (lo + kEdge), out_lo = lo > kEdge ? (lo - kEdge) * (lo - kEdge) : -1.0;
    std::size_t k = 1;
    for (; k < pts.size(); ++k) {
        const double dx = static_cast<double>(pts[k].first - cx);
        const double dy = static_cast<double>(pts[k].second - cy);
        const double d2 = dx * dx + dy * dy;
        if (d2 < in_hi && d2 > in_lo) continue;
        if (d2 > out_hi || d2 < out_lo) break;
        if (std::fabs(std::sqrt(d2) - r) > band) break;
    }
    return k - 1;
}

// Number of steps from i (i < n) equal to steps[i]; 0 at n.
std::size_t same_run(std::span<const Step> steps, std::size_t i, std::size_t n) {
    std::size_t j = i;
    while (j < n && steps[j] == steps[i]) ++j;
    return j - i;
}

// The end of the run of equal steps at i: after an end counter runs out,
// the rest of the last piece moves one axis only.
std::size_t run_end(std::span<const Step> steps, std::size_t i, std::size_t n) {
    return i + same_run(steps, i, n);
}

// The last end that can follow i reproduced points: the run at i, then at
// most the end allowance of correction run.
std::size_t run_bound(std::span<const Step> steps, std::size_t i, std::size_t n, double r) {
    return std::min(n, run_end(steps, i, n) + static_cast<std::size_t>(tail_allowance(r)));
}

// Methods whose correction run is at most about 2·| |end| − R | + kArcTail
// steps (the end lies behind the piece's start on an axis by at most its
// distance from the circle; double_recursion ends at the rounded point of
// the circle at the end's angle).
bool short_correction(ArcMethod method) {
    return method == ArcMethod::evaluation || method == ArcMethod::accelerated ||
           method == ArcMethod::double_recursion;
}

// Whether interpolate_arc accepts the end (x1, y1) of an arc from (x0, y0)
// about the origin (its check_arc, in the same arithmetic): both within
// kMaxInterpolateCoord, neither at the centre, |end| within max(2, R/8) of R.
bool arc_end_accepted(std::int64_t x0, std::int64_t y0, std::int64_t x1, std::int64_t y1) {
    for (std::int64_t c : {x0, y0, x1, y1})
        if (c < -kMaxInterpolateCoord || c > kMaxInterpolateCoord) return false;
    if ((x0 == 0 && y0 == 0) || (x1 == 0 && y1 == 0)) return false;
    const double r = std::sqrt(static_cast<double>(x0 * x0 + y0 * y0));
    const double re = std::sqrt(static_cast<double>(x1 * x1 + y1 * y1));
    return !(std::fabs(re - r) > std::fmax(2.0, r / 8));
}

struct AboutResult {
    std::size_t length = 0;
    std::size_t bound = 0;  // the largest end tried
};

// longest_arc_about over precomputed points, trying ends in (floor, bound].
AboutResult about(ArcMethod method, std::span<const Step> steps,
                  const std::vector<std::pair<std::int64_t, std::int64_t>>& pts, std::int64_t cx,
                  std::int64_t cy, bool ccw, std::size_t floor, std::vector<Step>& scratch,
                  std::size_t band = SIZE_MAX, bool near_ends = false) {
    AboutResult res;
    const std::size_t n = pts.size() - 1;
    if (n == 0 || (cx == 0 && cy == 0)) return res;
    const std::int64_t sx = -cx, sy = -cy;  // the start relative to the centre
    if (std::llabs(sx) > kMaxInterpolateCoord || std::llabs(sy) > kMaxInterpolateCoord)
        return res;
    // double_recursion moves along the circle from its first step (its
    // points are rounded points of the arc): a first step against the
    // direction cannot start it. (The other methods: the agreement below.)
    if (method == ArcMethod::double_recursion) {
        const std::int64_t cross = sx * step_axis(steps[0], 1) - sy * step_axis(steps[0], 0);
        if (ccw ? cross < 0 : cross > 0) return res;
    }
    const double r = std::sqrt(static_cast<double>(sx * sx + sy * sy));
    if (band == SIZE_MAX) band = band_length(pts, cx, cy, r, arc_band(method));
    std::size_t base = run_end(steps, band, n);
    const auto tail = static_cast<std::size_t>(tail_allowance(r));
    if (std::min(n, base + tail) <= floor) return res;
    const bool per_end = near_ends || short_correction(method);
    // An end k worth drawing: within the end allowance of its own distance
    // from the circle (per_end) and one interpolate_arc accepts.
    auto end_may = [&](std::size_t k, std::size_t b) {
        const std::int64_t ex = pts[k].first - cx, ey = pts[k].second - cy;
        if (per_end) {
            const double off = std::fabs(std::hypot(static_cast<double>(ex),
                                                    static_cast<double>(ey)) - r);
            if (k > b + 2 * static_cast<std::size_t>(std::ceil(off)) + kArcTail) return false;
        }
        return arc_end_accepted(sx, sy, ex, ey);
    };
    // No end worth drawing under the band's bound (which the agreement below
    // can only lower): nothing to draw, not even the reference.
    {
        std::size_t k = std::min(n, base + tail);
        while (k > floor && !end_may(k, base)) --k;
        if (k == floor) return res;
    }
    if (method != ArcMethod::double_recursion) {
        // The reference: the full circle, or for an arc shorter than 2R
        // steps (a sweep under about 2.9 radians, as a step is at most
        // sqrt(2) long) the arc to p_upper turned a quarter further, which
        // stays under a full turn and whose pieces up to p_upper's quadrant
        // are the full circle's (p_upper's quadrant is not its last piece).
        const std::size_t upper = std::min(n, base + tail);
        std::int64_t rx = sx, ry = sy;
        if (static_cast<double>(upper) < 2 * r) {
            const auto ux = static_cast<double>(pts[upper].first - cx);
            const auto uy = static_cast<double>(pts[upper].second - cy);
            const double u = std::hypot(ux, uy);
            if (u > 0) {  // on the circle, a quarter turn on
                rx = std::llround((ccw ? -uy : uy) * r / u);
                ry = std::llround((ccw ? ux : -ux) * r / u);
            }
        }
        scratch.clear();
        if (!interpolate_arc(method, sx, sy, rx, ry, ccw, scratch)) {
            scratch.clear();
            if (!interpolate_arc(method, sx, sy, sx, sy, ccw, scratch)) return res;
        }
        const auto lim = std::min(scratch.size(), n);
        std::size_t agree = 0;
        while (agree < lim && scratch[agree] == steps[agree]) ++agree;
        base = std::min(base, run_end(steps, agree, n));
    }
    const std::size_t upper = std::min(n, base + tail);
    res.bound = upper;
    for (std::size_t k = upper; k > floor; --k) {
        // interpolate_arc's own refusal is checked first (by end_may): a
        // refused end costs no error message.
        if (!end_may(k, base)) continue;
        const std::int64_t ex = pts[k].first - cx, ey = pts[k].second - cy;
        scratch.clear();
        if (!interpolate_arc(method, sx, sy, ex, ey, ccw, scratch)) continue;
        if (scratch.size() == k && std::equal(scratch.begin(), scratch.end(), steps.begin())) {
            res.length = k;
            return res;
        }
    }
    return res;
}

// Least-squares circle through the origin fitted to pts[1..m]: minimizes
// Σ (x² + y² − 2a·x − 2b·y)². False when the points are (nearly) collinear.
bool fit_centre(const std::vector<std::pair<std::int64_t, std::int64_t>>& pts, std::size_t m,
                double& a, double& b) {
    double sxx = 0, sxy = 0, syy = 0, sxz = 0, syz = 0;
    for (std::size_t k = 1; k <= m; ++k) {
        const auto x = static_cast<double>(pts[k].first), y = static_cast<double>(pts[k].second);
        const double z = x * x + y * y;
        sxx += x * x;
        sxy += x * y;
        syy += y * y;
        sxz += x * z;
        syz += y * z;
    }
    // Normal equations: [sxx sxy; sxy syy]·(2a, 2b) = (sxz, syz).
    const double det = sxx * syy - sxy * sxy;
    if (!(std::fabs(det) > 1e-9 * (sxx * syy + 1))) return false;
    a = (sxz * syy - syz * sxy) / det / 2;
    b = (syz * sxx - sxz * sxy) / det / 2;
    return std::isfinite(a) && std::isfinite(b);
}

// Centres allowed by the chord from the start to q when the start lies on
// the circle and q within a band β of it: c = q/2 + s·v + w·u (u along the
// chord, v across it, L = |q|) has |c − q| − |c| = −2wL / (|c − q| + |c|),
// so |w| <= β·(|c − q| + |c|) / (2L). s runs over ±kChordReach·L
// (for m <= kChordPoints; arcs flatter than that are left to the fits) or
// over a window about a fitted centre, in half steps, w likewise.
constexpr std::size_t kChordPoints = 16;
// Centres tried along the fitted radius, each side of the fitted centre.
constexpr double kRadialSpread = 64;

// Largest distance of pts[1..m] from the chord from the start to pts[m].
double sagitta(const std::vector<std::pair<std::int64_t, std::int64_t>>& pts, std::size_t m) {
    const auto qx = static_cast<double>(pts[m].first), qy = static_cast<double>(pts[m].second);
    const double len = std::hypot(qx, qy);
    double bow = 0;
    for (std::size_t k = 1; k <= m; ++k) {
        if (len < 1) {  // back at the start: the farthest point
            bow = std::max(bow, std::hypot(static_cast<double>(pts[k].first),
                                           static_cast<double>(pts[k].second)));
            continue;
        }
        const double cross = qx * static_cast<double>(pts[k].second) -
                             qy * static_cast<double>(pts[k].first);
        bow = std::max(bow, std::fabs(cross));
    }
    return len < 1 ? bow : bow / len;
}
constexpr double kChordReach = 4;

template <class Try>
std::size_t chord_centres(const std::pair<std::int64_t, std::int64_t>& q, double band,
                          double s_lo, double s_hi, Try&& try_centre) {
    const auto qx = static_cast<double>(q.first), qy = static_cast<double>(q.second);
    const double len = std::hypot(qx, qy);
    if (len < 2) return 0;
    const double ux = qx / len, uy = qy / len, vx = -uy, vy = ux;
    std::size_t reach = 0;
    for (double s = s_lo; s <= s_hi; s += 0.5) {
        const double rho = std::hypot(s, len / 2);
        const double wmax = band * rho / len + 0.5;
        for (double w = -wmax; w <= wmax; w += 0.5) {
            const double cx = qx / 2 + s * vx + w * ux, cy = qy / 2 + s * vy + w * uy;
            reach = std::max(reach, try_centre(std::llround(cx), std::llround(cy)));
        }
    }
    return reach;
}

// The position along the bisector of the chord to q (the s of chord_centres)
// of the point (a, b).
double chord_position(const std::pair<std::int64_t, std::int64_t>& q, double a, double b) {
    const auto qx = static_cast<double>(q.first), qy = static_cast<double>(q.second);
    const double len = std::hypot(qx, qy);
    if (len == 0) return 0;
    return ((a - qx / 2) * -qy + (b - qy / 2) * qx) / len;
}

}  // namespace

std::size_t longest_arc_about(ArcMethod method, std::span<const Step> steps, std::int64_t cx,
                              std::int64_t cy, bool ccw, std::size_t max_length) {
    std::vector<std::pair<std::int64_t, std::int64_t>> pts;
    prefix_points(steps, max_length, pts);
    std::vector<Step> scratch;
    return about(method, steps, pts, cx, cy, ccw, 0, scratch).length;
}

ArcFit longest_arc(ArcMethod method, std::span<const Step> steps,
                   const ArcSearchOptions& options) {
    ArcFit best;
    std::vector<std::pair<std::int64_t, std::int64_t>> pts;
    const std::size_t n = prefix_points(steps, options.max_length, pts);
    const std::size_t min_len = std::max<std::size_t>(1, options.min_length);
    if (n < min_len) return best;
    std::vector<Step> scratch;
    // Centre -> band, for the centres seen (a hash map: the search looks up
    // hundreds of centres per position).
    struct CentreHash {
        std::size_t operator()(const std::pair<std::int64_t, std::int64_t>& c) const noexcept {
            return std::hash<std::uint64_t>{}(static_cast<std::uint64_t>(c.first) * 0x9E3779B97F4A7C15ull ^
                                              static_cast<std::uint64_t>(c.second));
        }
    };
    std::unordered_map<std::pair<std::int64_t, std::int64_t>, std::size_t, CentreHash> tried;
    tried.reserve(1024);
    const double max_r = static_cast<double>(options.max_radius);

    // Candidates are collected with their band, then drawn in order of
    // decreasing band (stable: the order found on a tie), skipping those
    // whose bound cannot beat the best so far.
    struct Pending {
        std::size_t band;
        std::int64_t cx, cy;
    };
    std::vector<Pending> pending;
    auto try_centre = [&](std::int64_t cx, std::int64_t cy) -> std::size_t {
        const auto [it, fresh] = tried.try_emplace({cx, cy}, 0);
        if (!fresh) return it->second;
        if (cx == 0 && cy == 0) return 0;
        const double r = std::sqrt(static_cast<double>(cx * cx + cy * cy));
        if (r > max_r) return 0;
        const std::size_t band = band_length(pts, cx, cy, r, arc_band(method));
        it->second = band;
        pending.push_back({band, cx, cy});
        return band;
    };
    auto draw_pending = [&] {
        std::stable_sort(pending.begin(), pending.end(),
                         [](const Pending& a, const Pending& b) { return a.band > b.band; });
        std::size_t drawn = 0;
        for (const Pending& c : pending) {
            const double r = std::sqrt(static_cast<double>(c.cx * c.cx + c.cy * c.cy));
            const std::size_t floor = std::max(best.length, min_len - 1);
            if (run_bound(steps, c.band, n, r) <= floor) continue;
            if (options.max_drawn > 0 && ++drawn > options.max_drawn) break;
            // One direction only (options.one_direction): the one the band's
            // points turn in about c, seen at a point at most R steps on
            // (a sweep under pi), when they turn clearly.
            int turn = 0;
            if (options.one_direction) {
                const std::size_t j = std::min<std::size_t>(c.band, static_cast<std::size_t>(r));
                if (j >= 2) {
                    const std::int64_t qx = pts[j].first - c.cx, qy = pts[j].second - c.cy;
                    const std::int64_t cross = -c.cx * qy + c.cy * qx;
                    turn = cross > 0 ? 1 : cross < 0 ? -1 : 0;
                }
            }
            for (bool ccw : {true, false}) {
                if ((turn > 0 && !ccw) || (turn < 0 && ccw)) continue;
                const std::size_t fl = std::max(best.length, min_len - 1);
                const auto res = about(method, steps, pts, c.cx, c.cy, ccw, fl, scratch, c.band,
                                       options.near_ends);
                if (res.length > fl) {
                    best.length = res.length;
                    best.cx = c.cx;
                    best.cy = c.cy;
                    best.ccw = ccw;
                    best.ex = pts[res.length].first;
                    best.ey = pts[res.length].second;
                }
            }
        }
        pending.clear();
    };

    if (options.exhaustive_box > 0) {
        const std::int64_t b = options.exhaustive_box;
        for (std::int64_t cy = -b; cy <= b; ++cy)
            for (std::int64_t cx = -b; cx <= b; ++cx) try_centre(cx, cy);
        draw_pending();
    }
    const int box = std::max(0, options.centre_box);
    for (std::size_t m = 4;; m *= 2) {
        const std::size_t mm = std::min(m, n);
        const double bow = sagitta(pts, mm);
        double a = 0, b = 0;
        std::size_t reach = 0;
        const bool fitted = bow >= 1 && fit_centre(pts, mm, a, b) &&
                            std::hypot(a, b) <= max_r + kRadialSpread + 1;
        if (fitted) {
            const auto ca = static_cast<std::int64_t>(std::llround(a));
            const auto cb = static_cast<std::int64_t>(std::llround(b));
            // The fit's error grows as R²/m² (points scattered by a step
            // about an arc of small sagitta): a wider box for short arcs
            // of a small circle.
            const double r = std::hypot(a, b);
            std::int64_t wide = box;
            if (r <= 4.0 * static_cast<double>(mm))
                wide = std::max<std::int64_t>(
                    box, std::min(8.0, std::ceil(3 * r * r / double(mm * mm))));
            for (std::int64_t dy = -wide; dy <= wide; ++dy)
                for (std::int64_t dx = -wide; dx <= wide; ++dx)
                    reach = std::max(reach, try_centre(ca + dx, cb + dy));
            // The centre lies near the bisector of the chord to p_m (the
            // start is on the circle, p_m within the band) better than the
            // fit's radius is known: centres along the bisector too.
            const double spread =
                std::min(kRadialSpread, std::ceil(2 * r * r / double(mm * mm)) + 8);
            const double s0 = chord_position(pts[mm], a, b);
            reach = std::max(reach, chord_centres(pts[mm], arc_band(method), s0 - spread,
                                                  s0 + spread, try_centre));
        }
        // Short prefixes: every centre the chord to p_m allows (below).
        if (mm <= kChordPoints && mm >= 2 && bow >= options.min_bow / 2) {
            const double smax = kChordReach * std::hypot(static_cast<double>(pts[mm].first),
                                                         static_cast<double>(pts[mm].second));
            reach = std::max(reach,
                             chord_centres(pts[mm], arc_band(method), -smax, smax, try_centre));
        }
        // The doubling ends at the last point, or once the points bow clearly
        // (a fit is meaningful) and no candidate keeps half of them in its band.
        // Points that still bow by less than a step after 2·√(8·max_radius)
        // of them hold no arc of the allowed radii longer than half of them.
        if (mm == n || (m >= 16 && bow > 8 && 2 * reach < mm) ||
            (bow < 1 && static_cast<double>(mm) >= 2 * std::sqrt(8 * max_r)))
            break;
    }
    draw_pending();
    if (best.length < min_len || (options.min_bow > 0 && sagitta(pts, best.length) < options.min_bow))
        best = ArcFit{};
    return best;
}

}  // namespace stepzip
