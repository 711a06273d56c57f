// Streaming reverse interpolation (streaming.hpp): the held-back count never
// exceeds the bound, the emitted segments expand to exactly the pushed steps,
// and without a forced cut the segments are those of the batch greedy cut.
// Random chains with fixed seeds, every profile.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "stepzip/profile.hpp"
#include "stepzip/segmenter.hpp"
#include "stepzip/streaming.hpp"

namespace stepzip {
namespace {

// Digital lines drawn with random phases (long segments) mixed with random
// walk stretches (short ones); `four`: 4-connected steps only.
std::vector<Step> random_chain(std::mt19937_64& rng, int axes, bool four, std::size_t n,
                               int max_total = 40) {
    std::vector<Step> steps;
    std::uniform_int_distribution<int> coin(0, 2), dir(-1, 1), len(1, 15);
    while (steps.size() < n) {
        if (coin(rng) == 0) {
            for (int k = len(rng); k > 0; --k) {
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
            std::uniform_int_distribution<int> t(-max_total, max_total);
            for (int i = 0; i < axes; ++i) delta[i] = t(rng);
            if (delta[0] == 0) delta[0] = 1;
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

struct Case {
    Profile profile;
    int axes;
};

const Case kCases[] = {{Profile::eval4, 2}, {Profile::patent, 2}, {Profile::eval8, 2},
                       {Profile::eval8, 3}, {Profile::grbl, 2},   {Profile::grbl, 4},
                       {Profile::marlin, 2}, {Profile::marlin, 6}};

std::vector<Step> expand_all(Profile p, const std::vector<Segment>& segs, int axes) {
    std::vector<Step> out;
    for (const Segment& s : segs) {
        EXPECT_TRUE(check_segment(p, s, axes).ok());
        expand_segment(p, s, axes, out);
    }
    return out;
}

// Pushes `steps` one at a time; checks the bound and the accounting after
// every push; returns the segments after finish().
std::vector<Segment> stream(StreamingSegmenter& seg, const std::vector<Step>& steps) {
    std::vector<Segment> out;
    std::vector<Step> emitted;
    for (std::size_t i = 0; i < steps.size(); ++i) {
        const std::size_t before = out.size();
        auto r = seg.push(steps[i], out);
        EXPECT_TRUE(r.ok()) << r.error().message;
        EXPECT_LE(seg.held(), seg.max_held()) << "after step " << i + 1;
        for (std::size_t k = before; k < out.size(); ++k)
            expand_segment(seg.profile(), out[k], seg.axes(), emitted);
        // what is out plus what is held is exactly what was pushed
        EXPECT_EQ(emitted.size() + seg.held(), i + 1);
        EXPECT_TRUE(std::equal(emitted.begin(), emitted.end(), steps.begin()));
    }
    seg.finish(out);
    EXPECT_EQ(seg.held(), 0u);
    return out;
}

TEST(StreamingSegmenter, SameSegmentsAsBatchGreedyWhenNoBoundIsHit) {
    std::mt19937_64 rng(20240611);
    for (const Case& c : kCases) {
        const bool four = !profile_eight_connected(c.profile);
        for (int trial = 0; trial < 12; ++trial) {
            const auto steps = random_chain(rng, c.axes, four, 400 + 50 * trial);
            std::vector<Segment> batch;
            ASSERT_TRUE(segment_steps(steps, c.axes, c.profile, SegmenterKind::greedy, batch).ok());
            StreamingSegmenter seg(c.profile, c.axes);
            std::vector<Segment> out;
            for (Step s : steps) ASSERT_TRUE(seg.push(s, out).ok());
            EXPECT_EQ(seg.forced_cuts(), 0u);
            seg.finish(out);
            EXPECT_EQ(out, batch) << profile_name(c.profile) << " axes " << c.axes
                                  << " trial " << trial;
        }
    }
}

TEST(StreamingSegmenter, HeldStepsNeverExceedTheBoundAndOutputIsExact) {
    std::mt19937_64 rng(77);
    for (const Case& c : kCases) {
        const bool four = !profile_eight_connected(c.profile);
        for (std::size_t bound : {1u, 2u, 3u, 7u, 31u, 200u}) {
            const auto steps = random_chain(rng, c.axes, four, 600, 120);
            StreamingSegmenter seg(c.profile, c.axes, bound);
            ASSERT_TRUE(seg.valid());
            const auto out = stream(seg, steps);
            EXPECT_EQ(expand_all(c.profile, out, c.axes), steps)
                << profile_name(c.profile) << " bound " << bound;
        }
    }
}

TEST(StreamingSegmenter, ABoundOfOneGivesOneSegmentPerStepAtMost) {
    std::mt19937_64 rng(5);
    const auto steps = random_chain(rng, 2, false, 300);
    StreamingSegmenter seg(Profile::eval8, 2, 1);
    const auto out = stream(seg, steps);
    EXPECT_LE(out.size(), steps.size());
    EXPECT_EQ(expand_all(Profile::eval8, out, 2), steps);
}

TEST(StreamingSegmenter, LongLineIsForcedOutAtTheBoundAndStaysExact) {
    // One digital line of 5000 steps is one batch segment; with a bound of
    // 1000 it comes out in pieces of at most 1001 steps, as soon as the
    // bound is passed.
    std::vector<Step> steps;
    Segment line = default_segment(Profile::eval8, Point{5000, 1733}, 2);
    expand_segment(Profile::eval8, line, 2, steps);
    StreamingSegmenter seg(Profile::eval8, 2, 1000);
    std::vector<Segment> out;
    for (std::size_t i = 0; i < steps.size(); ++i) {
        ASSERT_TRUE(seg.push(steps[i], out).ok());
        if (i + 1 <= 1000) EXPECT_TRUE(out.empty());
        ASSERT_LE(seg.held(), 1000u);
    }
    EXPECT_GE(seg.forced_cuts(), 4u);
    seg.finish(out);
    EXPECT_EQ(expand_all(Profile::eval8, out, 2), steps);
    for (const Segment& s : out) EXPECT_LE(segment_length(s.delta, 2, true), 1001);
    // Unbounded (default bound), the line is one segment at its default phase.
    StreamingSegmenter whole(Profile::eval8, 2);
    std::vector<Segment> one;
    ASSERT_TRUE(whole.push(std::span<const Step>(steps), one).ok());
    EXPECT_TRUE(one.empty());
    whole.finish(one);
    ASSERT_EQ(one.size(), 1u);
    EXPECT_EQ(one[0], line);
}

TEST(StreamingSegmenter, SegmentIsEmittedByTheStepThatBreaksIt) {
    // eval8: four +x steps then a -y step; the leading axis x must move on
    // every tick, so the fifth step ends the run (4, 0) at once.
    StreamingSegmenter seg(Profile::eval8, 2);
    std::vector<Segment> out;
    for (int i = 0; i < 4; ++i) {
        ASSERT_TRUE(seg.push(freeman_to_step(0), out).ok());
        EXPECT_TRUE(out.empty());
        EXPECT_EQ(seg.held(), static_cast<std::size_t>(i + 1));
    }
    ASSERT_TRUE(seg.push(freeman_to_step(6), out).ok());
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].delta, (Point{4, 0}));
    EXPECT_EQ(seg.held(), 1u);

    // eval4: x x x x y is one digital line (4, 1); a -x step right after
    // changes the sign of x, so push 6 emits (4, 1).
    StreamingSegmenter s4(Profile::eval4, 2);
    std::vector<Segment> o4;
    const int codes[] = {0, 0, 0, 0, 2};
    for (int c : codes) ASSERT_TRUE(s4.push(freeman_to_step(c), o4).ok());
    EXPECT_TRUE(o4.empty());
    ASSERT_TRUE(s4.push(freeman_to_step(4), o4).ok());
    ASSERT_EQ(o4.size(), 1u);
    EXPECT_EQ(o4[0].delta, (Point{4, 1}));
    EXPECT_EQ(s4.held(), 1u);
}

TEST(StreamingSegmenter, SpansAndSingleStepsGiveTheSameSegments) {
    std::mt19937_64 rng(99);
    const auto steps = random_chain(rng, 2, false, 1000);
    StreamingSegmenter a(Profile::grbl, 2, 64), b(Profile::grbl, 2, 64);
    std::vector<Segment> oa, ob;
    for (Step s : steps) ASSERT_TRUE(a.push(s, oa).ok());
    for (std::size_t i = 0; i < steps.size(); i += 37) {
        const std::size_t n = std::min<std::size_t>(37, steps.size() - i);
        ASSERT_TRUE(b.push(std::span<const Step>(steps).subspan(i, n), ob).ok());
    }
    a.finish(oa);
    b.finish(ob);
    EXPECT_EQ(oa, ob);
}

TEST(StreamingSegmenter, FinishResetsForTheNextChain) {
    std::mt19937_64 rng(3);
    const auto first = random_chain(rng, 2, true, 200);
    const auto second = random_chain(rng, 2, true, 300);
    StreamingSegmenter seg(Profile::eval4, 2);
    std::vector<Segment> o1, o2, fresh;
    ASSERT_TRUE(seg.push(std::span<const Step>(first), o1).ok());
    seg.finish(o1);
    EXPECT_EQ(seg.pushed(), 0u);
    ASSERT_TRUE(seg.push(std::span<const Step>(second), o2).ok());
    seg.finish(o2);
    ASSERT_TRUE(segment_steps(second, 2, Profile::eval4, SegmenterKind::greedy, fresh).ok());
    EXPECT_EQ(o2, fresh);
    std::vector<Segment> none;
    seg.finish(none);
    EXPECT_TRUE(none.empty());
}

TEST(StreamingSegmenter, RejectedStepsLeaveTheStateUnchanged) {
    StreamingSegmenter seg(Profile::eval4, 2);
    std::vector<Segment> out;
    ASSERT_TRUE(seg.push(freeman_to_step(0), out).ok());
    auto diag = seg.push(freeman_to_step(1), out);
    ASSERT_FALSE(diag.ok());
    EXPECT_EQ(diag.error().code, Errc::connectivity);
    EXPECT_NE(diag.error().message.find("step 2"), std::string::npos);
    auto bad = seg.push(Step{0}, out);
    ASSERT_FALSE(bad.ok());
    EXPECT_EQ(bad.error().code, Errc::invalid_argument);
    auto third_axis = seg.push(Step{0x10}, out);
    EXPECT_EQ(third_axis.error().code, Errc::invalid_argument);
    EXPECT_EQ(seg.held(), 1u);
    EXPECT_EQ(seg.pushed(), 1u);

    StreamingSegmenter unusable(Profile::eval4, 3);
    EXPECT_FALSE(unusable.valid());
    EXPECT_EQ(unusable.push(freeman_to_step(0), out).error().code, Errc::invalid_argument);
    StreamingSegmenter zero(Profile::eval8, 2, 0);
    EXPECT_FALSE(zero.valid());
}

}  // namespace
}  // namespace stepzip
