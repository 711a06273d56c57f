// Double recursion for circles (seed 002): x[k+2] = 2a·x[k+1] − x[k].
#include "stepzip/interpolate/recursion.hpp"

#include <cmath>
#include <cstdlib>
#include <numbers>

#include "arc_walk.hpp"
#include "stepzip/interpolate/linear.hpp"

namespace stepzip {

Result<void> recursion_circular(std::int64_t x0, std::int64_t y0, std::int64_t x1,
                                std::int64_t y1, bool ccw, std::vector<Step>& out,
                                std::vector<ArcTracePoint>* trace) {
    if (auto r = detail::check_arc(x0, y0, x1, y1, "recursion_circular"); !r) return r;
    detail::ArcState s = detail::make_state(x0, y0, out, trace);
    const double radius = std::sqrt(static_cast<double>(s.r2));
    const double phi0 = std::atan2(static_cast<double>(y0), static_cast<double>(x0));
    // Sweep in the direction of travel, in (0, 2π]; the end on the start's
    // ray (end == start included) is a full circle.
    const std::int64_t cross = x0 * y1 - y0 * x1, dot = x0 * x1 + y0 * y1;
    double sweep;
    if (cross == 0 && dot > 0) {
        sweep = 2 * std::numbers::pi;
    } else {
        const double phi1 = std::atan2(static_cast<double>(y1), static_cast<double>(x1));
        sweep = ccw ? phi1 - phi0 : phi0 - phi1;
        while (sweep <= 0) sweep += 2 * std::numbers::pi;
        while (sweep > 2 * std::numbers::pi) sweep -= 2 * std::numbers::pi;
    }
    const auto k_total = static_cast<std::int64_t>(std::ceil(sweep * radius)) + 1;
    const double dphi = (ccw ? sweep : -sweep) / static_cast<double>(k_total);
    const double a2 = 2 * std::cos(dphi);
    auto exact = [&](std::int64_t k, double& x, double& y) {
        const double phi = phi0 + dphi * static_cast<double>(k);
        x = radius * std::cos(phi);
        y = radius * std::sin(phi);
    };
    double xp = static_cast<double>(x0), yp = static_cast<double>(y0);  // x[k-1]
    double xc, yc;                                                        // x[k]
    exact(1, xc, yc);
    for (std::int64_t k = 1; k <= k_total; ++k) {
        if (k > 1) {
            if (k % kRecursionRestart == 0) {
                exact(k - 1, xp, yp);
                exact(k, xc, yc);
            } else {
                const double xn = a2 * xc - xp, yn = a2 * yc - yp;  // (***) of seed 002
                xp = xc;
                yp = yc;
                xc = xn;
                yc = yn;
            }
        }
        const auto nx = static_cast<std::int64_t>(std::llround(xc));
        const auto ny = static_cast<std::int64_t>(std::llround(yc));
        const std::int64_t dx = nx - s.x, dy = ny - s.y;
        if (dx == 0 && dy == 0) continue;
        if (std::llabs(dx) <= 1 && std::llabs(dy) <= 1) s.step(static_cast<int>(dx), static_cast<int>(dy));
        else detail::correction_run(s, nx, ny, true);  // not reached while Δφ·R < 1
    }
    detail::correction_run(s, x1, y1, true);
    return {};
}

}  // namespace stepzip
