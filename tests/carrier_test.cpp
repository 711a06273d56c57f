// Evaluation function on a constant carrier frequency (seed 004 §6.2.2.3):
// a hand-worked run with its error functions N_i, M_i, exact ends for every
// |dx|, |dy| <= 100 and several period counts, the bounds 0 <= N_i, M_i < n.
#include <gtest/gtest.h>

#include <cstdlib>
#include <vector>

#include "stepzip/interpolate/carrier.hpp"

namespace stepzip {
namespace {

// (5, 3) over n = 5 periods: Σ|Δy| = ceil(3i/5) = 1, 2, 2, 3, 3, so
// Δy = 1, 1, 0, 1, 0 and M_i = 5·Σ − 3i = 2, 4, 1, 3, 0.
TEST(CarrierLinear, HandWorkedFiveThree) {
    std::vector<Step> steps;
    std::vector<CarrierPeriod> trace;
    ASSERT_TRUE(carrier_linear(5, 3, 0, steps, &trace));
    const std::vector<CarrierPeriod> want = {
        {1, 1, 0, 2}, {1, 1, 0, 4}, {1, 0, 0, 1}, {1, 1, 0, 3}, {1, 0, 0, 0}};
    EXPECT_EQ(trace, want);
    EXPECT_EQ(steps.size(), 5u);
}

// (−2, 1) over 4 periods: Σ|Δx| = ceil(2i/4) = 1, 1, 2, 2; Σ|Δy| = 1, 1, 1, 1.
TEST(CarrierLinear, HandWorkedWithIdlePeriods) {
    std::vector<Step> steps;
    std::vector<CarrierPeriod> trace;
    ASSERT_TRUE(carrier_linear(-2, 1, 4, steps, &trace));
    const std::vector<CarrierPeriod> want = {
        {-1, 1, 2, 3}, {0, 0, 0, 2}, {-1, 0, 2, 1}, {0, 0, 0, 0}};
    EXPECT_EQ(trace, want);
    EXPECT_EQ(steps, (std::vector<Step>{make_step2(-1, 1), make_step2(-1, 0)}));
}

TEST(CarrierLinear, EndsExactlyWithBoundedErrorsForAllSmallTotals) {
    for (int dx = -100; dx <= 100; ++dx)
        for (int dy = -100; dy <= 100; ++dy) {
            const int l = std::max(std::abs(dx), std::abs(dy));
            for (int n : {0, l + 1, 2 * l + 3}) {
                if (l == 0 && n > 0) continue;
                std::vector<Step> steps;
                std::vector<CarrierPeriod> trace;
                ASSERT_TRUE(carrier_linear(dx, dy, n, steps, &trace));
                const std::int64_t periods = n > 0 ? n : l;
                ASSERT_EQ(static_cast<std::int64_t>(trace.size()), periods);
                std::int64_t x = 0, y = 0;
                for (Step s : steps) {
                    ASSERT_TRUE(step_valid(s, 2));
                    x += step_axis(s, 0);
                    y += step_axis(s, 1);
                }
                ASSERT_EQ(x, dx);
                ASSERT_EQ(y, dy);
                for (const CarrierPeriod& p : trace) {
                    ASSERT_GE(p.n, 0);
                    ASSERT_LT(p.n, std::max<std::int64_t>(periods, 1));
                    ASSERT_GE(p.m, 0);
                    ASSERT_LT(p.m, std::max<std::int64_t>(periods, 1));
                }
                if (!trace.empty()) {
                    ASSERT_EQ(trace.back().n, 0);
                    ASSERT_EQ(trace.back().m, 0);
                }
            }
        }
}

TEST(CarrierLinear, RejectsTooFewPeriods) {
    std::vector<Step> steps;
    auto r = carrier_linear(7, 2, 6, steps);
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().code, Errc::invalid_argument);
    EXPECT_TRUE(steps.empty());
}

}  // namespace
}  // namespace stepzip
