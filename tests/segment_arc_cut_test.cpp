// Arcs and lines back from steps: random G-code jobs of lines and arcs,
// stepped with each arc method, cut by cut_arcs_and_lines, redraw (through
// G-code text) to the same steps, and come back with one arc per original
// arc — all but a few: an arc may be split in two where its last steps and
// the next line's first ones are drawn by another arc too.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "stepzip/segment/arc.hpp"
#include "stepzip/vectors.hpp"

namespace stepzip {
namespace {

constexpr ArcMethod kMethods[] = {ArcMethod::evaluation, ArcMethod::accelerated, ArcMethod::dda,
                                  ArcMethod::prediction_correction,
                                  ArcMethod::double_recursion};

// One path of `moves` random moves from (0, 0): lines of 20 to 200 steps,
// arcs of radius 15 to 150 turning 60 to 300 degrees either way. Returns
// the number of arcs.
std::size_t random_job(std::mt19937_64& rng, int moves, Drawing& drawing) {
    constexpr double kPi = 3.14159265358979323846;
    std::uniform_real_distribution<double> unit(0, 1);
    VectorPath path;
    std::int64_t x = 0, y = 0;
    std::size_t arcs = 0;
    for (int i = 0; i < moves; ++i) {
        VectorMove m;
        if (rng() % 2 == 0) {
            const double len = 20 + 180 * unit(rng), a = 2 * kPi * unit(rng);
            m.x = x + std::llround(len * std::cos(a));
            m.y = y + std::llround(len * std::sin(a));
        } else {
            const double r = 15 + 135 * unit(rng), a = 2 * kPi * unit(rng);
            m.cx = x + std::llround(r * std::cos(a));
            m.cy = y + std::llround(r * std::sin(a));
            const bool ccw = rng() % 2 == 0;
            const double sweep = (60 + 240 * unit(rng)) * kPi / 180 * (ccw ? 1 : -1);
            const auto sx = static_cast<double>(x - m.cx), sy = static_cast<double>(y - m.cy);
            m.x = m.cx + std::llround(sx * std::cos(sweep) - sy * std::sin(sweep));
            m.y = m.cy + std::llround(sx * std::sin(sweep) + sy * std::cos(sweep));
            m.kind = ccw ? MoveKind::arc_ccw : MoveKind::arc_cw;
            ++arcs;
        }
        path.moves.push_back(m);
        x = m.x;
        y = m.y;
    }
    drawing.push_back(path);
    return arcs;
}

std::size_t count_arcs(const Drawing& d) {
    std::size_t n = 0;
    for (const VectorPath& p : d)
        for (const VectorMove& m : p.moves) n += m.kind != MoveKind::line;
    return n;
}

TEST(ArcCut, RandomJobsComeBackWithTheirArcs) {
    std::mt19937_64 rng(2026);
    int jobs = 0, same_count = 0;
    for (ArcMethod method : kMethods) {
        const Profile profile = method == ArcMethod::evaluation ||
                                        method == ArcMethod::prediction_correction
                                    ? Profile::eval4
                                    : Profile::eval8;
        for (int job = 0; job < 3; ++job) {
            Drawing original;
            const std::size_t arcs = random_job(rng, 6, original);
            // Through G-code text, as `interpolate` reads it.
            auto read = read_gcode(write_gcode(original));
            ASSERT_TRUE(read) << read.error().message;
            DrawingInterpolation how;
            how.profile = profile;
            how.arc_method = method;
            auto chains = interpolate_drawing(*read, how);
            ASSERT_TRUE(chains) << chains.error().message;
            auto cut = cut_chains_into_arcs(*chains, profile, method);
            ASSERT_TRUE(cut) << cut.error().message;
            auto drawing = arc_cut_to_drawing(*cut);
            ASSERT_TRUE(drawing);
            const std::string where =
                std::string(arc_method_name(method)) + " job " + std::to_string(job);
            const std::size_t found = count_arcs(*drawing);
            EXPECT_LE(found, arcs + 1) << where;
            EXPECT_GE(found + 1, arcs) << where;
            ++jobs;
            same_count += found == arcs;
            ASSERT_TRUE(check_redraw(*drawing, *chains, profile, method)) << where;
            // The G-code written for the cut redraws the same steps.
            auto again = read_gcode(write_gcode(*drawing));
            ASSERT_TRUE(again);
            auto redrawn = interpolate_drawing(*again, how);
            ASSERT_TRUE(redrawn);
            ASSERT_EQ(redrawn->size(), chains->size());
            for (std::size_t c = 0; c < chains->size(); ++c)
                EXPECT_EQ((*redrawn)[c].steps, (*chains)[c].steps) << where;
        }
    }
    // At most one job in ten has an arc more or less than it was drawn with.
    EXPECT_GE(same_count * 10, jobs * 9) << same_count << " of " << jobs;
}

TEST(ArcCut, LinesOnlyStayLines) {
    Drawing d{VectorPath{0, 0, {}}};
    for (auto [x, y] : {std::pair{40, 7}, {40, 60}, {-3, 90}, {-50, 20}}) {
        VectorMove m;
        m.x = x;
        m.y = y;
        d[0].moves.push_back(m);
    }
    DrawingInterpolation how;
    how.profile = Profile::eval8;
    auto chains = interpolate_drawing(d, how);
    ASSERT_TRUE(chains);
    for (ArcMethod method : kMethods) {
        auto cut = cut_chains_into_arcs(*chains, Profile::eval8, method);
        ASSERT_TRUE(cut);
        auto drawing = arc_cut_to_drawing(*cut);
        ASSERT_TRUE(drawing);
        EXPECT_EQ(count_arcs(*drawing), 0u) << arc_method_name(method);
        EXPECT_TRUE(check_redraw(*drawing, *chains, Profile::eval8, method));
    }
}

TEST(ArcCut, RefusesOtherAxisCounts) {
    std::vector<ArcCutMove> out;
    const std::vector<Step> steps(3, make_step2(1, 0));
    EXPECT_EQ(cut_arcs_and_lines(steps, 3, Profile::eval8, ArcMethod::evaluation, {}, out)
                  .error()
                  .code,
              Errc::invalid_argument);
}

}  // namespace
}  // namespace stepzip
