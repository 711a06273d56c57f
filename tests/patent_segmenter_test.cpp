// SU 1089551 approximation mode (seed 001, Fig. 5) and the patent segmenter.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <random>
#include <string_view>
#include <vector>

#include "stepzip/chain.hpp"
#include "stepzip/interpolate/linear.hpp"
#include "stepzip/profile.hpp"
#include "stepzip/segmenter.hpp"

namespace stepzip {
namespace {

std::vector<Step> freeman(std::string_view codes) {
    auto c = from_freeman(0, 0, codes);
    EXPECT_TRUE(c.ok());
    return c.value().steps;
}

Point pt(std::int64_t x, std::int64_t y) {
    Point p{};
    p[0] = x;
    p[1] = y;
    return p;
}

// SPEC §2.3: input X Y X X Y X X Y X X X; the 11th step violates and (8, 3)
// is read out.
TEST(PatentApproximate, Fig5GoldenVector) {
    std::vector<Point> ends;
    std::vector<std::int64_t> trace;
    ASSERT_TRUE(patent_approximate(freeman("02002002000"), ends, &trace).ok());
    EXPECT_EQ(trace, (std::vector<std::int64_t>{0, -1, 0, 1, -2, 0, 2, -3, 0, 3, 6}));
    ASSERT_EQ(ends.size(), 1u);
    EXPECT_EQ(ends[0], pt(8, 3));
}

TEST(PatentApproximate, Fig5MirroredIntoEveryQuadrant) {
    const char* codes[] = {"02002002000", "42442442444", "46446446444", "06006006000"};
    const Point want[] = {pt(8, 3), pt(-8, 3), pt(-8, -3), pt(8, -3)};
    for (int q = 0; q < 4; ++q) {
        std::vector<Point> ends;
        std::vector<std::int64_t> trace;
        ASSERT_TRUE(patent_approximate(freeman(codes[q]), ends, &trace).ok());
        EXPECT_EQ(trace, (std::vector<std::int64_t>{0, -1, 0, 1, -2, 0, 2, -3, 0, 3, 6}));
        ASSERT_EQ(ends.size(), 1u);
        EXPECT_EQ(ends[0], want[q]);
    }
}

// After a violation everything resets: the next steps start a new segment.
// At the end of the message the counters are read out as they stand.
TEST(PatentApproximate, ResetAfterViolationAndEndOfMessage) {
    std::vector<Point> ends;
    std::vector<std::int64_t> trace;
    ASSERT_TRUE(patent_approximate(freeman("0200200200022"), ends, &trace).ok());
    ASSERT_EQ(ends.size(), 2u);
    EXPECT_EQ(ends[0], pt(8, 3));
    EXPECT_EQ(ends[1], pt(0, 2));
    EXPECT_EQ(trace.size(), 13u);
    EXPECT_EQ(trace[11], 0);  // y-step from a fresh adder: F -= X = 0
}

// SPEC §2.3: the modes are not inverses. Forward (7, 3) is read back as one
// segment (7, 3); forward (3, 3) = YXXYYX is split in two.
TEST(PatentApproximate, ModesAreNotInverses) {
    std::vector<Step> fwd;
    patent_forward(7, 3, 3 - 7, fwd);
    EXPECT_EQ(fwd, freeman("0020020020"));
    std::vector<Point> ends;
    ASSERT_TRUE(patent_approximate(fwd, ends).ok());
    EXPECT_EQ(ends, (std::vector<Point>{pt(7, 3)}));

    fwd.clear();
    patent_forward(3, 3, 0, fwd);
    EXPECT_EQ(fwd, freeman("200220"));
    ends.clear();
    ASSERT_TRUE(patent_approximate(fwd, ends).ok());
    EXPECT_EQ(ends, (std::vector<Point>{pt(2, 1), pt(1, 2)}));
}

TEST(PatentApproximate, SignChangeStartsANewSegment) {
    std::vector<Point> ends;
    ASSERT_TRUE(patent_approximate(freeman("0044"), ends).ok());
    EXPECT_EQ(ends, (std::vector<Point>{pt(2, 0), pt(-2, 0)}));
}

TEST(PatentApproximate, RefusesDiagonalsAndMoreAxes) {
    std::vector<Point> ends;
    auto r = patent_approximate(freeman("01"), ends);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, Errc::connectivity);
    EXPECT_NE(r.error().message.find("step 2"), std::string::npos);
    const int d[3] = {0, 0, 1};
    const std::vector<Step> z = {make_step(d, 3)};
    r = patent_approximate(z, ends);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, Errc::invalid_argument);
}

