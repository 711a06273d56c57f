// Every linear interpolator ends exactly on its end point, for every |dx|,
// |dy| <= 200 and every phase of its stated range; outside the range it does
// not (the range is tight). The evaluation function stays in its bounds.
#include <gtest/gtest.h>

#include <cstdlib>
#include <random>
#include <vector>

#include "stepzip/chain.hpp"
#include "stepzip/interpolate/linear.hpp"
#include "stepzip/profile.hpp"

namespace stepzip {
namespace {

constexpr int kMax = 200;

Point end_of(const std::vector<Step>& steps, int axes) {
    Point p{};
    for (Step s : steps) apply_step(p, s, axes);
    return p;
}

TEST(EvalLinear, ExactWithoutForcingOnlyInsidePhaseRange) {
    std::vector<Step> steps;
    std::vector<std::int64_t> trace;
    for (int a = 0; a <= kMax; ++a)
        for (int b = 0; b <= kMax; ++b) {
            if (a + b == 0) continue;
            const int step = (a + b > 60) ? 7 : 1;  // all phases for small, a sample for large
            for (std::int64_t f0 = -b - 2; f0 < a + 2; f0 += (f0 >= -b && f0 < a - 1) ? step : 1) {
                steps.clear();
                trace.clear();
                std::int64_t forced = 0;
                eval_linear(a, b, f0, steps, &trace, &forced);
                const bool in_range = -b <= f0 && f0 < a;
                ASSERT_EQ(steps.size(), static_cast<std::size_t>(a + b));
                const Point e = end_of(steps, 2);
                ASSERT_EQ(e[0], a);
                ASSERT_EQ(e[1], b);
                if (in_range) {
                    ASSERT_EQ(forced, 0) << a << "," << b << " f0=" << f0;
                    for (std::int64_t f : trace) {
                        ASSERT_GE(f, -b);
                        ASSERT_LT(f, a);
                    }
                } else if (a > 0 && b > 0) {
                    ASSERT_GT(forced, 0) << a << "," << b << " f0=" << f0;
                }
            }
        }
}

TEST(EvalLinear, AllQuadrantsMirrorTheFirst) {
    for (int dx = -30; dx <= 30; ++dx)
        for (int dy = -30; dy <= 30; ++dy) {
            if (dx == 0 && dy == 0) continue;
            std::vector<Step> q1, q;
            eval_linear(std::abs(dx), std::abs(dy), 0, q1);
            eval_linear(dx, dy, 0, q);
            ASSERT_EQ(q1.size(), q.size());
            for (std::size_t i = 0; i < q.size(); ++i) {
                ASSERT_EQ(std::abs(step_axis(q[i], 0)), step_axis(q1[i], 0));
                ASSERT_EQ(std::abs(step_axis(q[i], 1)), step_axis(q1[i], 1));
            }
            const Point e = end_of(q, 2);
            ASSERT_EQ(e[0], dx);
            ASSERT_EQ(e[1], dy);
        }
}

TEST(AcceleratedLinear, ExactExactlyInsidePhaseRange) {
    std::vector<Step> steps;
    std::vector<std::int64_t> trace;
    for (int dx = -kMax; dx <= kMax; dx += (std::abs(dx) < 40 ? 1 : 3))
        for (int dy = -kMax; dy <= kMax; dy += (std::abs(dy) < 40 ? 1 : 3)) {
            if (dx == 0 && dy == 0) continue;
            const std::int64_t l = std::max(std::abs(dx), std::abs(dy));
            const std::int64_t s = std::min(std::abs(dx), std::abs(dy));
            const bool degenerate = s == 0 || s == l;
            const std::int64_t stride = l > 50 ? 5 : 1;
            for (std::int64_t f0 = -s - 2; f0 < l - s + 2; f0 += (f0 >= -s && f0 < l - s - 1) ? stride : 1) {
                steps.clear();
                trace.clear();
                accelerated_linear(dx, dy, f0, steps, &trace);
                ASSERT_EQ(steps.size(), static_cast<std::size_t>(l));
                const Point e = end_of(steps, 2);
                const bool exact = e[0] == dx && e[1] == dy;
                const bool in_range = -s <= f0 && f0 < l - s;
                if (degenerate || in_range) {
                    ASSERT_TRUE(exact) << dx << "," << dy << " f0=" << f0;
                } else {
                    ASSERT_FALSE(exact) << dx << "," << dy << " f0=" << f0;
                }
                if (in_range && !degenerate)
                    for (std::int64_t f : trace) {
                        ASSERT_GE(f, -s);
                        ASSERT_LT(f, l - s);
                    }
                for (Step st : steps) ASSERT_TRUE(step_valid(st, 2));
            }
        }
}

// Every point of a linear interpolation lies within one step of the ideal line.
TEST(LinearInterpolators, PointsWithinOneStepOfIdealLine) {
    for (int dx = -60; dx <= 60; ++dx)
        for (int dy = -60; dy <= 60; ++dy) {
            if (dx == 0 && dy == 0) continue;
            for (int which = 0; which < 3; ++which) {
                std::vector<Step> steps;
                if (which == 0) eval_linear(dx, dy, 0, steps);
                if (which == 1) accelerated_linear(dx, dy, 0, steps);
                if (which == 2) patent_forward(dx, dy, std::abs(dy) - std::abs(dx), steps);
                Point p{};
                const double norm = std::sqrt(double(dx) * dx + double(dy) * dy);
                for (Step s : steps) {
                    apply_step(p, s, 2);
                    // distance of p from the line through 0 and (dx, dy)
                    const double dist = std::abs(double(dx) * p[1] - double(dy) * p[0]) / norm;
                    ASSERT_LE(dist, 1.0) << "interpolator " << which << " " << dx << "," << dy;
                }
            }
        }
}

TEST(AcceleratedLinear, ProductDecisionsForDegenerateLines) {
    std::vector<Step> s;
    accelerated_linear(5, 5, 0, s);
    for (Step st : s) EXPECT_EQ(st, make_step2(1, 1));
    s.clear();
    accelerated_linear(0, -4, 0, s);
    for (Step st : s) EXPECT_EQ(st, make_step2(0, -1));
    EXPECT_EQ(s.size(), 4u);
}

TEST(MultiAxisLinear, RandomVectorsEndExactly) {
    std::mt19937_64 rng(12345);
    for (int iter = 0; iter < 20000; ++iter) {
        const int axes = 3 + static_cast<int>(rng() % 4);
        Point delta{};
        bool any = false;
        for (int i = 0; i < axes; ++i) {
            delta[i] = static_cast<std::int64_t>(rng() % 401) - 200;
            any = any || delta[i] != 0;
        }
        if (!any) continue;
        const int lead = leading_axis(delta, axes);
        const std::int64_t l = std::llabs(delta[lead]);
        std::int64_t phases[kMaxAxes] = {};
        int j = 0;
        for (int i = 0; i < axes; ++i) {
            if (i == lead) continue;
            const std::int64_t s = std::llabs(delta[i]);
            // a random phase in [-S, L - S) (any value when degenerate)
            phases[j++] = (s == 0 || s == l) ? 0 : -s + static_cast<std::int64_t>(rng() % (l));
        }
        for (auto variant : {MultiAxisVariant::standard, MultiAxisVariant::first_step_all_axes}) {
            std::vector<Step> steps;
            multiaxis_linear(delta, axes, phases, steps, variant);
            ASSERT_EQ(steps.size(), static_cast<std::size_t>(l));
            const Point e = end_of(steps, axes);
            for (int i = 0; i < axes; ++i) ASSERT_EQ(e[i], delta[i]) << "iter " << iter;
            for (Step s : steps) ASSERT_EQ(step_axis(s, lead), delta[lead] > 0 ? 1 : -1);
            if (variant == MultiAxisVariant::first_step_all_axes)
                for (int i = 0; i < axes; ++i)
                    ASSERT_EQ(step_axis(steps[0], i), (delta[i] > 0) - (delta[i] < 0));
        }
    }
}

TEST(MultiAxisLinear, TwoAxesMatchAccelerated) {
    for (int dx = -40; dx <= 40; ++dx)
        for (int dy = -40; dy <= 40; ++dy) {
            if (dx == 0 && dy == 0) continue;
            Point delta{};
            delta[0] = dx;
            delta[1] = dy;
            const std::int64_t s = std::min(std::abs(dx), std::abs(dy));
            const std::int64_t l = std::max(std::abs(dx), std::abs(dy));
            for (std::int64_t f0 = -s; f0 < std::max<std::int64_t>(l - s, -s + 1); ++f0) {
                std::vector<Step> a, b;
                multiaxis_linear(delta, 2, &f0, a);
                accelerated_linear(dx, dy, f0, b);
                ASSERT_EQ(a, b);
            }
        }
}

TEST(MultiAxisLinear, FirstStepVariantIsNotAPhaseOfStandard) {
    // For (4, 2) and (6, 4) no phase of the standard rule gives the variant's
    // pattern (for coprime totals such as (5, 2) one does).
    for (auto [l, s] : {std::pair{4, 2}, std::pair{6, 4}}) {
        Point delta{};
        delta[0] = l;
        delta[1] = s;
        std::vector<Step> variant;
        multiaxis_linear(delta, 2, nullptr, variant, MultiAxisVariant::first_step_all_axes);
        bool found = false;
        for (std::int64_t f0 = -s; f0 < l - s; ++f0) {
            std::vector<Step> st;
            accelerated_linear(l, s, f0, st);
            found = found || st == variant;
        }
        EXPECT_FALSE(found) << l << "," << s;
    }
}

}  // namespace
}  // namespace stepzip
