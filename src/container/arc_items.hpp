// Arc items of the table block (docs/FORMAT.md 1.10.1): a circular arc
// drawn by one of the library's arc interpolators, held in a cut as a
// Segment of a two-axis frame whose unused coordinates carry it —
// delta[0..1] the end and delta[2..3] the centre (both relative to the arc's
// start), delta[4] the direction (1 clockwise, 2 counter-clockwise),
// delta[5] the arc method. A line of a two-axis frame has delta[2..5] zero,
// so the models and the window treat an arc as one more item whose identity
// is all of these fields. Internal to src/container.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "stepzip/document.hpp"
#include "stepzip/error.hpp"
#include "stepzip/interpolate/arc.hpp"
#include "stepzip/profile.hpp"
#include "stepzip/segment.hpp"
#include "stepzip/segment/arc.hpp"

namespace stepzip::stz {

/// Arc methods a table block may declare (ArcMethod values 0..kArcMethods-1).
inline constexpr unsigned kArcMethods = 5;

/// Whether `s` is an arc item (two-axis frames only).
inline bool is_arc(const Segment& s, int axes) { return axes == 2 && s.delta[4] != 0; }

/// The arc item of `fit` drawn by `method`.
inline Segment arc_item(const ArcFit& fit, ArcMethod method) {
    Segment s{};
    s.delta[0] = fit.ex;
    s.delta[1] = fit.ey;
    s.delta[2] = fit.cx;
    s.delta[3] = fit.cy;
    s.delta[4] = fit.ccw ? 2 : 1;
    s.delta[5] = static_cast<std::int64_t>(method);
    return s;
}

inline bool arc_ccw(const Segment& s) { return s.delta[4] == 2; }
inline ArcMethod arc_method_of(const Segment& s) { return static_cast<ArcMethod>(s.delta[5]); }

/// The most steps an arc item of centre (cx, cy) may draw: 9·ceil(R) + 16,
/// R = |centre| (a full turn is at most 8R steps, the end correction less
/// than R/2 + 16).
/// A block that declares fewer steps is corrupt (docs/FORMAT.md 1.10.1), so
/// an arc never draws more than its block declares.
std::uint64_t arc_step_bound(std::int64_t cx, std::int64_t cy);

/// Appends the steps of arc item `s` to `out`; false when the interpolator
/// refuses it (out unchanged).
bool draw_arc_item(const Segment& s, std::vector<Step>& out);

/// Steps of item `s` (a line under `p`, or an arc, drawn to count them);
/// 0 for an arc the interpolator refuses.
std::uint64_t item_steps(const Segment& s, Profile p, int axes);

/// Cuts every chain of a two-axis `block` into default-phase lines of `p`
/// and arcs drawn by `method` (cut_arcs_and_lines with the encoder's
/// bounds), as arc items; an arc whose step bound exceeds the block's
/// steps is cut into lines instead. Errors: those
/// of cut_arcs_and_lines, prefixed with the chain.
Result<void> arc_block_cut(const Block& block, Profile p, ArcMethod method,
                           std::vector<std::vector<Segment>>& out, std::uint64_t first_chain,
                           const std::string& source);

}  // namespace stepzip::stz
