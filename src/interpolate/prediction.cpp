// Prediction and correction for circles (seed 004 §6.2.2.5, Fig. 6.30).
#include "stepzip/interpolate/prediction.hpp"

#include <cstdlib>

#include "arc_walk.hpp"

namespace stepzip {

namespace {
int sign(std::int64_t v) { return (v > 0) - (v < 0); }

// (2) correction: from the prediction P = (px, py), single steps toward the
// centre along P->O by the linear evaluation function until Fk < 0.
void correct(PredictionCycle& cyc, std::int64_t r2, bool lead_x) {
    std::int64_t fk = cyc.px * cyc.px + cyc.py * cyc.py - r2;
    cyc.fk = fk;
    cyc.corrections = 0;
    std::int64_t cx = cyc.px, cy = cyc.py;
    // On the 45° line the axis that did not lead goes first, so the
    // correction does not undo the leading move.
    const std::int64_t apx = std::llabs(cyc.px), apy = std::llabs(cyc.py);
    const bool major_x = apx > apy || (apx == apy && !lead_x);
    const std::int64_t mj = major_x ? apx : apy, mn = major_x ? apy : apx;
    std::int64_t fl = 0;
    while (fk >= 0 && (cx != 0 || cy != 0)) {
        const bool move_major = fl >= 0;
        const bool move_x = (move_major == major_x && cx != 0) || cy == 0;
        if (move_x) {
            fk -= 2 * std::llabs(cx) - 1;
            cx -= sign(cx);
        } else {
            fk -= 2 * std::llabs(cy) - 1;
            cy -= sign(cy);
        }
        fl += move_major ? -mn : mj;
        ++cyc.corrections;
    }
    cyc.cx = cx;
    cyc.cy = cy;
}
}  // namespace

Result<void> prediction_circular(std::int64_t x0, std::int64_t y0, std::int64_t x1,
                                 std::int64_t y1, bool ccw, std::vector<Step>& out,
                                 std::vector<PredictionCycle>* trace) {
    if (auto r = detail::check_arc(x0, y0, x1, y1, "prediction_circular"); !r) return r;
    detail::ArcState s = detail::make_state(x0, y0, out, nullptr);
    auto piece = [&](detail::ArcState& st, detail::Piece& pc) {
        const std::int64_t cap = 4 * (pc.cx + pc.cy) + 8;
        for (std::int64_t n = 0; n < cap && (pc.cx > 0 || pc.cy > 0); ++n) {
            // (1) prediction along the tangent (|tx|, |ty|) = (|y|, |x|).
            const std::int64_t ax = std::llabs(st.x), ay = std::llabs(st.y);
            const bool lead_x = ax < ay || (ax == ay && !pc.x_decreasing);
            int ux = lead_x ? 1 : (2 * ay >= ax ? 1 : 0);
            int uy = lead_x ? (2 * ax >= ay ? 1 : 0) : 1;
            if (pc.cx == 0) ux = 0;
            if (pc.cy == 0) uy = 0;
            if (ux == 0 && uy == 0) (pc.cx > 0 ? ux : uy) = 1;
            PredictionCycle cyc;
            cyc.px = st.x + ux * pc.mx;
            cyc.py = st.y + uy * pc.my;
            correct(cyc, st.r2, lead_x);
            // The node lies inside the circle, so the rounded tangent step may
            // too, where the seed assumes it outside: when the other choice of
            // the minor move gives a node nearer the circle that still moves
            // the leading axis, take that one.
            int vx = ux, vy = uy;
            if (lead_x && pc.cy > 0) vy = 1 - uy;
            if (!lead_x && pc.cx > 0) vx = 1 - ux;
            if ((vx != ux || vy != uy) && (vx || vy)) {
                PredictionCycle alt;
                alt.px = st.x + vx * pc.mx;
                alt.py = st.y + vy * pc.my;
                correct(alt, st.r2, lead_x);
                const std::int64_t f_cyc = cyc.cx * cyc.cx + cyc.cy * cyc.cy - st.r2;
                const std::int64_t f_alt = alt.cx * alt.cx + alt.cy * alt.cy - st.r2;
                const bool alt_moves = lead_x ? alt.cx != st.x : alt.cy != st.y;
                if (alt_moves && f_alt > f_cyc) cyc = alt;
            }
            const std::int64_t cx = cyc.cx, cy = cyc.cy;
            std::int64_t rx = cx - st.x, ry = cy - st.y;
            const std::int64_t along_x = rx * pc.mx, along_y = ry * pc.my;
            if ((rx == 0 && ry == 0) || along_x > pc.cx || along_y > pc.cy) break;
            // Emit M_i -> M_{i+1} as unit steps chosen by the sign of F.
            while (rx != 0 || ry != 0) {
                bool move_x;
                if (rx == 0) move_x = false;
                else if (ry == 0) move_x = true;
                else {
                    const bool x_shrinks = st.x * sign(rx) < 0;
                    move_x = (st.f() >= 0) == x_shrinks;
                }
                if (move_x) { st.step(sign(rx), 0); rx -= sign(rx); }
                else        { st.step(0, sign(ry)); ry -= sign(ry); }
            }
            pc.cx -= along_x;
            pc.cy -= along_y;
            if (trace) trace->push_back(cyc);
        }
    };
    detail::walk_arc(s, x1, y1, ccw, false, piece);
    return {};
}

}  // namespace stepzip
