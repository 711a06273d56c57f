// Steps -> vectors -> steps is exact: segment_default_phase() cuts a chain
// into segments whose end points alone, redrawn by the profile's
// interpolator, give the chain back; for polylines each profile drew, and
// for plots stepped by Bresenham's algorithm at a phase that is no
// profile's own.
#include <gtest/gtest.h>

#include <cstdlib>
#include <random>
#include <vector>

#include "stepzip/vectors.hpp"

using namespace stepzip;

namespace {

struct Vertex {
    std::int64_t x, y;
};

std::vector<Vertex> random_polyline(std::mt19937& rng, int vertices, int reach) {
    std::uniform_int_distribution<int> d(-reach, reach);
    std::vector<Vertex> v{{d(rng), d(rng)}};
    while (static_cast<int>(v.size()) < vertices) {
        const Vertex n{v.back().x + d(rng), v.back().y + d(rng)};
        if (n.x != v.back().x || n.y != v.back().y) v.push_back(n);
    }
    return v;
}

Drawing as_drawing(const std::vector<Vertex>& v) {
    VectorPath path{v[0].x, v[0].y, {}};
    for (std::size_t i = 1; i < v.size(); ++i) {
        VectorMove m;
        m.x = v[i].x;
        m.y = v[i].y;
        path.moves.push_back(m);
    }
    return {path};
}

// Bresenham's line algorithm as textbooks write it (error term 2·dy - dx,
// step the minor axis when it is positive): neither GRBL's counter at L/2
// nor Marlin's, nor the evaluation function at 0. `four` inserts the major
// step before each minor one (a 4-connected staircase).
void bresenham(std::int64_t dx, std::int64_t dy, bool four, std::vector<Step>& out) {
    const std::int64_t ax = std::llabs(dx), ay = std::llabs(dy);
    const int sx = dx < 0 ? -1 : 1, sy = dy < 0 ? -1 : 1;
    const bool x_major = ax >= ay;
    const std::int64_t major = x_major ? ax : ay, minor = x_major ? ay : ax;
    std::int64_t e = 2 * minor - major;
    for (std::int64_t i = 0; i < major; ++i) {
        const bool both = e > 0;
        if (both) e -= 2 * major;
        e += 2 * minor;
        const int mx = x_major ? sx : 0, my = x_major ? 0 : sy;
        if (!both) {
            out.push_back(make_step2(mx, my));
        } else if (four) {
            out.push_back(make_step2(mx, my));
            out.push_back(make_step2(x_major ? 0 : sx, x_major ? sy : 0));
        } else {
            out.push_back(make_step2(sx, sy));
        }
    }
}

// Cuts `chain` for vectors under `p`, checks every segment is at the
// default phase, and redraws the end points.
void expect_exact_round_trip(const Chain& chain, Profile p) {
    SCOPED_TRACE(std::string(profile_name(p)));
    SegmentedChain sc;
    sc.chain = chain;
    ASSERT_TRUE(segment_default_phase(chain.steps, 2, p, sc.segments).ok());
    for (const Segment& s : sc.segments) EXPECT_EQ(s, default_segment(p, s.delta, 2));
    auto drawing = segments_to_drawing({sc});
    ASSERT_TRUE(drawing.ok());
    EXPECT_TRUE(check_redraw(*drawing, {chain}, p).ok());
    DrawingInterpolation how;
    how.profile = p;
    auto redrawn = interpolate_drawing(*drawing, how);
    ASSERT_TRUE(redrawn.ok());
    ASSERT_EQ(redrawn->size(), 1u);
    EXPECT_EQ((*redrawn)[0], chain);
}

}  // namespace

TEST(VectorsExact, TheIssueExampleUnderEveryProfile) {
    // G1 X7 Y3 / X20 Y5 / X30 Y30: the free-phase greedy cut ends its first
    // segment at (8, 3), which no interpolator redraws into these steps.
    const std::vector<Vertex> v{{0, 0}, {7, 3}, {20, 5}, {30, 30}};
    for (Profile p : kAllProfiles) {
        DrawingInterpolation how;
        how.profile = p;
        auto chains = interpolate_drawing(as_drawing(v), how);
        ASSERT_TRUE(chains.ok());
        expect_exact_round_trip((*chains)[0], p);
        std::vector<Segment> cut;
        ASSERT_TRUE(segment_default_phase((*chains)[0].steps, 2, p, cut).ok());
        ASSERT_EQ(cut.size(), 3u) << profile_name(p);  // the polyline's own vertices
        EXPECT_EQ(cut[0].delta, (Point{7, 3}));
    }
}

TEST(VectorsExact, PolylinesDrawnByEachProfile) {
    std::mt19937 rng(12);
    for (Profile p : kAllProfiles)
        for (int round = 0; round < 40; ++round) {
            const auto v = random_polyline(rng, 12, round < 20 ? 9 : 300);
            DrawingInterpolation how;
            how.profile = p;
            auto chains = interpolate_drawing(as_drawing(v), how);
            ASSERT_TRUE(chains.ok());
            expect_exact_round_trip((*chains)[0], p);
        }
}

TEST(VectorsExact, BresenhamPlotsUnderEveryProfile) {
    std::mt19937 rng(1965);
    for (int round = 0; round < 30; ++round) {
        const auto v = random_polyline(rng, 10, round < 15 ? 12 : 500);
        for (bool four : {false, true}) {
            Chain chain;
            chain.start = {v[0].x, v[0].y};
            for (std::size_t i = 1; i < v.size(); ++i)
                bresenham(v[i].x - v[i - 1].x, v[i].y - v[i - 1].y, four, chain.steps);
            for (Profile p : kAllProfiles)
                if (four || profile_eight_connected(p)) expect_exact_round_trip(chain, p);
        }
    }
}

TEST(VectorsExact, RandomWalksStillRoundTrip) {
    std::mt19937 rng(7);
    for (Profile p : kAllProfiles) {
        Chain chain;
        chain.start = {3, -4};
        const bool eight = profile_eight_connected(p);
        for (int i = 0; i < 3000; ++i)
            chain.steps.push_back(freeman_to_step(static_cast<int>(rng() % 8) & (eight ? 7 : 6)));
        expect_exact_round_trip(chain, p);
    }
}

TEST(VectorsExact, RedrawCheckFindsAPhaseTheVectorsCannotCarry) {
    // (8, 3) at eval8's default phase draws 0 1 0 0 1 0 0 1 ... ; these
    // steps are (8, 3) at another phase: exact as a segment, not as a vector.
    Chain chain;
    for (int i = 0; i < 8; ++i) chain.steps.push_back(make_step2(1, i % 3 == 0 ? 1 : 0));
    std::vector<Segment> free_cut;
    ASSERT_TRUE(segment_steps(chain.steps, 2, Profile::eval8, SegmenterKind::greedy, free_cut).ok());
    ASSERT_EQ(free_cut.size(), 1u);
    ASSERT_NE(free_cut[0], default_segment(Profile::eval8, free_cut[0].delta, 2));
    auto drawing = segments_to_drawing({SegmentedChain{chain, free_cut}});
    ASSERT_TRUE(drawing.ok());
    const auto r = check_redraw(*drawing, {chain}, Profile::eval8);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, Errc::mismatch);
    EXPECT_NE(r.error().message.find("chain 1"), std::string::npos) << r.error().message;
    expect_exact_round_trip(chain, Profile::eval8);
}
