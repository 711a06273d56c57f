// Reverse interpolation round trip (SPEC §4): for every profile and
// segmenter, expanding the segments reproduces the steps exactly and every
// segment passes check_segment(). Random chains with fixed seeds.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "stepzip/profile.hpp"
#include "stepzip/segmenter.hpp"

namespace stepzip {
namespace {

constexpr SegmenterKind kKinds[] = {SegmenterKind::greedy, SegmenterKind::optimal,
                                    SegmenterKind::patent};

// A chain of `n` steps: random-slope pieces (digital lines drawn with random
// phases) mixed with random-walk stretches, so both long and short segments occur.
std::vector<Step> random_chain(std::mt19937_64& rng, int axes, bool four, std::size_t n) {
    std::vector<Step> steps;
    std::uniform_int_distribution<int> coin(0, 2), dir(-1, 1), len(1, 60);
    while (steps.size() < n) {
        if (coin(rng) == 0) {
            for (int k = len(rng) / 4; k >= 0; --k) {
                int d[kMaxAxes] = {};
                if (four) {
                    d[std::uniform_int_distribution<int>(0, axes - 1)(rng)] = coin(rng) ? 1 : -1;
                } else {
                    do {
                        for (int i = 0; i < axes; ++i) d[i] = dir(rng);
                    } while (!step_valid(make_step(d, axes), axes));
                }
                steps.push_back(make_step(d, axes));
            }
        } else {
            Point delta{};
            for (int i = 0; i < axes; ++i) delta[i] = std::uniform_int_distribution<int>(-40, 40)(rng);
            if (four) delta[std::uniform_int_distribution<int>(0, 1)(rng)] += 1;
            else delta[0] = delta[0] == 0 ? 1 : delta[0];
            const Profile p = four ? Profile::eval4 : Profile::eval8;
            Segment seg = default_segment(p, delta, axes);
            for (int j = 0; j < phase_count(p, axes); ++j) {
                const auto ab = *phase_arguments(p, seg, axes, j);
                const PhaseRange r = phase_range(p, ab.first, ab.second);
                seg.phase[j] = std::uniform_int_distribution<std::int64_t>(r.lo, r.hi - 1)(rng);
            }
            expand_segment(p, seg, axes, steps);
        }
    }
    steps.resize(n);
    return steps;
}

void expect_round_trip(Profile p, SegmenterKind k, const std::vector<Step>& steps, int axes) {
    std::vector<Segment> segs;
    SegmentStats stats;
    auto r = segment_steps(steps, axes, p, k, segs, &stats);
    ASSERT_TRUE(r.ok()) << r.error().message;
    std::vector<Step> back;
    for (const Segment& s : segs) {
        ASSERT_TRUE(check_segment(p, s, axes).ok());
        expand_segment(p, s, axes, back);
    }
    ASSERT_EQ(back, steps) << profile_name(p) << " " << segmenter_name(k) << " axes " << axes;
    if (k == SegmenterKind::patent) EXPECT_LE(stats.patent_exact, stats.patent_segments);
}

TEST(SegmenterRoundTrip, FourConnectedTwoAxes) {
    std::mt19937_64 rng(11);
    for (int rep = 0; rep < 40; ++rep) {
        const auto steps = random_chain(rng, 2, true, 400);
        for (Profile p : kAllProfiles)
            for (SegmenterKind k : kKinds) expect_round_trip(p, k, steps, 2);
    }
}

TEST(SegmenterRoundTrip, EightConnectedTwoAxes) {
    std::mt19937_64 rng(12);
    for (int rep = 0; rep < 40; ++rep) {
        const auto steps = random_chain(rng, 2, false, 400);
        for (Profile p : {Profile::eval8, Profile::grbl, Profile::marlin})
            for (SegmenterKind k : {SegmenterKind::greedy, SegmenterKind::optimal})
                expect_round_trip(p, k, steps, 2);
    }
}

TEST(SegmenterRoundTrip, ThreeToSixAxes) {
    std::mt19937_64 rng(13);
    for (int axes = 3; axes <= 6; ++axes)
        for (int rep = 0; rep < 15; ++rep) {
            const auto steps = random_chain(rng, axes, rep % 3 == 0, 300);
            for (Profile p : {Profile::eval8, Profile::grbl, Profile::marlin})
                for (SegmenterKind k : {SegmenterKind::greedy, SegmenterKind::optimal})
                    expect_round_trip(p, k, steps, axes);
        }
}

TEST(SegmenterRoundTrip, PatentSegmenterRefusesDiagonalSteps) {
    std::vector<Step> steps = {make_step2(1, 0), make_step2(1, 1)};
    std::vector<Segment> segs;
    auto r = segment_steps(steps, 2, Profile::eval8, SegmenterKind::patent, segs);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, Errc::unsupported);
}

TEST(SegmenterRoundTrip, ConnectivityErrorNamesTheStep) {
    std::vector<Step> steps = {make_step2(1, 0), make_step2(0, 1), make_step2(1, 1)};
    std::vector<Segment> segs;
    auto r = segment_steps(steps, 2, Profile::eval4, SegmenterKind::greedy, segs);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, Errc::connectivity);
    EXPECT_NE(r.error().message.find("step 3"), std::string::npos);
}

TEST(SegmenterRoundTrip, EmptyInputGivesNoSegments) {
    std::vector<Segment> segs;
    for (Profile p : kAllProfiles)
        for (SegmenterKind k : kKinds)
            ASSERT_TRUE(segment_steps({}, 2, p, k, segs).ok());
    EXPECT_TRUE(segs.empty());
}

}  // namespace
}  // namespace stepzip
