// Core types: steps, chains, Freeman-8 conversion.
#include <gtest/gtest.h>

#include <random>

#include "stepzip/chain.hpp"

namespace stepzip {
namespace {

TEST(Step, FreemanCodesMatchTheSpecTable) {
    const int expect[8][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
    for (int c = 0; c < 8; ++c) {
        const Step s = freeman_to_step(c);
        EXPECT_EQ(step_axis(s, 0), expect[c][0]);
        EXPECT_EQ(step_axis(s, 1), expect[c][1]);
        EXPECT_EQ(step_to_freeman(s), c);
        EXPECT_TRUE(step_valid(s, 2));
        EXPECT_EQ(s, make_step2(expect[c][0], expect[c][1]));
    }
}

TEST(Step, ValidityRules) {
    EXPECT_FALSE(step_valid(0, 2));
    EXPECT_FALSE(step_valid(0x02, 2));   // direction bit on a resting axis
    EXPECT_FALSE(step_valid(0x10, 2));   // axis 2 on a two-axis chain
    EXPECT_TRUE(step_valid(0x10, 3));
    EXPECT_EQ(step_weight(0x15), 3);
}

TEST(Chain, FreemanRoundTripAndEnd) {
    auto c = from_freeman(3, -2, "0123456701");
    ASSERT_TRUE(c);
    EXPECT_EQ(*to_freeman(*c), "0123456701");
    EXPECT_EQ(c->end()[0], 3 + 1 + 1);
    EXPECT_EQ(c->end()[1], -2 + 1);
    EXPECT_FALSE(c->four_connected());
    EXPECT_TRUE(from_freeman(0, 0, "0246")->four_connected());
    EXPECT_EQ(chain_points(*c).size(), 11u);
}

// end() sums each axis in one pass; it must read every step as apply_step()
// does, a DIR bit on a resting axis (invalid, "10") included.
TEST(Chain, EndIsTheLastPointOnEveryAxisCount) {
    std::mt19937 rng(11);
    for (int axes = 2; axes <= kMaxAxes; ++axes) {
        for (int t = 0; t < 20; ++t) {
            Chain c;
            c.axes = axes;
            for (int a = 0; a < axes; ++a) c.start[a] = static_cast<std::int64_t>(rng() % 2001) - 1000;
            const std::size_t n = rng() % 3000;
            for (std::size_t i = 0; i < n; ++i) c.steps.push_back(static_cast<Step>(rng() & 0xFFFu));
            Point expect = c.start;
            for (const Step s : c.steps) apply_step(expect, s, axes);
            EXPECT_EQ(c.end(), expect) << axes << " axes, " << n << " steps";
            const std::vector<Point> pts = chain_points(c);
            EXPECT_EQ(pts.back(), expect);
        }
    }
}

TEST(Chain, FreemanRejectsBadDigit) {
    auto c = from_freeman(0, 0, "0128");
    ASSERT_FALSE(c);
    EXPECT_EQ(c.error().code, Errc::syntax);
    EXPECT_NE(c.error().message.find("character 4"), std::string::npos);
}

}  // namespace
}  // namespace stepzip
