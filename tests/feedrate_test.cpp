// The feed-rate block (seed 000 "БЛОК ЗА ЗАДАВАНЕ НА СКОРОСТТА", seed 002):
// the ×1.41 / ×1.73 rule on hand-computed stamps, the DDA period formula,
// constant path speed with exact factors, and the synchronization buffer.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "stepzip/interpolate/dda.hpp"
#include "stepzip/interpolate/feedrate.hpp"

namespace stepzip {
namespace {

Step step3(int x, int y, int z) {
    const int d[3] = {x, y, z};
    return make_step(d, 3);
}

TEST(FeedRate, SeedFactors) {
    EXPECT_DOUBLE_EQ(axis_factor(1), 1.0);
    EXPECT_DOUBLE_EQ(axis_factor(2), 1.41);
    EXPECT_DOUBLE_EQ(axis_factor(3), 1.73);
    EXPECT_DOUBLE_EQ(axis_factor(4), 2.0);
    EXPECT_DOUBLE_EQ(axis_factor(2, AxisFactor::exact), std::sqrt(2.0));
}

// V = 10 steps/s, Δt = 0.1 s: x, xy, y, xyz, x. The interval after the
// two-axis step is 0.141 s, after the three-axis step 0.173 s.
TEST(FeedRate, HandComputedStamps) {
    const std::vector<Step> steps = {step3(1, 0, 0), step3(1, 1, 0), step3(0, 1, 0),
                                     step3(1, 1, -1), step3(-1, 0, 0)};
    auto t = feed_times(steps, 3, 10.0);
    ASSERT_TRUE(t);
    const double want[] = {0.1, 0.2, 0.341, 0.441, 0.614};
    ASSERT_EQ(t->size(), 5u);
    for (int i = 0; i < 5; ++i) EXPECT_NEAR((*t)[i], want[i], 1e-12) << i;
}

TEST(FeedRate, ExactFactorsKeepThePathSpeed) {
    std::mt19937 rng(7);
    std::vector<Step> steps;
    double length = 0;
    for (int i = 0; i < 1000; ++i) {
        int d[3];
        do {
            for (int& v : d) v = static_cast<int>(rng() % 3) - 1;
        } while (d[0] == 0 && d[1] == 0 && d[2] == 0);
        steps.push_back(make_step(d, 3));
        if (i < 999) length += std::sqrt(static_cast<double>(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
    }
    auto t = feed_times(steps, 3, 250.0, AxisFactor::exact);
    ASSERT_TRUE(t);
    EXPECT_NEAR(length / (t->back() - t->front()), 250.0, 1e-9);
}

TEST(FeedRate, RejectsBadInput) {
    EXPECT_FALSE(feed_times({make_step2(1, 0)}, 2, 0.0));
    EXPECT_FALSE(feed_times({make_step2(1, 0)}, 2, std::nan("")));
    auto r = feed_times({make_step2(1, 0), Step{0}}, 2, 1.0);
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("step 1"), std::string::npos);
}

// Δt = √(ΔX² + ΔY²) / (V·2^p): (3, 4) at V = 5 with p = 3 gives 5 / 40.
TEST(FeedRate, DdaPeriodFormula) {
    EXPECT_DOUBLE_EQ(dda_period(3, 4, 5.0, 3), 0.125);
    EXPECT_DOUBLE_EQ(dda_period(-6, 8, 2.0, 0), 5.0);
    EXPECT_DOUBLE_EQ(dda_period(3, 4, 0.0, 3), 0.0);
}

// A DDA line always runs 2^p cycles and the leading axis carries on the last
// one, so the last stamp is T = L / V whatever p is.
TEST(FeedRate, DdaLastStampIsLengthOverSpeed) {
    for (int dx = -40; dx <= 40; dx += 3)
        for (int dy = -40; dy <= 40; dy += 5) {
            if (dx == 0 && dy == 0) continue;
            for (int extra : {0, 3}) {
                std::vector<Step> steps;
                DdaTrace trace;
                ASSERT_TRUE(dda_linear(dx, dy, 0, steps, &trace));
                ASSERT_TRUE(dda_linear(dx, dy, trace.p + extra, steps, &trace));
                const double v = 12.5;
                const auto t = dda_times(trace, dda_period(dx, dy, v, trace.p));
                EXPECT_NEAR(t.back(), std::hypot(dx, dy) / v, 1e-9);
            }
        }
}

TEST(FeedRate, DdaTimesHandWorked) {
    std::vector<Step> steps;
    DdaTrace trace;
    ASSERT_TRUE(dda_linear(5, 3, 3, steps, &trace));  // carries at cycles 2..8
    const auto t = dda_times(trace, 0.5);
    EXPECT_EQ(t, (std::vector<double>{1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0}));
}

// Fast interpolator, buffer of 2: it runs ahead, stops when the buffer is
// full, and the drive keeps its clock.
TEST(SyncBuffer, FastInterpolatorWaitsForTheDrive) {
    auto r = simulate_sync_buffer({1, 2, 3, 4}, 0.25, 2);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->issued, (std::vector<double>{1, 2, 3, 4}));
    EXPECT_EQ(r->computed, (std::vector<double>{0.25, 0.5, 1.25, 2.25}));
    EXPECT_DOUBLE_EQ(r->interpolator_stall, 1.25);
    EXPECT_EQ(r->underruns, 0u);
    EXPECT_EQ(r->max_fill, 2u);
}

// Slow interpolator: every tick finds the buffer empty and the drive waits.
TEST(SyncBuffer, SlowInterpolatorDelaysTheDrive) {
    auto r = simulate_sync_buffer({1, 2, 3}, 1.5, 1);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->issued, (std::vector<double>{1.5, 3.0, 4.5}));
    EXPECT_EQ(r->underruns, 3u);
    EXPECT_DOUBLE_EQ(r->interpolator_stall, 0.0);
}

TEST(SyncBuffer, NeverHoldsMoreThanItsCapacity) {
    std::mt19937 rng(11);
    for (std::size_t cap = 1; cap <= 8; ++cap)
        for (int trial = 0; trial < 50; ++trial) {
            std::vector<double> drive;
            double t = 0;
            for (int i = 0; i < 200; ++i) {
                t += 0.5 + (rng() % 100) / 100.0;
                drive.push_back(t);
            }
            const double compute = (rng() % 150) / 100.0;
            auto r = simulate_sync_buffer(drive, compute, cap);
            ASSERT_TRUE(r);
            ASSERT_LE(r->max_fill, cap);
            for (std::size_t i = 0; i < drive.size(); ++i) {
                ASSERT_GE(r->issued[i], r->computed[i]);
                const double interval = drive[i] - (i ? drive[i - 1] : 0.0);
                const double prev = i ? r->issued[i - 1] : 0.0;
                ASSERT_GE(r->issued[i], prev + interval - 1e-12);
            }
        }
}

TEST(SyncBuffer, RejectsBadInput) {
    EXPECT_FALSE(simulate_sync_buffer({1, 2}, 0.1, 0));
    EXPECT_FALSE(simulate_sync_buffer({2, 1}, 0.1, 1));
    EXPECT_FALSE(simulate_sync_buffer({1, 2}, -1.0, 1));
}

}  // namespace
}  // namespace stepzip
