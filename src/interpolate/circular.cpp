// Evaluation-function circular interpolation and its accelerated octant
// version (seed 000 "Кръгова интерполация", "УСКОРЕН АЛГОРИТЪМ"; seed 004
// §6.2.2.1 Fig. 6.21, §6.2.2.2).
#include "stepzip/interpolate/circular.hpp"

#include <cstdlib>

#include "arc_walk.hpp"

namespace stepzip {

using detail::ArcState;
using detail::Piece;

namespace {

// One quadrant by the evaluation function: F >= 0 steps the decreasing axis,
// F < 0 the increasing one; a counter at zero forces the other axis.
void eval_piece(ArcState& s, Piece& p) {
    while (p.cx > 0 || p.cy > 0) {
        const bool want_decreasing = s.f() >= 0;
        bool move_x = want_decreasing == p.x_decreasing;
        if (move_x && p.cx == 0) move_x = false;
        else if (!move_x && p.cy == 0) move_x = true;
        if (move_x) { s.step(p.mx, 0); --p.cx; }
        else        { s.step(0, p.my); --p.cy; }
    }
}

// One quadrant by the accelerated rule: the axis with the smaller |coord|
// leads (ties: the increasing axis); diagonal or leading-only by F's sign.
void accelerated_piece(ArcState& s, Piece& p) {
    while (p.cx > 0 || p.cy > 0) {
        const std::int64_t ax = std::llabs(s.x), ay = std::llabs(s.y);
        const bool lead_x = ax < ay || (ax == ay && !p.x_decreasing);
        const bool lead_decreasing = lead_x == p.x_decreasing;
        const bool f_nonneg = s.f() >= 0;
        const bool diag = lead_decreasing ? !f_nonneg : f_nonneg;
        int dx = (lead_x || diag) ? 1 : 0;
        int dy = (!lead_x || diag) ? 1 : 0;
        if (p.cx == 0) dx = 0;
        if (p.cy == 0) dy = 0;
        if (dx == 0 && dy == 0) (p.cx > 0 ? dx : dy) = 1;
        s.step(dx * p.mx, dy * p.my);
        p.cx -= dx;
        p.cy -= dy;
    }
}

}  // namespace

Result<void> eval_circular(std::int64_t x0, std::int64_t y0, std::int64_t x1, std::int64_t y1,
                           bool ccw, std::vector<Step>& out, std::vector<ArcTracePoint>* trace) {
    if (auto r = detail::check_arc(x0, y0, x1, y1, "eval_circular"); !r) return r;
    ArcState s = detail::make_state(x0, y0, out, trace);
    detail::walk_arc(s, x1, y1, ccw, false, eval_piece);
    return {};
}

Result<void> accelerated_circular(std::int64_t x0, std::int64_t y0, std::int64_t x1,
                                  std::int64_t y1, bool ccw, std::vector<Step>& out,
                                  std::vector<ArcTracePoint>* trace) {
    if (auto r = detail::check_arc(x0, y0, x1, y1, "accelerated_circular"); !r) return r;
    ArcState s = detail::make_state(x0, y0, out, trace);
    detail::walk_arc(s, x1, y1, ccw, true, accelerated_piece);
    return {};
}

}  // namespace stepzip
