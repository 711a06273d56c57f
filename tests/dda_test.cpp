// Linear DDA (seed 004 §6.2.2.4, seed 000: 2^p cycles): a hand-worked run,
// exact ends for every |dx|, |dy| <= 100 and several register widths, the
// "on or below the line" property, and argument errors.
#include <gtest/gtest.h>

#include <cstdlib>
#include <vector>

#include "stepzip/interpolate/dda.hpp"

namespace stepzip {
namespace {

// (5, 3), p = 3: registers add 5 and 3 each of 8 cycles. x carries at cycles
// 2, 4, 5, 7, 8; y at 3, 6, 8.
TEST(DdaLinear, HandWorkedFiveThree) {
    std::vector<Step> steps;
    DdaTrace trace;
    ASSERT_TRUE(dda_linear(5, 3, 3, steps, &trace));
    const std::vector<Step> want = {make_step2(1, 0), make_step2(0, 1), make_step2(1, 0),
                                    make_step2(1, 0), make_step2(0, 1), make_step2(1, 0),
                                    make_step2(1, 1)};
    EXPECT_EQ(steps, want);
    EXPECT_EQ(trace.step_cycle, (std::vector<std::uint64_t>{2, 3, 4, 5, 6, 7, 8}));
    EXPECT_EQ(trace.cycles, 8u);
    EXPECT_EQ(trace.p, 3);
}

TEST(DdaLinear, AutomaticWidthIsTheSmallestThatFits) {
    std::vector<Step> steps;
    DdaTrace trace;
    ASSERT_TRUE(dda_linear(-100, 37, 0, steps, &trace));
    EXPECT_EQ(trace.p, 7);  // 64 < 100 <= 128
    ASSERT_TRUE(dda_linear(64, 1, 0, steps, &trace));
    EXPECT_EQ(trace.p, 6);
}

TEST(DdaLinear, EndsExactlyAndStaysOnOrBelowTheLineForAllSmallTotals) {
    for (int dx = -100; dx <= 100; ++dx)
        for (int dy = -100; dy <= 100; ++dy)
            for (int extra : {0, 2}) {
                std::vector<Step> steps;
                DdaTrace trace;
                int p = 0;
                while ((1 << p) < std::max(std::abs(dx), std::abs(dy))) ++p;
                ASSERT_TRUE(dda_linear(dx, dy, p + extra, steps, &trace));
                std::int64_t x = 0, y = 0;
                const std::int64_t w = std::int64_t{1} << trace.p;
                for (std::size_t i = 0; i < steps.size(); ++i) {
                    ASSERT_TRUE(step_valid(steps[i], 2));
                    x += step_axis(steps[i], 0);
                    y += step_axis(steps[i], 1);
                    // After cycle c each axis has carried floor(c·|d| / 2^p) times.
                    const auto c = static_cast<std::int64_t>(trace.step_cycle[i]);
                    ASSERT_EQ(std::llabs(x), c * std::abs(dx) / w) << dx << "," << dy;
                    ASSERT_EQ(std::llabs(y), c * std::abs(dy) / w) << dx << "," << dy;
                }
                ASSERT_EQ(x, dx);
                ASSERT_EQ(y, dy);
                // One step per cycle with a carry: between max and sum of |d|.
                ASSERT_GE(steps.size(), static_cast<std::size_t>(
                                            std::max(std::abs(dx), std::abs(dy))));
                ASSERT_LE(steps.size(), static_cast<std::size_t>(std::abs(dx) + std::abs(dy)));
            }
}

TEST(DdaLinear, RejectsNarrowRegistersAndHugeTotals) {
    std::vector<Step> steps;
    auto r = dda_linear(9, 1, 3, steps);  // 2^3 < 9
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().code, Errc::invalid_argument);
    EXPECT_NE(r.error().message.find("dda_linear(9,1"), std::string::npos);
    EXPECT_FALSE(dda_linear(std::int64_t{1} << 30, 0, 0, steps));
    EXPECT_FALSE(dda_linear(1, 1, 41, steps));
    EXPECT_TRUE(steps.empty());
}

}  // namespace
}  // namespace stepzip
