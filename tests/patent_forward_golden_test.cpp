// Patent SU 1089551, Fig. 4: forward mode of (7, 3), F after every step.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "stepzip/chain.hpp"
#include "stepzip/interpolate/linear.hpp"
#include "stepzip/interpolate/segment.hpp"
#include "stepzip/profile.hpp"

namespace stepzip {
namespace {

std::string letters(const std::vector<Step>& steps) {
    std::string s;
    for (Step st : steps) s += step_axis(st, 0) != 0 ? 'X' : 'Y';
    return s;
}

TEST(PatentForward, Fig4GoldenVector) {
    std::vector<Step> steps;
    std::vector<std::int64_t> trace;
    patent_forward(7, 3, 3 - 7, steps, &trace);
    EXPECT_EQ(letters(steps), "XXYXXYXXYX");
    EXPECT_EQ(trace, (std::vector<std::int64_t>{-1, 2, -3, -1, 1, -2, -1, 0, -1, -1}));
}

TEST(PatentForward, ProfileGivesFreemanOfSpecExample) {
    Chain chain;
    Point delta{};
    delta[0] = 7;
    delta[1] = 3;
    expand_segment(Profile::patent, default_segment(Profile::patent, delta, 2), 2, chain.steps);
    EXPECT_EQ(*to_freeman(chain), "0020020020");
}

TEST(PatentForward, ModesAreNotInverses) {
    // SPEC 2.3: forward of (3, 3) gives YXXYYX.
    std::vector<Step> steps;
    patent_forward(3, 3, 0, steps);
    EXPECT_EQ(letters(steps), "YXXYYX");
}

// With its own F00 = Y - X the forward mode never needs a counter to stop an
// axis, and ends exactly on its end point, in every quadrant.
TEST(PatentForward, DefaultPhaseEndsExactlyWithoutForcing) {
    for (int dx = -60; dx <= 60; ++dx)
        for (int dy = -60; dy <= 60; ++dy) {
            if (dx == 0 && dy == 0) continue;
            const std::int64_t a = std::abs(dx), b = std::abs(dy);
            std::int64_t x = a, y = b, f = b - a;
            std::vector<Step> steps;
            patent_forward(dx, dy, b - a, steps);
            for (Step s : steps) {
                const bool xstep = step_axis(s, 0) != 0;
                // the natural rule (F < 0 -> x) chose this step, no counter forced it
                ASSERT_EQ(xstep, f < 0) << dx << "," << dy;
                if (xstep) { --x; f += y; } else { --y; f -= x; }
                ASSERT_GE(x, 0);
                ASSERT_GE(y, 0);
            }
            Chain c;
            c.steps = steps;
            ASSERT_EQ(c.end()[0], dx);
            ASSERT_EQ(c.end()[1], dy);
            ASSERT_EQ(steps.size(), static_cast<std::size_t>(a + b));
        }
}

// Every pattern a phase can give is given by a phase inside phase_range().
TEST(PatentForward, PhaseRangeCoversEveryPattern) {
    for (std::int64_t a = 0; a <= 14; ++a)
        for (std::int64_t b = 0; b <= 14; ++b) {
            if (a + b == 0) continue;
            const PhaseRange r = phase_range(Profile::patent, a, b);
            std::vector<std::vector<Step>> inside;
            for (std::int64_t f = r.lo; f < r.hi; ++f) {
                std::vector<Step> s;
                patent_forward(a, b, f, s);
                inside.push_back(s);
            }
            const std::int64_t wide = 4 * (a * b + a + b + 2);
            for (std::int64_t f = -wide; f <= wide; ++f) {
                std::vector<Step> s;
                patent_forward(a, b, f, s);
                bool found = false;
                for (const auto& t : inside) found = found || t == s;
                ASSERT_TRUE(found) << a << "," << b << " f0=" << f;
            }
        }
}

}  // namespace
}  // namespace stepzip
