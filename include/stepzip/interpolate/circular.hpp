// stepzip — circular interpolation by the evaluation function (seed 000,
// seed 004 §6.2.2.1 Fig. 6.21) and its accelerated octant version (seed 000
// "УСКОРЕН АЛГОРИТЪМ", seed 004 §6.2.2.2).
//
// Both take the centre at the origin, R² = x0² + y0² and F = x² + y² − R²
// (F = 0 at the start), and cut the arc at the axes into quadrant pieces
// (see interpolate_arc in arc.hpp for the common geometry, limits and the
// end-point guarantee). Thread-safe (no shared state).
#pragma once

#include <cstdint>
#include <vector>

#include "stepzip/error.hpp"
#include "stepzip/step.hpp"

namespace stepzip {

/// One traced point: the point reached after a step and F there.
struct ArcTracePoint {
    std::int64_t x = 0;
    std::int64_t y = 0;
    std::int64_t f = 0;  ///< x² + y² − R²
    friend bool operator==(const ArcTracePoint&, const ArcTracePoint&) = default;
};

/// Evaluation-function circular interpolation, 4-connected. Inside a quadrant
/// one axis moves toward the centre's axis ("decreasing", |coord| shrinks)
/// and the other away from it: F >= 0: step the decreasing axis, F < 0: step
/// the increasing axis; F += 2·c·m + 1 for the moved coordinate c and move m
/// (seed 000 first quadrant CCW: F >= 0: F −= 2x − 1, x −= 1; F < 0:
/// F += 2y + 1, y += 1, x and y taken before the step). End counters KOX, KOY
/// per piece; a counter at zero disables its axis.
/// Invariant: away from the end correction, every point is within one step of
/// the circle (|√(x²+y²) − R| <= 1, checked for all R <= 100).
/// Complexity: O(steps) = O(arc length in steps), O(1) per step.
/// `trace`, when given, receives the point and F after every step.
/// Errors: as interpolate_arc. On error nothing is appended.
Result<void> eval_circular(std::int64_t x0, std::int64_t y0, std::int64_t x1, std::int64_t y1,
                           bool ccw, std::vector<Step>& out,
                           std::vector<ArcTracePoint>* trace = nullptr);

/// Accelerated (octant) evaluation-function circular interpolation,
/// 8-connected. The leading axis is the one with the smaller |coordinate|
/// (the faster one along the arc; it changes at the 45° line; on the line
/// itself the increasing axis leads — the seeds leave x == y open). Leading
/// axis increasing: F >= 0: diagonal, F < 0: leading only. Leading axis
/// decreasing: F >= 0: leading only, F < 0: diagonal. (Seed 000 first
/// quadrant CCW: x > y: F >= 0: x −= 1, y += 1, F += −2x + 2y + 2; F < 0:
/// y += 1, F += 2y + 1; x < y: F >= 0: x −= 1, F += −2x + 1; F < 0: diagonal.)
/// A counter at zero removes its axis from a diagonal.
/// Invariant: every point within one step of the circle (checked, R <= 100).
/// Complexity: O(steps), O(1) per step. Errors: as interpolate_arc.
Result<void> accelerated_circular(std::int64_t x0, std::int64_t y0, std::int64_t x1,
                                  std::int64_t y1, bool ccw, std::vector<Step>& out,
                                  std::vector<ArcTracePoint>* trace = nullptr);

}  // namespace stepzip
