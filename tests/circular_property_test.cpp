// Properties of every circular interpolator over whole ranges: every step is
// a valid unit step (single-axis where the method is 4-connected), the path
// ends exactly on the end point, full circles return to the start, every
// point lies within one step of the ideal circle (1.5 for the DDA), and the motion never runs
// backward in angle. All R up to 100, all 8 quadrant × direction variants,
// arcs crossing quadrants, random arcs with a fixed seed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "stepzip/interpolate/arc.hpp"
#include "stepzip/interpolate/circular.hpp"

namespace stepzip {
namespace {

constexpr ArcMethod kMethods[] = {ArcMethod::evaluation, ArcMethod::accelerated, ArcMethod::dda,
                                  ArcMethod::prediction_correction, ArcMethod::double_recursion};

bool four_connected(ArcMethod m) {
    return m == ArcMethod::evaluation || m == ArcMethod::prediction_correction;
}

// The band around the ideal circle that every point keeps: one step, and
// 1.5 steps for the DDA, which has no evaluation-function feedback (dda.hpp).
double band(ArcMethod m) { return m == ArcMethod::dda ? 1.5 : 1.0; }

struct Walk {
    std::int64_t x = 0, y = 0;
    double max_dev = 0;      // max |√(x²+y²) − R| over the points
    bool backward = false;   // a step against the direction of travel
};

// Applies the steps from (x0, y0), checking each; returns the walk summary.
Walk walk(ArcMethod m, std::int64_t x0, std::int64_t y0, bool ccw, const std::vector<Step>& steps,
          const std::string& what) {
    Walk w{x0, y0};
    const double r = std::sqrt(static_cast<double>(x0 * x0 + y0 * y0));
    for (Step s : steps) {
        EXPECT_TRUE(step_valid(s, 2)) << what;
        if (four_connected(m)) EXPECT_EQ(step_weight(s), 1) << what;
        const int dx = step_axis(s, 0), dy = step_axis(s, 1);
        const std::int64_t cross = w.x * dy - w.y * dx;
        if (ccw ? cross < 0 : cross > 0) w.backward = true;
        w.x += dx;
        w.y += dy;
        const double d = std::fabs(std::sqrt(static_cast<double>(w.x * w.x + w.y * w.y)) - r);
        if (d > w.max_dev) w.max_dev = d;
    }
    return w;
}

std::string name(ArcMethod m, std::int64_t x0, std::int64_t y0, std::int64_t x1, std::int64_t y1,
                 bool ccw) {
    return std::string(arc_method_name(m)) + " (" + std::to_string(x0) + "," + std::to_string(y0) +
           ")->(" + std::to_string(x1) + "," + std::to_string(y1) + (ccw ? ") ccw" : ") cw");
}

TEST(CircularProperty, FullCirclesFromEveryAxisPointReturnWithinOneStep) {
    const std::int64_t axis[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    for (ArcMethod m : kMethods)
        for (std::int64_t r = 1; r <= 100; ++r)
            for (const auto& a : axis)
                for (bool ccw : {true, false}) {
                    const std::int64_t x0 = a[0] * r, y0 = a[1] * r;
                    std::vector<Step> steps;
                    const std::string what = name(m, x0, y0, x0, y0, ccw);
                    ASSERT_TRUE(interpolate_arc(m, x0, y0, x0, y0, ccw, steps)) << what;
                    const Walk w = walk(m, x0, y0, ccw, steps, what);
                    ASSERT_EQ(w.x, x0) << what;
                    ASSERT_EQ(w.y, y0) << what;
                    EXPECT_LE(w.max_dev, band(m)) << what;
                    EXPECT_FALSE(w.backward) << what;
                    if (m == ArcMethod::evaluation)
                        EXPECT_EQ(steps.size(), static_cast<std::size_t>(8 * r)) << what;
                    if (m == ArcMethod::accelerated) {
                        // Diagonals save steps: between 4R (all diagonal) and 8R.
                        EXPECT_GE(steps.size(), static_cast<std::size_t>(4 * r)) << what;
                        EXPECT_LT(steps.size(), static_cast<std::size_t>(8 * r)) << what;
                    }
                }
}

TEST(CircularProperty, FullCirclesFromEveryIntegerStartUpToCoordinate50) {
    for (ArcMethod m : kMethods)
        for (std::int64_t x0 = -50; x0 <= 50; ++x0)
            for (std::int64_t y0 = -50; y0 <= 50; ++y0) {
                if (x0 == 0 && y0 == 0) continue;
                for (bool ccw : {true, false}) {
                    std::vector<Step> steps;
                    const std::string what = name(m, x0, y0, x0, y0, ccw);
                    ASSERT_TRUE(interpolate_arc(m, x0, y0, x0, y0, ccw, steps)) << what;
                    const Walk w = walk(m, x0, y0, ccw, steps, what);
                    ASSERT_EQ(w.x, x0) << what;
                    ASSERT_EQ(w.y, y0) << what;
                    EXPECT_LE(w.max_dev, band(m)) << what;
                }
            }
}

TEST(CircularProperty, RandomArcsCrossingQuadrantsEndExactly) {
    std::mt19937_64 rng(20240611);
    std::uniform_int_distribution<int> coord(-100, 100);
    std::uniform_real_distribution<double> angle(0, 2 * std::numbers::pi);
    double worst[5] = {};
    for (int n = 0; n < 4000; ++n) {
        const std::int64_t x0 = coord(rng), y0 = coord(rng);
        if (x0 == 0 && y0 == 0) continue;
        const double r = std::sqrt(static_cast<double>(x0 * x0 + y0 * y0));
        const double phi = angle(rng);
        const auto x1 = static_cast<std::int64_t>(std::llround(r * std::cos(phi)));
        const auto y1 = static_cast<std::int64_t>(std::llround(r * std::sin(phi)));
        if (x1 == 0 && y1 == 0) continue;
        const bool ccw = (n & 1) != 0;
        for (ArcMethod m : kMethods) {
            std::vector<Step> steps;
            const std::string what = name(m, x0, y0, x1, y1, ccw);
            ASSERT_TRUE(interpolate_arc(m, x0, y0, x1, y1, ccw, steps)) << what;
            const Walk w = walk(m, x0, y0, ccw, steps, what);
            ASSERT_EQ(w.x, x1) << what;
            ASSERT_EQ(w.y, y1) << what;
            // The end is rounded onto the circle: the closing run may add up
            // to half a step to the band.
            EXPECT_LE(w.max_dev, band(m) + 0.5) << what;
            worst[static_cast<int>(m)] = std::max(worst[static_cast<int>(m)], w.max_dev);
        }
    }
    for (ArcMethod m : kMethods)
        RecordProperty(std::string("max_deviation_") + std::string(arc_method_name(m)),
                       std::to_string(worst[static_cast<int>(m)]));
}

// Rotating the whole problem by 90° rotates the path: the 8 variants are one
// rule (Fig. 6.21). Checked where no correction run is involved.
TEST(CircularProperty, EvaluationAndAcceleratedAreRotationSymmetric) {
    for (ArcMethod m : {ArcMethod::evaluation, ArcMethod::accelerated})
        for (std::int64_t r = 1; r <= 60; ++r)
            for (bool ccw : {true, false}) {
                std::vector<Step> base;
                ASSERT_TRUE(interpolate_arc(m, r, 0, r, 0, ccw, base));
                std::int64_t sx = r, sy = 0;
                for (int k = 1; k < 4; ++k) {
                    const std::int64_t tx = -sy, ty = sx;  // rotate the start by 90°
                    sx = tx;
                    sy = ty;
                    std::vector<Step> rot;
                    ASSERT_TRUE(interpolate_arc(m, sx, sy, sx, sy, ccw, rot));
                    ASSERT_EQ(rot.size(), base.size());
                    for (std::size_t i = 0; i < base.size(); ++i) {
                        int dx = step_axis(base[i], 0), dy = step_axis(base[i], 1);
                        for (int j = 0; j < k; ++j) {
                            const int t = -dy;
                            dy = dx;
                            dx = t;
                        }
                        ASSERT_EQ(rot[i], make_step2(dx, dy)) << r << " k=" << k << " i=" << i;
                    }
                }
            }
}

// Mirroring in the line y = x turns a counter-clockwise arc into a clockwise
// one: the steps are the mirrored steps.
TEST(CircularProperty, EvaluationAndAcceleratedMirrorBetweenDirections) {
    for (ArcMethod m : {ArcMethod::evaluation, ArcMethod::accelerated})
        for (std::int64_t r = 1; r <= 60; ++r) {
            std::vector<Step> ccw, cw;
            ASSERT_TRUE(interpolate_arc(m, r, 0, 0, r, true, ccw));
            ASSERT_TRUE(interpolate_arc(m, 0, r, r, 0, false, cw));
            ASSERT_EQ(ccw.size(), cw.size());
            for (std::size_t i = 0; i < ccw.size(); ++i)
                ASSERT_EQ(cw[i], make_step2(step_axis(ccw[i], 1), step_axis(ccw[i], 0))) << r;
        }
}

}  // namespace
}  // namespace stepzip