// Chebyshev deviation, tick by tick, of the forward path of `delta` at the
// profile's default phase from `piece` (the shorter path waits at its end).
std::int64_t deviation(Profile p, const Point& delta, const std::vector<Step>& piece) {
    std::vector<Step> fwd;
    expand_segment(p, default_segment(p, delta, 2), 2, fwd);
    Point a{}, b{};
    std::int64_t dev = 0;
    for (std::size_t t = 0; t < std::max(fwd.size(), piece.size()); ++t) {
        if (t < piece.size()) apply_step(a, piece[t], 2);
        if (t < fwd.size()) apply_step(b, fwd[t], 2);
        dev = std::max<std::int64_t>({dev, std::llabs(a[0] - b[0]), std::llabs(a[1] - b[1])});
    }
    return dev;
}

TEST(PatentSegmenter, Fig5ChainIsMadeExactAndReported) {
    const auto steps = freeman("02002002000");
    for (Profile p : kAllProfiles) {
        std::vector<Segment> segs;
        SegmentStats stats;
        ASSERT_TRUE(segment_steps(steps, 2, p, SegmenterKind::patent, segs, &stats).ok());
        std::vector<Step> back;
        for (const Segment& s : segs) {
            ASSERT_TRUE(check_segment(p, s, 2).ok());
            expand_segment(p, s, 2, back);
        }
        EXPECT_EQ(back, steps) << profile_name(p);
        EXPECT_EQ(stats.patent_segments, 1u);
        EXPECT_EQ(stats.patent_exact, 0u) << profile_name(p);  // (8, 3) is not this word
        EXPECT_EQ(stats.patent_max_deviation, deviation(p, pt(8, 3), steps)) << profile_name(p);
        EXPECT_GE(stats.patent_max_deviation, 1);
        EXPECT_GT(segs.size(), 1u);  // runs of 1, 2, 2, 3 x-steps: not one digital line
    }
}

TEST(PatentSegmenter, ForwardPatentLinesAreExactAsReadOut) {
    // Every patent forward line up to 12 x 12 that the mode reads back whole.
    for (int x = 0; x <= 12; ++x)
        for (int y = 0; y <= 12; ++y) {
            if (x == 0 && y == 0) continue;
            std::vector<Step> fwd;
            patent_forward(x, y, y - x, fwd);
            std::vector<Point> ends;
            ASSERT_TRUE(patent_approximate(fwd, ends).ok());
            std::vector<Segment> segs;
            SegmentStats stats;
            ASSERT_TRUE(
                segment_steps(fwd, 2, Profile::patent, SegmenterKind::patent, segs, &stats).ok());
            EXPECT_EQ(stats.patent_segments, ends.size());
            if (ends.size() == 1) {
                EXPECT_EQ(stats.patent_exact, 1u) << x << " " << y;
                EXPECT_EQ(stats.patent_max_deviation, 0);
                ASSERT_EQ(segs.size(), 1u);
                EXPECT_EQ(segs[0], default_segment(Profile::patent, pt(x, y), 2));
            }
        }
}

TEST(PatentSegmenter, StatsAddUpOverRandomChains) {
    std::mt19937_64 rng(9);
    for (int rep = 0; rep < 50; ++rep) {
        std::vector<Step> steps;
        std::uniform_int_distribution<int> code(0, 3);
        const int base = code(rng);
        for (int k = 0; k < 300; ++k)
            steps.push_back(freeman_to_step(2 * ((base + (code(rng) < 3 ? 0 : 1)) % 4)));
        std::vector<Point> ends;
        ASSERT_TRUE(patent_approximate(steps, ends).ok());
        std::vector<Segment> segs;
        SegmentStats stats;
        ASSERT_TRUE(segment_steps(steps, 2, Profile::eval4, SegmenterKind::patent, segs, &stats).ok());
        EXPECT_EQ(stats.patent_segments, ends.size());
        EXPECT_LE(stats.patent_exact, stats.patent_segments);
        std::int64_t dev = 0;
        std::uint64_t exact = 0;
        std::size_t pos = 0;
        for (const Point& e : ends) {
            const auto len = static_cast<std::size_t>(std::llabs(e[0]) + std::llabs(e[1]));
            const std::vector<Step> piece(steps.begin() + pos, steps.begin() + pos + len);
            std::vector<Step> fwd;
            expand_segment(Profile::eval4, default_segment(Profile::eval4, e, 2), 2, fwd);
            exact += fwd == piece;
            dev = std::max(dev, deviation(Profile::eval4, e, piece));
            pos += len;
        }
        EXPECT_EQ(pos, steps.size());
        EXPECT_EQ(stats.patent_exact, exact);
        EXPECT_EQ(stats.patent_max_deviation, dev);
        // the segments never cross a read-out end point
        EXPECT_GE(segs.size(), ends.size());
    }
}

}  // namespace
}  // namespace stepzip
