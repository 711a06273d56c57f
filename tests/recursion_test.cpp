// Double recursion (seed 002): the points it visits are the rounded points
// R·(cos, sin)(φ0 + kΔφ) computed directly, and the recursion
// x[k+2] = 2a·x[k+1] − x[k] itself reproduces the rotation.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "stepzip/interpolate/recursion.hpp"

namespace stepzip {
namespace {

TEST(Recursion, TheRecurrenceIsARotation) {
    // Seed 002: from x[k+1] = a·x[k] − b·y[k], y[k+1] = b·x[k] + a·y[k] and
    // a² + b² = 1 follows x[k+2] = 2a·x[k+1] − x[k].
    const double d = 0.01, a = std::cos(d), b = std::sin(d);
    double x0 = 7, y0 = 2, x1 = a * x0 - b * y0, y1 = b * x0 + a * y0;
    for (int k = 0; k < 100; ++k) {
        const double x2 = 2 * a * x1 - x0, y2 = 2 * a * y1 - y0;
        EXPECT_NEAR(x2, a * x1 - b * y1, 1e-12);
        EXPECT_NEAR(y2, b * x1 + a * y1, 1e-12);
        x0 = x1; y0 = y1; x1 = x2; y1 = y2;
    }
}

// Quarter arcs from (R, 0) to (0, R): K = ceil(R·π/2) + 1 angles, each point
// the rounded R·(cos kΔφ, sin kΔφ). Radii where a coordinate falls within
// 1e-6 of a rounding tie are skipped (either rounding would be right).
TEST(Recursion, VisitsTheRoundedPointsOfTheCircle) {
    int checked = 0;
    for (std::int64_t r = 1; r <= 300; ++r) {
        const double sweep = std::numbers::pi / 2;
        const auto k_total = static_cast<std::int64_t>(std::ceil(sweep * static_cast<double>(r))) + 1;
        const double dphi = sweep / static_cast<double>(k_total);
        std::vector<std::pair<std::int64_t, std::int64_t>> want;
        bool tie = false;
        std::int64_t px = r, py = 0;
        for (std::int64_t k = 1; k <= k_total; ++k) {
            const double x = static_cast<double>(r) * std::cos(dphi * static_cast<double>(k));
            const double y = static_cast<double>(r) * std::sin(dphi * static_cast<double>(k));
            for (double v : {x, y})
                if (std::fabs(std::fabs(v - std::floor(v)) - 0.5) < 1e-6) tie = true;
            const auto nx = static_cast<std::int64_t>(std::llround(x));
            const auto ny = static_cast<std::int64_t>(std::llround(y));
            if (nx != px || ny != py) want.emplace_back(nx, ny);
            px = nx;
            py = ny;
        }
        if (tie) continue;
        std::vector<Step> steps;
        std::vector<ArcTracePoint> trace;
        ASSERT_TRUE(recursion_circular(r, 0, 0, r, true, steps, &trace));
        ASSERT_EQ(trace.size(), want.size()) << r;
        for (std::size_t i = 0; i < want.size(); ++i) {
            ASSERT_EQ(trace[i].x, want[i].first) << r << " i=" << i;
            ASSERT_EQ(trace[i].y, want[i].second) << r << " i=" << i;
        }
        ++checked;
    }
    EXPECT_GT(checked, 200);
}

// Long arcs exercise the restarts: a full circle of radius 20000 stays
// within √2/2 of the circle and returns to its start.
TEST(Recursion, LargeFullCircleStaysOnTheCircle) {
    std::vector<Step> steps;
    std::vector<ArcTracePoint> trace;
    ASSERT_TRUE(recursion_circular(12000, -16000, 12000, -16000, false, steps, &trace));
    double worst = 0;
    for (const ArcTracePoint& p : trace)
        worst = std::max(worst, std::fabs(std::hypot(static_cast<double>(p.x),
                                                     static_cast<double>(p.y)) - 20000.0));
    EXPECT_LE(worst, std::sqrt(0.5) + 1e-6);
    EXPECT_EQ(trace.back().x, 12000);
    EXPECT_EQ(trace.back().y, -16000);
}

}  // namespace
}  // namespace stepzip
