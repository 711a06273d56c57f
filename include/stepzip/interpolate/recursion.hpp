// stepzip — circular interpolation by double recursion (seed 002 "Метод
// двойной рекурсии"). Thread-safe (no shared state).
#pragma once

#include <cstdint>
#include <vector>

#include "stepzip/error.hpp"
#include "stepzip/interpolate/circular.hpp"
#include "stepzip/step.hpp"

namespace stepzip {

/// Number of recursion steps between restarts from directly computed points.
inline constexpr int kRecursionRestart = 256;

/// Double recursion, 8-connected output. The points of the circle at angles
/// φ0 + k·Δφ satisfy x[k+2] = 2a·x[k+1] − x[k], y[k+2] = 2a·y[k+1] − y[k]
/// with a = cos Δφ (seed 002, from the rotation x[k+1] = a·x[k] − b·y[k],
/// y[k+1] = b·x[k] + a·y[k], b = sin Δφ, and a² + b² = 1). The sweep is cut
/// into K = ceil(sweep·R) + 1 equal angles, so one recursion step moves each
/// coordinate by less than one unit; the real points are rounded to the
/// nearest integers and each change of the rounded point is one unit step.
/// Computed in double precision; the three-term recursion lets rounding
/// errors grow with k, so it restarts from R·(cos, sin) every
/// kRecursionRestart steps. The last point is R·(cos φ1, sin φ1) rounded; the
/// correction run of interpolate_arc then reaches the end exactly.
/// Invariant: every point is within √2/2 + 1e-6 of the circle (before the
/// final correction run). Complexity: O(R·sweep). Errors: as interpolate_arc.
/// Does not promise bit-identical output across platforms whose libm differ
/// (cos/sin of the restarts).
Result<void> recursion_circular(std::int64_t x0, std::int64_t y0, std::int64_t x1,
                                std::int64_t y1, bool ccw, std::vector<Step>& out,
                                std::vector<ArcTracePoint>* trace = nullptr);

}  // namespace stepzip
