// Rates and accelerations read out of timed logs whose planner settings are
// known (corpora/timed/, made by corpora/tools/timed_stream.py; settings in
// corpora/README.md).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "stepzip/document.hpp"
#include "stepzip/timed.hpp"

namespace stepzip {
namespace {

Chain timed_chain(const char* name) {
    std::ifstream f(std::string(STEPZIP_SOURCE_DIR) + "/corpora/timed/" + name, std::ios::binary);
    std::ostringstream s;
    s << f.rdbuf();
    auto chains = read_chains(InputFormat::timed, s.str());
    EXPECT_TRUE(chains.ok());
    EXPECT_EQ(chains->size(), 1u);
    return chains->front();
}

// Tolerances: rates within 2 %, accelerations within 10 % of the setting.
void expect_near_rel(double got, double want, double tol, const std::string& what) {
    EXPECT_NEAR(got, want, tol * want) << what;
}

TEST(TimedMotion, TwoAxisStreamGivesItsPlannerSettings) {
    // 80 steps/mm, 6000 mm/min, 500 mm/s^2, 30 us ticks.
    const auto m = estimate_axis_motion(timed_chain("trapezoid-2axis.steps"), 30e-6);
    ASSERT_EQ(m.size(), 3u);
    for (int a = 1; a <= 2; ++a) {
        EXPECT_GT(m[a].windows, 100u);
        expect_near_rel(m[a].max_rate, 6000.0 / 60 * 80, 0.02, "rate axis " + std::to_string(a));
        expect_near_rel(m[a].acceleration, 500.0 * 80, 0.10, "acceleration axis " + std::to_string(a));
    }
}

TEST(TimedMotion, ThreeAxisStreamGivesItsPlannerSettings) {
    // X, Y: 160 steps/mm, 4000 mm/min, 300 mm/s^2; Z: 400 steps/mm, 100 mm/s^2
    // (its 2 mm lifts never reach the Z rate limit); 40 us ticks.
    const auto m = estimate_axis_motion(timed_chain("trapezoid-3axis.steps"), 40e-6);
    ASSERT_EQ(m.size(), 4u);
    for (int a = 1; a <= 2; ++a) {
        expect_near_rel(m[a].max_rate, 4000.0 / 60 * 160, 0.02, "rate axis " + std::to_string(a));
        expect_near_rel(m[a].acceleration, 300.0 * 160, 0.10, "acceleration axis " + std::to_string(a));
    }
    expect_near_rel(m[3].acceleration, 100.0 * 400, 0.10, "acceleration of Z");
    EXPECT_LT(m[3].max_rate, 1200.0 / 60 * 400);
}

TEST(TimedMotion, ConstantRateGivesNoAcceleration) {
    Chain c;
    c.axes = 3;
    for (int t = 0; t < 20000; ++t) c.steps.push_back(static_cast<Step>(1 | (t % 5 == 0 ? 0x4 : 0)));
    const auto m = estimate_axis_motion(c, 1e-5);
    ASSERT_EQ(m.size(), 3u);
    EXPECT_EQ(m[1].steps, 4000u);
    EXPECT_NEAR(m[1].max_rate, 20000.0, 1e-6);
    EXPECT_NEAR(m[1].acceleration, 0.0, 1.0);
    EXPECT_EQ(m[2].steps, 0u);
    EXPECT_EQ(m[2].windows, 0u);
}

}  // namespace
}  // namespace stepzip
