// stepzip — circular interpolation by prediction and correction (seed 004
// §6.2.2.5, Fig. 6.30). Thread-safe (no shared state).
#pragma once

#include <cstdint>
#include <vector>

#include "stepzip/error.hpp"
#include "stepzip/interpolate/circular.hpp"
#include "stepzip/step.hpp"

namespace stepzip {

/// One cycle of the method: node M_i, predicted point P and corrected node.
struct PredictionCycle {
    std::int64_t px = 0, py = 0;   ///< prediction along the tangent
    std::int64_t fk = 0;           ///< Fк at the prediction, px² + py² − R²
    std::int64_t cx = 0, cy = 0;   ///< corrected node M_{i+1}
    int corrections = 0;           ///< correction steps toward the centre
};

/// Prediction and correction, 4-connected output. Each cycle from node
/// M_i = (x, y): (1) prediction, one step along the tangent: the leading axis
/// (smaller |coordinate|) moves one unit in the direction of travel and the
/// other axis moves round(|lead|/|other|) ∈ {0, 1} (the tangent's slope);
/// the node lies inside the circle, so that P may be too (the seed assumes
/// it outside): when the other choice of the minor move gives a corrected
/// node nearer the circle that still moves the leading axis, it is taken;
/// (2) correction, when Fк = px² + py² − R² >= 0: single steps from P toward
/// the centre O along the line P→O by the linear evaluation function
/// (Fл = 0 at P; Fл >= 0: the axis with the larger |coordinate| of P moves
/// toward O (on a tie the axis that did not lead), Fл −= the other |coordinate| of P; Fл < 0: the other axis moves,
/// Fл += the larger one; Fк updated exactly) until Fк < 0. Seed 004 writes
/// the rule for the octant |y| > |x| (Fл >= 0: y −= 1, Fл −= x_P;
/// Fл < 0: x −= 1, Fл += y_P); the other octant is its mirror. The node is
/// then inside the circle by less than one step (seed 004). The move
/// M_i → M_{i+1} is emitted as single-axis unit steps, each one chosen by the
/// sign of F like eval_circular. Quadrant pieces and end counters as in
/// interpolate_arc; a cycle that would overshoot a counter ends the piece
/// with the correction run.
/// A cycle with no net move also ends the piece that way.
/// Invariant: every node satisfies F < 0 or is the start; every emitted point
/// lies within one step of the circle (checked, R <= 100).
/// Complexity: O(1) amortized per step. Errors: as interpolate_arc.
Result<void> prediction_circular(std::int64_t x0, std::int64_t y0, std::int64_t x1,
                                 std::int64_t y1, bool ccw, std::vector<Step>& out,
                                 std::vector<PredictionCycle>* trace = nullptr);

}  // namespace stepzip
