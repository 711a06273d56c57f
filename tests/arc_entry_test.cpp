// The uniform entry points of arc.hpp: method names, dispatch to the
// interpolator of each method, direction, errors (with `out` unchanged), and
// lines that end exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "stepzip/interpolate/arc.hpp"
#include "stepzip/interpolate/circular.hpp"
#include "stepzip/interpolate/dda.hpp"
#include "stepzip/interpolate/prediction.hpp"
#include "stepzip/interpolate/recursion.hpp"

namespace stepzip {
namespace {

TEST(ArcEntry, MethodNamesRoundTrip) {
    for (ArcMethod m : {ArcMethod::evaluation, ArcMethod::accelerated, ArcMethod::dda,
                        ArcMethod::prediction_correction, ArcMethod::double_recursion})
        EXPECT_EQ(parse_arc_method(arc_method_name(m)), m);
    EXPECT_EQ(parse_arc_method("prediction"), ArcMethod::prediction_correction);
    EXPECT_EQ(parse_arc_method("recursion"), ArcMethod::double_recursion);
    EXPECT_FALSE(parse_arc_method("circle"));
    EXPECT_FALSE(parse_arc_method(""));
    EXPECT_EQ(parse_line_method("dda"), LineMethod::dda);
    EXPECT_EQ(parse_line_method("carrier"), LineMethod::carrier);
    EXPECT_EQ(line_method_name(LineMethod::carrier), "carrier");
    EXPECT_FALSE(parse_line_method("eval"));
}

TEST(ArcEntry, DispatchesToEachMethod) {
    std::vector<Step> a, b;
    ASSERT_TRUE(interpolate_arc(ArcMethod::evaluation, 7, 3, -3, 7, true, a));
    ASSERT_TRUE(eval_circular(7, 3, -3, 7, true, b));
    EXPECT_EQ(a, b);
    a.clear(); b.clear();
    ASSERT_TRUE(interpolate_arc(ArcMethod::accelerated, 7, 3, -3, 7, true, a));
    ASSERT_TRUE(accelerated_circular(7, 3, -3, 7, true, b));
    EXPECT_EQ(a, b);
    a.clear(); b.clear();
    ASSERT_TRUE(interpolate_arc(ArcMethod::dda, 7, 3, -3, 7, true, a));
    ASSERT_TRUE(dda_circular(7, 3, -3, 7, true, b));
    EXPECT_EQ(a, b);
    a.clear(); b.clear();
    ASSERT_TRUE(interpolate_arc(ArcMethod::prediction_correction, 7, 3, -3, 7, true, a));
    ASSERT_TRUE(prediction_circular(7, 3, -3, 7, true, b));
    EXPECT_EQ(a, b);
    a.clear(); b.clear();
    ASSERT_TRUE(interpolate_arc(ArcMethod::double_recursion, 7, 3, -3, 7, true, a));
    ASSERT_TRUE(recursion_circular(7, 3, -3, 7, true, b));
    EXPECT_EQ(a, b);
}

// A half circle from (10, 0) to (−10, 0) passes above the centre counter-
// clockwise (G3) and below it clockwise (G2).
TEST(ArcEntry, DirectionPicksTheHalf) {
    for (ArcMethod m : {ArcMethod::evaluation, ArcMethod::accelerated, ArcMethod::dda,
                        ArcMethod::prediction_correction, ArcMethod::double_recursion})
        for (bool ccw : {true, false}) {
            std::vector<Step> steps;
            ASSERT_TRUE(interpolate_arc(m, 10, 0, -10, 0, ccw, steps));
            std::int64_t x = 10, y = 0, ymin = 0, ymax = 0;
            for (Step s : steps) {
                x += step_axis(s, 0);
                y += step_axis(s, 1);
                ymin = std::min(ymin, y);
                ymax = std::max(ymax, y);
            }
            EXPECT_EQ(x, -10);
            EXPECT_EQ(y, 0);
            if (ccw) { EXPECT_GE(ymax, 9); EXPECT_EQ(ymin, 0); }
            else     { EXPECT_LE(ymin, -9); EXPECT_EQ(ymax, 0); }
        }
}

TEST(ArcEntry, ErrorsLeaveTheOutputUnchanged) {
    const std::int64_t big = kMaxInterpolateCoord + 1;
    for (ArcMethod m : {ArcMethod::evaluation, ArcMethod::accelerated, ArcMethod::dda,
                        ArcMethod::prediction_correction, ArcMethod::double_recursion}) {
        std::vector<Step> out = {make_step2(1, 0)};
        const struct { std::int64_t x0, y0, x1, y1; } bad[] = {
            {0, 0, 1, 0},        // R == 0
            {big, 0, 0, big},    // beyond the limit
            {5, 0, 0, 0},        // end at the centre
            {50, 0, 0, 80},      // end far off the circle
        };
        for (const auto& b : bad) {
            auto r = interpolate_arc(m, b.x0, b.y0, b.x1, b.y1, true, out);
            ASSERT_FALSE(r);
            EXPECT_EQ(r.error().code, Errc::invalid_argument);
            EXPECT_NE(r.error().message.find("arc ("), std::string::npos) << r.error().message;
        }
        EXPECT_EQ(out.size(), 1u);
    }
}

TEST(ArcEntry, LinesEndExactly) {
    for (LineMethod m : {LineMethod::dda, LineMethod::carrier})
        for (int dx = -100; dx <= 100; ++dx)
            for (int dy = -100; dy <= 100; dy += 7) {
                std::vector<Step> steps;
                ASSERT_TRUE(interpolate_line(m, dx, dy, steps));
                std::int64_t x = 0, y = 0;
                for (Step s : steps) {
                    ASSERT_TRUE(step_valid(s, 2));
                    x += step_axis(s, 0);
                    y += step_axis(s, 1);
                }
                ASSERT_EQ(x, dx);
                ASSERT_EQ(y, dy);
            }
    std::vector<Step> steps;
    EXPECT_FALSE(interpolate_line(LineMethod::dda, kMaxInterpolateCoord + 1, 0, steps));
    EXPECT_FALSE(interpolate_line(LineMethod::carrier, 0, -kMaxInterpolateCoord - 1, steps));
    EXPECT_TRUE(steps.empty());
}

}  // namespace
}  // namespace stepzip
