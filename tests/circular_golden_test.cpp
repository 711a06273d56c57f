// Golden vectors of the circular interpolators, worked by hand from the
// seeds' rules. Seed 000 and seed 004 give the rules (and seed 000 the
// register view) but their printed example tables did not survive in the
// text, so each vector below was computed by hand from the rule quoted
// beside it: the point and F = x² + y² − R² after every step.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "stepzip/interpolate/arc.hpp"
#include "stepzip/interpolate/circular.hpp"
#include "stepzip/interpolate/dda.hpp"
#include "stepzip/interpolate/prediction.hpp"

namespace stepzip {
namespace {

std::string freeman(const std::vector<Step>& steps) {
    std::string s;
    for (Step st : steps) s += static_cast<char>('0' + step_to_freeman(st));
    return s;
}

// Seed 000, first quadrant counter-clockwise: F >= 0: x −= 1, F += −2x + 1;
// F < 0: y += 1, F += 2y + 1 (x, y before the step); counters KOX = KOY = 5.
TEST(CircularGolden, EvaluationFirstQuadrantCcwRadius5) {
    std::vector<Step> steps;
    std::vector<ArcTracePoint> trace;
    ASSERT_TRUE(eval_circular(5, 0, 0, 5, true, steps, &trace));
    const std::vector<ArcTracePoint> want = {
        {4, 0, -9}, {4, 1, -8}, {4, 2, -5}, {4, 3, 0}, {3, 3, -7},
        {3, 4, 0},  {2, 4, -5}, {2, 5, 4},  {1, 5, 1}, {0, 5, 0}};
    EXPECT_EQ(trace, want);
    EXPECT_EQ(freeman(steps), "4222424244");
}

// The same quarter clockwise from (0, 5) to (5, 0) (Fig. 6.21: F >= 0 steps
// y −= 1, F < 0 steps x += 1) is its mirror in the line y = x.
TEST(CircularGolden, EvaluationFirstQuadrantCwRadius5) {
    std::vector<Step> steps;
    std::vector<ArcTracePoint> trace;
    ASSERT_TRUE(eval_circular(0, 5, 5, 0, false, steps, &trace));
    const std::vector<ArcTracePoint> want = {
        {0, 4, -9}, {1, 4, -8}, {2, 4, -5}, {3, 4, 0}, {3, 3, -7},
        {4, 3, 0},  {4, 2, -5}, {5, 2, 4},  {5, 1, 1}, {5, 0, 0}};
    EXPECT_EQ(trace, want);
}

// Seed 000 register view: registers 1 and 2 start at −2X_H and 2Y_H and
// change by 2 after their coordinate changes; the adder's carry input adds 1.
TEST(CircularGolden, EvaluationMatchesTheRegisterView) {
    std::vector<Step> steps;
    std::vector<ArcTracePoint> trace;
    ASSERT_TRUE(eval_circular(60, 11, 0, 61, true, steps, &trace));
    std::int64_t reg1 = -2 * 60, reg2 = 2 * 11, f = 0;
    for (std::size_t i = 0; i < steps.size(); ++i) {
        if (step_axis(steps[i], 0) != 0) { f += reg1 + 1; reg1 += 2; }
        else { f += reg2 + 1; reg2 += 2; }
        ASSERT_EQ(trace[i].f, f) << i;
    }
    EXPECT_EQ(trace.back().x, 0);
    EXPECT_EQ(trace.back().y, 61);
}

// A full circle of radius 2 crosses all four quadrants; each quarter is the
// previous one turned by 90°.
TEST(CircularGolden, EvaluationFullCircleRadius2) {
    std::vector<Step> steps;
    std::vector<ArcTracePoint> trace;
    ASSERT_TRUE(eval_circular(2, 0, 2, 0, true, steps, &trace));
    EXPECT_EQ(freeman(steps), "4224644606602002");
    ASSERT_EQ(trace.size(), 16u);
    EXPECT_EQ(trace[3], (ArcTracePoint{0, 2, 0}));
    EXPECT_EQ(trace[6], (ArcTracePoint{-2, 1, 1}));
    EXPECT_EQ(trace[15], (ArcTracePoint{2, 0, 0}));
}

// Seed 000 accelerated, first quadrant: x > y: F >= 0: x −= 1, y += 1,
// F += −2x + 2y + 2; F < 0: y += 1, F += 2y + 1. x < y: F >= 0: x −= 1,
// F += −2x + 1; F < 0: diagonal.
TEST(CircularGolden, AcceleratedFirstQuadrantCcwRadius5) {
    std::vector<Step> steps;
    std::vector<ArcTracePoint> trace;
    ASSERT_TRUE(accelerated_circular(5, 0, 0, 5, true, steps, &trace));
    const std::vector<ArcTracePoint> want = {{4, 1, -8}, {4, 2, -5}, {4, 3, 0}, {3, 4, 0},
                                             {2, 4, -5}, {1, 5, 1},  {0, 5, 0}};
    EXPECT_EQ(trace, want);
    EXPECT_EQ(freeman(steps), "3223434");
}

// On x == y the seeds leave the octant open; the increasing axis leads.
TEST(CircularGolden, AcceleratedFullCircleRadius2) {
    std::vector<Step> steps;
    ASSERT_TRUE(accelerated_circular(2, 0, 2, 0, true, steps));
    EXPECT_EQ(freeman(steps), "324546760102");
}

// DDA, radius 2: p = 2 (2^p >= round(R) + 2), registers start at 2; each
// cycle the x register adds |y|, then the y register adds |x| after the x
// move. Cycle 1: y carries; 3: x; 4: y; 6: x.
TEST(CircularGolden, DdaQuarterRadius2) {
    std::vector<Step> steps;
    DdaTrace trace;
    ASSERT_TRUE(dda_circular(2, 0, 0, 2, true, steps, &trace));
    EXPECT_EQ(freeman(steps), "2424");
    EXPECT_EQ(trace.p, 2);
    EXPECT_EQ(trace.step_cycle, (std::vector<std::uint64_t>{1, 3, 4, 6}));
    EXPECT_EQ(trace.cycles, 6u);
}

// Prediction and correction, radius 5 (seed 004 §6.2.2.5): tangent step,
// then steps toward the centre until Fк < 0.
TEST(CircularGolden, PredictionQuarterRadius5) {
    std::vector<Step> steps;
    std::vector<PredictionCycle> trace;
    ASSERT_TRUE(prediction_circular(5, 0, 0, 5, true, steps, &trace));
    ASSERT_EQ(trace.size(), 6u);
    const std::int64_t want[6][6] = {
        // px, py, fk, cx, cy, corrections
        {5, 1, 1, 4, 1, 1}, {4, 2, -5, 4, 2, 0}, {3, 3, -7, 3, 3, 0},
        {2, 4, -5, 2, 4, 0}, {1, 5, 1, 1, 4, 1}, {0, 4, -9, 0, 4, 0}};
    for (int i = 0; i < 6; ++i) {
        EXPECT_EQ(trace[i].px, want[i][0]) << i;
        EXPECT_EQ(trace[i].py, want[i][1]) << i;
        EXPECT_EQ(trace[i].fk, want[i][2]) << i;
        EXPECT_EQ(trace[i].cx, want[i][3]) << i;
        EXPECT_EQ(trace[i].cy, want[i][4]) << i;
        EXPECT_EQ(trace[i].corrections, want[i][5]) << i;
    }
    // Nodes joined by single-axis steps chosen by F's sign; the last unit
    // comes from the closing run (the cycle from (0,4) makes no progress).
    EXPECT_EQ(freeman(steps), "4222424442");
}

// An end point off the circle: the end counters (a forced step once KOX is
// spent) reach it exactly.
TEST(CircularGolden, EndOffTheCircleIsReachedByTheCounters) {
    std::vector<Step> steps;
    std::vector<ArcTracePoint> trace;
    ASSERT_TRUE(eval_circular(5, 0, 0, 6, true, steps, &trace));
    EXPECT_EQ(trace.back().x, 0);
    EXPECT_EQ(trace.back().y, 6);
    EXPECT_EQ(freeman(steps), "42224242442");
}

}  // namespace
}  // namespace stepzip
