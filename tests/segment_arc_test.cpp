// The arc recognizer against brute force: for every integer centre in a box,
// both directions and every end point, the longest prefix that
// interpolate_arc reproduces, compared with longest_arc_about (per centre)
// and longest_arc (over the centres), for every arc method.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "stepzip/interpolate/arc.hpp"
#include "stepzip/segment/arc.hpp"

namespace stepzip {
namespace {

constexpr ArcMethod kMethods[] = {ArcMethod::evaluation, ArcMethod::accelerated, ArcMethod::dda,
                                  ArcMethod::prediction_correction,
                                  ArcMethod::double_recursion};

bool eight_connected(ArcMethod m) {
    return m == ArcMethod::accelerated || m == ArcMethod::dda || m == ArcMethod::double_recursion;
}

// The longest k such that interpolate_arc(m, -c, p_k - c, ccw) == steps[0, k):
// every end tried.
std::size_t brute_about(ArcMethod m, const std::vector<Step>& steps, std::int64_t cx,
                        std::int64_t cy, bool ccw) {
    if (cx == 0 && cy == 0) return 0;
    std::size_t best = 0;
    std::int64_t x = 0, y = 0;
    std::vector<Step> out;
    for (std::size_t k = 1; k <= steps.size(); ++k) {
        x += step_axis(steps[k - 1], 0);
        y += step_axis(steps[k - 1], 1);
        out.clear();
        if (!interpolate_arc(m, -cx, -cy, x - cx, y - cy, ccw, out)) continue;
        if (out.size() == k && std::equal(out.begin(), out.end(), steps.begin())) best = k;
    }
    return best;
}

std::string freeman(const std::vector<Step>& steps) {
    std::string s;
    for (Step st : steps) s += static_cast<char>('0' + step_to_freeman(st));
    return s;
}

std::vector<Step> random_steps(std::mt19937_64& rng, std::size_t n, bool eight) {
    std::vector<Step> s;
    for (std::size_t i = 0; i < n; ++i) {
        const int code = static_cast<int>(rng() % 8);
        s.push_back(freeman_to_step(eight ? code : (code & 6)));
    }
    return s;
}

// An arc drawn by `m` about a random integer centre (radius <= rmax) to a
// random end on its circle, then `extra` random steps.
std::vector<Step> drawn_arc(std::mt19937_64& rng, ArcMethod m, std::int64_t rmax,
                            std::size_t extra, std::size_t* arc_steps = nullptr,
                            std::int64_t* r2 = nullptr) {
    for (;;) {
        const std::int64_t sx = static_cast<std::int64_t>(rng() % (2 * rmax + 1)) - rmax;
        const std::int64_t sy = static_cast<std::int64_t>(rng() % (2 * rmax + 1)) - rmax;
        if (sx == 0 && sy == 0) continue;
        const double r = std::hypot(static_cast<double>(sx), static_cast<double>(sy));
        const double a = std::uniform_real_distribution<double>(0, 6.283185307)(rng);
        const auto ex = static_cast<std::int64_t>(std::llround(r * std::cos(a)));
        const auto ey = static_cast<std::int64_t>(std::llround(r * std::sin(a)));
        if (ex == 0 && ey == 0) continue;
        std::vector<Step> s;
        if (!interpolate_arc(m, sx, sy, ex, ey, rng() % 2 == 0, s)) continue;
        if (arc_steps) *arc_steps = s.size();
        if (r2) *r2 = sx * sx + sy * sy;
        const auto more = random_steps(rng, extra, eight_connected(m));
        s.insert(s.end(), more.begin(), more.end());
        return s;
    }
}

struct Brute {
    std::size_t length = 0;
};

Brute brute_box(ArcMethod m, const std::vector<Step>& steps, std::int64_t box) {
    Brute b;
    for (std::int64_t cy = -box; cy <= box; ++cy)
        for (std::int64_t cx = -box; cx <= box; ++cx)
            for (bool ccw : {true, false})
                b.length = std::max(b.length, brute_about(m, steps, cx, cy, ccw));
    return b;
}

// Verifies an ArcFit by drawing it.
void expect_reproduces(ArcMethod m, const std::vector<Step>& steps, const ArcFit& f) {
    ASSERT_GT(f.length, 0u);
    ASSERT_LE(f.length, steps.size());
    std::vector<Step> out;
    ASSERT_TRUE(interpolate_arc(m, -f.cx, -f.cy, f.ex - f.cx, f.ey - f.cy, f.ccw, out));
    EXPECT_EQ(std::vector<Step>(steps.begin(), steps.begin() + static_cast<long>(f.length)), out);
}

// Per centre: the bounded search equals the brute force (every end tried),
// on drawn arcs with random tails and on random steps.
TEST(ArcRecognizer, AboutEqualsBruteForceOnEveryCentre) {
    std::mt19937_64 rng(14);
    for (ArcMethod m : kMethods) {
        for (int round = 0; round < 24; ++round) {
            const bool random = round % 4 == 3;
            const auto steps = random ? random_steps(rng, 10, eight_connected(m))
                                      : drawn_arc(rng, m, 7, 5);
            const std::int64_t box = 9;
            for (std::int64_t cy = -box; cy <= box; ++cy)
                for (std::int64_t cx = -box; cx <= box; ++cx)
                    for (bool ccw : {true, false})
                        ASSERT_EQ(brute_about(m, steps, cx, cy, ccw),
                                  longest_arc_about(m, steps, cx, cy, ccw))
                            << arc_method_name(m) << " round " << round << " centre (" << cx
                            << "," << cy << ") ccw " << ccw << " steps " << freeman(steps);
        }
    }
}

// Over a box of centres: the exhaustive mode finds an arc at least as long
// as the brute force over the box (the estimated centres may add a longer
// one from outside it), and its answer reproduces the steps.
TEST(ArcRecognizer, ExhaustiveModeEqualsBruteForce) {
    std::mt19937_64 rng(1414);
    for (ArcMethod m : kMethods) {
        for (int round = 0; round < 12; ++round) {
            const auto steps = round % 3 == 2 ? random_steps(rng, 9, eight_connected(m))
                                              : drawn_arc(rng, m, 6, 4);
            ArcSearchOptions o;
            o.min_length = 1;
            o.exhaustive_box = 8;
            const ArcFit f = longest_arc(m, steps, o);
            const Brute b = brute_box(m, steps, 8);
            ASSERT_GE(f.length, b.length) << arc_method_name(m) << " round " << round;
            if (f.length > 0) expect_reproduces(m, steps, f);
        }
    }
}

// Centres found from the steps alone: on a drawn arc of at least
// min_length steps the estimate finds an arc at least as long as the drawn
// one, and as long as the brute force over a box holding every centre of
// radius <= 12 from the start.
TEST(ArcRecognizer, EstimatedCentreFindsDrawnArcs) {
    std::mt19937_64 rng(140);
    int found_brute = 0, total = 0;
    for (ArcMethod m : kMethods) {
        for (int round = 0; round < 30; ++round) {
            std::size_t drawn = 0;
            const auto steps = drawn_arc(rng, m, 9, 6, &drawn);
            if (drawn < 8) continue;
            ++total;
            const ArcFit f = longest_arc(m, steps);
            ASSERT_GE(f.length, drawn)
                << arc_method_name(m) << " round " << round << " steps " << freeman(steps);
            expect_reproduces(m, steps, f);
            const Brute b = brute_box(m, steps, 12);
            EXPECT_LE(f.length, b.length);
            found_brute += f.length == b.length;
        }
    }
    EXPECT_EQ(found_brute, total);
}

// Larger radii: arcs drawn about centres up to 500 steps away (on each
// axis) are found whole from the steps alone, for every method, when they
// bow by 2 steps or more (n² >= 16R, n steps; a flatter arc is a digital
// straight line as far as its steps show, and may be found shorter).
TEST(ArcRecognizer, FindsLargeArcs) {
    std::mt19937_64 rng(7);
    int tried = 0;
    for (ArcMethod m : kMethods) {
        for (int round = 0; round < 6; ++round) {
            std::size_t drawn = 0;
            std::int64_t r2 = 0;
            const auto steps = drawn_arc(rng, m, 500, 0, &drawn, &r2);
            if (drawn < 8 || static_cast<double>(drawn * drawn) < 16 * std::sqrt(double(r2)))
                continue;
            ++tried;
            const ArcFit f = longest_arc(m, steps);
            ASSERT_EQ(f.length, drawn) << arc_method_name(m) << " round " << round;
            expect_reproduces(m, steps, f);
        }
    }
    EXPECT_GE(tried, 20);
}

// A straight run is also drawn by arcs (an end whose counter is used up at
// once leaves one axis to move); whatever is found reproduces the run.
// Input shorter than min_length gives nothing.
TEST(ArcRecognizer, StraightRunsAndShortInput) {
    const std::vector<Step> run(40, make_step2(1, 0));
    for (ArcMethod m : kMethods) {
        const ArcFit f = longest_arc(m, run);
        if (f.length > 0) expect_reproduces(m, run, f);
        EXPECT_EQ(longest_arc(m, std::span<const Step>(run).first(7)).length, 0u);
        EXPECT_EQ(longest_arc(m, {}).length, 0u);
    }
}

}  // namespace
}  // namespace stepzip
