// Arc geometry shared by the circular interpolators (seed 000, seed 004
// Fig. 6.21): checks, quadrant pieces, correction run.
#include "arc_walk.hpp"

#include <cmath>
#include <algorithm>
#include <cstdlib>
#include <string>

#include "stepzip/interpolate/arc.hpp"
#include "stepzip/interpolate/linear.hpp"

namespace stepzip::detail {

namespace {
// Motion of (x, y) inside quadrant q when travelling counter-clockwise:
// I (−,+), II (−,−), III (+,−), IV (+,+); clockwise is the opposite.
constexpr int kCcwMx[4] = {-1, -1, +1, +1};
constexpr int kCcwMy[4] = {+1, -1, -1, +1};
// Signs of the coordinates inside quadrant q.
constexpr int kQx[4] = {+1, -1, -1, +1};
constexpr int kQy[4] = {+1, +1, -1, -1};
}  // namespace

std::int64_t round_sqrt(std::int64_t v) noexcept {
    if (v <= 0) return 0;
    auto r = static_cast<std::int64_t>(std::sqrt(static_cast<double>(v)));
    while (r * r > v) --r;
    while ((r + 1) * (r + 1) <= v) ++r;
    // (r + 1/2)² = r² + r + 1/4: round up when v > r² + r.
    return v - r * r > r ? r + 1 : r;
}

Result<void> check_arc(std::int64_t x0, std::int64_t y0, std::int64_t x1, std::int64_t y1,
                       const char* who) {
    const std::int64_t lim = kMaxInterpolateCoord;
    const auto where = [&] {
        return std::string(who) + ": arc (" + std::to_string(x0) + "," + std::to_string(y0) +
               ")->(" + std::to_string(x1) + "," + std::to_string(y1) + ")";
    };
    for (std::int64_t c : {x0, y0, x1, y1})
        if (c < -lim || c > lim)
            return make_error(Errc::invalid_argument,
                              where() + ": coordinate beyond the limit 2^24");
    if (x0 == 0 && y0 == 0)
        return make_error(Errc::invalid_argument, where() + ": radius 0 (start at the centre)");
    if (x1 == 0 && y1 == 0)
        return make_error(Errc::invalid_argument, where() + ": end at the centre");
    const double r = std::sqrt(static_cast<double>(x0 * x0 + y0 * y0));
    const double re = std::sqrt(static_cast<double>(x1 * x1 + y1 * y1));
    if (std::fabs(re - r) > std::fmax(2.0, r / 8))
        return make_error(Errc::invalid_argument,
                          where() + ": end not on the circle (|end| = " + std::to_string(re) +
                              ", R = " + std::to_string(r) + ")");
    return {};
}

ArcState make_state(std::int64_t x0, std::int64_t y0, std::vector<Step>& out,
                    std::vector<ArcTracePoint>* trace) {
    ArcState s;
    s.x = x0;
    s.y = y0;
    s.r2 = x0 * x0 + y0 * y0;
    s.rr = round_sqrt(s.r2);
    s.out = &out;
    s.trace = trace;
    return s;
}

int quadrant(std::int64_t x, std::int64_t y, bool ccw) noexcept {
    if (ccw) {
        if (x > 0 && y >= 0) return 0;
        if (x <= 0 && y > 0) return 1;
        if (x < 0 && y <= 0) return 2;
        return 3;
    }
    if (x >= 0 && y > 0) return 0;
    if (x < 0 && y >= 0) return 1;
    if (x <= 0 && y < 0) return 2;
    return 3;
}

PiecePlan plan_pieces(std::int64_t x0, std::int64_t y0, std::int64_t x1, std::int64_t y1,
                      bool ccw) noexcept {
    const int qs = quadrant(x0, y0, ccw), qe = quadrant(x1, y1, ccw);
    const std::int64_t cross = x0 * y1 - y0 * x1;
    const bool ahead = ccw ? cross > 0 : cross < 0;
    PiecePlan plan;
    plan.first = qs;
    if (qs == qe && ahead) {
        plan.count = 1;
    } else if (qs == qe) {
        plan.count = 5;  // full circle (end == start, or behind the start)
    } else {
        const int d = ccw ? (qe - qs + 4) & 3 : (qs - qe + 4) & 3;
        plan.count = d + 1;
    }
    return plan;
}

Piece make_piece(const ArcState& s, int q, bool ccw, bool last, std::int64_t x1,
                 std::int64_t y1) noexcept {
    Piece p;
    p.mx = ccw ? kCcwMx[q] : -kCcwMx[q];
    p.my = ccw ? kCcwMy[q] : -kCcwMy[q];
    p.x_decreasing = p.mx * kQx[q] < 0;
    if (last) {
        p.tx = x1;
        p.ty = y1;
    } else if (p.x_decreasing) {
        // The piece ends on the y axis, at least round(R) from the centre.
        p.tx = 0;
        p.ty = p.my * std::max<std::int64_t>(s.rr, std::llabs(s.y));
    } else {
        p.ty = 0;
        p.tx = p.mx * std::max<std::int64_t>(s.rr, std::llabs(s.x));
    }
    p.cx = std::max<std::int64_t>(0, (p.tx - s.x) * p.mx);
    p.cy = std::max<std::int64_t>(0, (p.ty - s.y) * p.my);
    return p;
}

void correction_run(ArcState& s, std::int64_t tx, std::int64_t ty, bool eight) {
    const std::int64_t dx = tx - s.x, dy = ty - s.y;
    if (dx == 0 && dy == 0) return;
    std::vector<Step> run;
    if (eight) accelerated_linear(dx, dy, 0, run);
    else eval_linear(dx, dy, 0, run);
    for (Step st : run) s.step(step_axis(st, 0), step_axis(st, 1));
}

}  // namespace stepzip::detail
