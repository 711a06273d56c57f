// Internal: the arc geometry shared by the circular interpolators — argument
// checks, the cut into quadrant pieces with the seeds' end counters KOX/KOY,
// and the final correction run. Not installed.
#pragma once

#include <cstdint>
#include <vector>

#include "stepzip/error.hpp"
#include "stepzip/interpolate/circular.hpp"
#include "stepzip/step.hpp"

namespace stepzip::detail {

/// Checks the arguments of an arc (see interpolate_arc).
Result<void> check_arc(std::int64_t x0, std::int64_t y0, std::int64_t x1, std::int64_t y1,
                       const char* who);

/// round(√v) for v >= 0.
std::int64_t round_sqrt(std::int64_t v) noexcept;

/// The running point of an arc; every step goes through step().
struct ArcState {
    std::int64_t x = 0, y = 0;
    std::int64_t r2 = 0;      ///< R²
    std::int64_t rr = 0;      ///< round(R)
    std::vector<Step>* out = nullptr;
    std::vector<ArcTracePoint>* trace = nullptr;

    std::int64_t f() const noexcept { return x * x + y * y - r2; }
    void step(int sx, int sy) {
        out->push_back(make_step2(sx, sy));
        x += sx;
        y += sy;
        if (trace) trace->push_back({x, y, f()});
    }
};

/// The state at the start point (x0, y0) of an arc, R² = x0² + y0².
ArcState make_state(std::int64_t x0, std::int64_t y0, std::vector<Step>& out,
                    std::vector<ArcTracePoint>* trace);

/// One quadrant piece: the motion of each axis inside the quadrant and the
/// end counters toward its target.
struct Piece {
    int mx = 0, my = 0;          ///< direction of travel of x and y (±1)
    bool x_decreasing = false;   ///< true when the x move shrinks |x| (y's grows |y|)
    std::int64_t cx = 0, cy = 0; ///< KOX, KOY: unit moves left on each axis
    std::int64_t tx = 0, ty = 0; ///< target point
};

/// Runs `run(state, piece)` for every quadrant piece of the arc from the
/// state's point to (x1, y1), then a correction run to each piece's target
/// (4-connected when `eight` is false). `run` moves the state by steps in
/// (mx, my) and decrements the counters; it may stop early.
template <class Run>
void walk_arc(ArcState& s, std::int64_t x1, std::int64_t y1, bool ccw, bool eight, Run&& run);

/// A straight run from the state's point to (tx, ty): eval_linear with phase
/// 0 (4-connected) or accelerated_linear with phase 0 (8-connected).
void correction_run(ArcState& s, std::int64_t tx, std::int64_t ty, bool eight);

/// Quadrant index 0..3 (I..IV) of a point for the direction of travel; a
/// point on an axis belongs to the quadrant the motion enters.
int quadrant(std::int64_t x, std::int64_t y, bool ccw) noexcept;

/// The quadrant pieces: `count` quadrants starting at `first`, stepping by
/// +1 (ccw) or −1 (cw) modulo 4; the last one ends at the end point, the
/// others on an axis.
struct PiecePlan {
    int first = 0;
    int count = 1;
};
PiecePlan plan_pieces(std::int64_t x0, std::int64_t y0, std::int64_t x1, std::int64_t y1,
                      bool ccw) noexcept;

/// The piece of quadrant q from the state's point to its axis (last ==
/// false) or to (x1, y1) (last == true).
Piece make_piece(const ArcState& s, int q, bool ccw, bool last, std::int64_t x1,
                 std::int64_t y1) noexcept;

template <class Run>
void walk_arc(ArcState& s, std::int64_t x1, std::int64_t y1, bool ccw, bool eight, Run&& run) {
    const PiecePlan plan = plan_pieces(s.x, s.y, x1, y1, ccw);
    int q = plan.first;
    for (int i = 0; i < plan.count; ++i) {
        const bool last = i + 1 == plan.count;
        Piece p = make_piece(s, q, ccw, last, x1, y1);
        run(s, p);
        correction_run(s, p.tx, p.ty, eight);
        q = (q + (ccw ? 1 : 3)) & 3;
    }
}

}  // namespace stepzip::detail
