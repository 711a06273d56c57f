// stepzip — exact circular arcs recovered from unit steps (reverse circular
// interpolation).
//
// The forward circular interpolators (interpolate_arc, arc.hpp) draw an arc
// from its start, end, integer centre and direction. The recognizer here
// runs them backwards: from a chain point it finds the centre, direction and
// end of the longest arc that one of those interpolators reproduces step for
// step. Every answer is verified by forward interpolation with the
// library's own interpolator, so it is exact by construction; the search
// only decides which candidates are tried.
//
// Supported: two-axis steps; integer centres (the interpolators take the
// start and end relative to the centre as integers, so a centre off the
// integer grid cannot be reproduced by them at all); every ArcMethod; arcs
// of one full turn at most (interpolate_arc draws no more); radius up to
// ArcSearchOptions::max_radius. docs/ALGORITHMS.md ("Arc recognition")
// describes the search and what it can miss.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "stepzip/error.hpp"
#include "stepzip/interpolate/arc.hpp"
#include "stepzip/profile.hpp"
#include "stepzip/segment.hpp"
#include "stepzip/segmenter.hpp"
#include "stepzip/step.hpp"

namespace stepzip {

/// An arc found at the front of a step sequence. Coordinates are relative to
/// the arc's start (the point before its first step).
struct ArcFit {
    std::int64_t cx = 0, cy = 0;  ///< centre
    std::int64_t ex = 0, ey = 0;  ///< end point (the sum of the arc's steps)
    bool ccw = false;             ///< counter-clockwise (G3) or clockwise (G2)
    std::size_t length = 0;       ///< steps reproduced; 0 when no arc was found
    friend bool operator==(const ArcFit&, const ArcFit&) = default;
};

/// Bounds of the search.
struct ArcSearchOptions {
    /// Shortest arc reported, in steps (>= 1). Shorter runs give length 0.
    std::size_t min_length = 8;
    /// Longest arc looked for, in steps: the search reads at most this many.
    std::size_t max_length = std::size_t{1} << 15;
    /// Largest radius (|centre| from the start) considered, in steps.
    std::int64_t max_radius = std::int64_t{1} << 14;
    /// Half width of the box of integer centres tried around each estimate
    /// of the centre (the estimates are least-squares circles through the
    /// start; see docs/ALGORITHMS.md).
    int centre_box = 2;
    /// > 0: only arcs that bow by at least this many steps (their largest
    /// distance from their chord, or from their start when they close) are
    /// reported, and no centres are sought for a prefix of up to 16 points
    /// that bows by less than half of it (a straight stretch then costs
    /// little). 0: every arc.
    double min_bow = 0;
    /// > 0: at most this many candidate centres are drawn per search (those
    /// with the longest bands first): faster, and may miss an arc. 0: no limit.
    std::size_t max_drawn = 0;
    /// true: for every method, ends are tried only up to 2·| |end| − R | +
    /// kArcTail steps past the bounds (as for evaluation, accelerated and
    /// double_recursion always): dda and prediction arcs whose end lies far
    /// off the circle may be missed, and large radii cost far less.
    bool near_ends = false;
    /// true: a candidate centre is drawn in one direction only when the
    /// points within its band turn clearly one way about it (seen at most
    /// R steps on): half the drawing, and an arc whose first points turn
    /// against its direction is missed.
    bool one_direction = false;
    /// > 0: also try every integer centre (cx, cy) with |cx|, |cy| <= this
    /// (exhaustive mode, for small radii and tests; (2b+1)^2 centres).
    std::int64_t exhaustive_box = 0;
};

/// The length of the longest prefix of `steps` (at most max_length steps)
/// that interpolate_arc(method, start − c, end − c, ccw) reproduces exactly,
/// where the start is the origin, c = (cx, cy) and the end is the sum of
/// the prefix; 0 when none has at least 1 step. Only ends k <= U are tried:
/// with `band` the number of leading points within arc_band(method) of the
/// circle through the start and `agreement` the common prefix of the steps
/// and the full circle drawn from the start (methods other than
/// double_recursion, whose path depends on its end), U is the end of the run
/// of equal steps at min(band, agreement) (after an end counter runs out one
/// axis moves alone) plus the end allowance ceil(max(2, R/8)) + kArcTail for
/// the correction run that interpolate_arc may add for an end off the circle
/// — for evaluation, accelerated and double_recursion the allowance of an
/// end p is 2·ceil(| |p − c| − R |) + kArcTail. Ends are drawn from U down;
/// the first reproduced one is returned (docs/algorithms/reverse.md §6).
/// Cost: O(band), O(R) for the full circle, O(k) per end drawn. Thread-safe.
std::size_t longest_arc_about(ArcMethod method, std::span<const Step> steps, std::int64_t cx,
                              std::int64_t cy, bool ccw,
                              std::size_t max_length = std::size_t{1} << 15);

/// Distance from the circle through the start, in steps, within which the
/// recognizer expects the points of an arc drawn by `method` before its end
/// correction run: the interpolators' documented bands (1 for evaluation,
/// accelerated and prediction, 1.5 for dda, √2/2 for double_recursion) plus
/// a quarter step. Thread-safe.
constexpr double arc_band(ArcMethod method) noexcept {
    switch (method) {
        case ArcMethod::dda: return 1.75;
        case ArcMethod::double_recursion: return 0.75;
        default: return 1.25;
    }
}
/// Steps added to the end allowance ceil(max(2, R/8)).
inline constexpr std::int64_t kArcTail = 2;

/// The longest arc at the front of `steps` (two-axis steps; a step on
/// another axis ends the search) over candidate centres found from the
/// steps: least-squares circles through the start fitted to the first m
/// points, m = 4, 8, 16, ..., the integer centres near each fit and along
/// the bisector of the chord to the m-th point, every centre that chord
/// allows for m <= 16, plus the exhaustive box when set
/// (src/segment/arc_recognizer.cpp, docs/algorithms/reverse.md §6). The
/// candidates are drawn with longest_arc_about, both directions, in order
/// of decreasing band (ties: the order found) while they can beat the best.
/// Returns length 0 when no arc of at least min_length steps (and min_bow)
/// was found. Cost: O(m) per fit, O(band) per candidate, then
/// longest_arc_about per candidate drawn. Thread-safe.
ArcFit longest_arc(ArcMethod method, std::span<const Step> steps,
                   const ArcSearchOptions& options = {});

/// One move of a cut into arcs and lines: a line segment (default_segment
/// of the profile) or an arc. `delta` / the arc's end are relative to the
/// move's start.
struct ArcCutMove {
    bool is_arc = false;
    Segment line{};   ///< lines: the segment (default phase)
    ArcFit arc{};     ///< arcs: centre, end, direction, length
    std::size_t steps = 0;  ///< steps the move draws
};

/// Options of cut_arcs_and_lines().
struct ArcCutOptions {
    ArcSearchOptions search{};
    /// Arc starts tried after a found arc's start (the one whose arc ends
    /// farthest wins; the steps before it become lines), and arc ends tried
    /// before a found arc's end (the one after which the next arc reaches
    /// farthest wins).
    std::size_t lookahead = 16;
    SegmenterKind lines = SegmenterKind::greedy;  ///< segment_default_phase for the lines
};

/// Cuts two-axis `steps` into arcs drawn by `method` and default-phase lines
/// of `profile` (segment_default_phase). Walking the steps, a position where
/// longest_arc() finds an arc (at most 64 centres drawn, near_ends, one_direction) that bows by 2
/// steps or more from its chord (flatter runs are left to the lines) starts
/// an arc: of the starts within the lookahead, the one whose arc ends
/// farthest; its end is moved back by up to `lookahead` steps when the next
/// arc then reaches farther (and more than `lookahead` steps past it). The arc is taken when the lines from the
/// previous arc to its start, plus one, are at least two fewer than the
/// lines from the previous arc to its end; the steps between arcs are cut
/// into lines. Appends moves whose forward interpolation (lines under the
/// profile at the default phase, arcs by interpolate_arc with `method`) is
/// exactly `steps` — each arc is drawn and compared when chosen; the
/// caller's redraw (check_redraw) proves the whole. Errors:
/// Errc::invalid_argument when `axes` is not 2; those of profile_accepts()
/// and segment_default_phase(). Thread-safe.
/// Cost: one longest_arc() per position outside the arcs, up to
/// 2·lookahead more per arc, and the line cuts (from the previous arc, per
/// arc found).
Result<void> cut_arcs_and_lines(std::span<const Step> steps, int axes, Profile profile,
                                ArcMethod method, const ArcCutOptions& options,
                                std::vector<ArcCutMove>& out);

}  // namespace stepzip
