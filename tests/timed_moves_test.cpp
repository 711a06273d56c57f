// Moves and their speeds read out of timed chains (include/stepzip/timed.hpp):
// trapezoid moves generated here with known speeds and acceleration, the
// corpus stream planned at a known acceleration, and the corpus streams'
// planned moves (corpora/timed/*.moves) found again.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "stepzip/document.hpp"
#include "stepzip/segmenter.hpp"
#include "stepzip/timed.hpp"

namespace stepzip {
namespace {

// Time (s) at which a trapezoid move (entry v0, cruise vc, exit v1, path
// acceleration a, length len) reaches path position p.
double trapezoid_time(double v0, double vc, double v1, double a, double len, double p) {
    const double d_up = (vc * vc - v0 * v0) / (2 * a), d_down = (vc * vc - v1 * v1) / (2 * a);
    const double t_up = (vc - v0) / a, t_cruise = (len - d_up - d_down) / vc;
    if (p <= d_up) return (-v0 + std::sqrt(v0 * v0 + 2 * a * p)) / a;
    if (p <= len - d_down) return t_up + (p - d_up) / vc;
    const double q = p - (len - d_down);  // into the ramp down
    return t_up + t_cruise + (vc - std::sqrt(std::max(0.0, vc * vc - 2 * a * q))) / a;
}

struct Trapezoid {
    double v0, vc, v1, a;  // along the path, steps/s and steps/s^2
    std::int64_t dx, dy;   // the move, dx leading
};

// A timed chain (time, x, y) of one move: the x steps at the times the
// path passes (k + 1) / dx of its length, y by Bresenham on x, in ticks of
// `tick` seconds (the tick a step falls in), then 10 idle ticks.
Chain timed_move(const Trapezoid& m, double tick) {
    const double len = std::hypot(static_cast<double>(m.dx), static_cast<double>(m.dy));
    Chain c;
    c.axes = 3;
    const int tick_only[3] = {1, 0, 0};
    const Step idle = make_step(tick_only, 3);
    std::int64_t err = m.dx / 2;
    for (std::int64_t k = 0; k < m.dx; ++k) {
        const double t = trapezoid_time(m.v0, m.vc, m.v1, m.a, len, static_cast<double>(k + 1) * len / m.dx);
        const auto tick_of = static_cast<std::size_t>(std::floor(t / tick));
        if (c.steps.size() <= tick_of) c.steps.resize(tick_of + 1, idle);
        err -= m.dy;
        int d[3] = {1, 1, 0};
        if (err < 0) {
            err += m.dx;
            d[2] = 1;
        }
        EXPECT_EQ(c.steps[tick_of], idle) << "two steps in one tick";
        c.steps[tick_of] = make_step(d, 3);
    }
    c.steps.resize(c.steps.size() + 10, idle);
    return c;
}

TEST(TimedMoves, PathDropsTimeAndIdleTicks) {
    Chain c;
    c.axes = 3;
    c.start = {5, 7, 9};
    const int idle[3] = {1, 0, 0}, xy[3] = {1, 1, -1}, y[3] = {1, 0, 1};
    c.steps = {make_step(idle, 3), make_step(xy, 3), make_step(idle, 3), make_step(y, 3)};
    const TimedPath p = timed_path(c);
    EXPECT_EQ(p.path.axes, 2);
    EXPECT_EQ(p.path.start[0], 7);
    EXPECT_EQ(p.path.start[1], 9);
    ASSERT_EQ(p.path.steps.size(), 2u);
    EXPECT_EQ(p.path.steps[0], make_step2(1, -1));
    EXPECT_EQ(p.path.steps[1], make_step2(0, 1));
    EXPECT_EQ(p.ticks, (std::vector<std::uint64_t>{1, 3}));
}

// Known settings come back within 2 % of the cruise speed (speeds) and 5 %
// (acceleration), at 25 µs ticks (a step every 10 ticks or more).
TEST(TimedMoves, GeneratedTrapezoidsGiveTheirSettingsBack) {
    const double tick = 25e-6;
    const Trapezoid moves[] = {
        {0, 4000, 0, 20000, 3000, 1500},      // from rest to rest
        {800, 3000, 1200, 15000, 2500, 0},    // junction speeds at both ends, one axis
        {1500, 3500, 0, 40000, 1800, 1700},   // near diagonal, short ramps
        {0, 2000, 2000, 8000, 4000, 1000},    // no ramp down
    };
    for (const Trapezoid& m : moves) {
        const Chain c = timed_move(m, tick);
        const TimedPath p = timed_path(c);
        std::vector<std::uint64_t> lead;
        for (std::size_t k = 0; k < p.path.steps.size(); ++k)
            if (step_axis(p.path.steps[k], 0) != 0) lead.push_back(p.ticks[k]);
        ASSERT_EQ(lead.size(), static_cast<std::size_t>(m.dx));
        const double len = std::hypot(static_cast<double>(m.dx), static_cast<double>(m.dy));
        const MoveSpeeds s = move_speeds(lead, len, tick);
        const std::string what = "move " + std::to_string(m.dx) + "," + std::to_string(m.dy);
        EXPECT_NEAR(s.cruise, m.vc, 0.02 * m.vc) << what;
        EXPECT_NEAR(s.entry, m.v0, 0.02 * m.vc) << what;
        EXPECT_NEAR(s.exit, m.v1, 0.02 * m.vc) << what;
        EXPECT_NEAR(s.acceleration, m.a, 0.05 * m.a) << what;
        EXPECT_GT(s.ramp_steps, 0u) << what;
    }
}

// A move at a constant rate whose last stepper segment runs faster (8
// ticks a step, then its last 10 steps at 7, as a controller finishes a
// move on time): the cruise is the rate held, not the fastest window (which
// read about 9 % more), and the move has no ramps.
TEST(TimedMoves, ConstantRateMoveReadsTheRateHeld) {
    std::vector<std::uint64_t> ticks;
    std::uint64_t at = 100;
    for (int k = 0; k < 160; ++k) {
        ticks.push_back(at);
        at += k < 150 ? 8 : 7;
    }
    const double tick = 40e-6, held = 1.0 / (8 * tick);  // steps/s (length = steps: an axis-parallel move)
    const MoveSpeeds s = move_speeds(ticks, 160.0, tick);
    EXPECT_NEAR(s.cruise, held, 0.02 * held);
    // no ramps: the faster last segment is no acceleration of the planner
    EXPECT_EQ(s.acceleration, 0);
    EXPECT_EQ(s.ramp_steps, 0u);
}

// A move at one planned speed whose stepper segments alternate between
// two rates 20 % apart (24 and 20 ticks a step, 15 steps each): it starts
// and ends near its speed, so the cruise is its mean speed (the stretch
// near the fastest rate alone read 3 % over it).
TEST(TimedMoves, AlternatingSegmentsReadTheirMeanSpeed) {
    std::vector<std::uint64_t> ticks{0};
    for (int k = 1; k < 60; ++k) ticks.push_back(ticks.back() + ((k - 1) / 15 % 2 == 0 ? 24 : 20));
    const double tick = 30e-6;
    const double mean = 59.0 / (static_cast<double>(ticks.back() - ticks.front()) * tick);
    const MoveSpeeds s = move_speeds(ticks, 60.0, tick);
    EXPECT_NEAR(s.cruise, mean, 0.01 * mean);
}

TEST(TimedMoves, TooFewStepsGiveNothing) {
    const std::uint64_t one[] = {4};
    const MoveSpeeds s = move_speeds(one, 1.0, 1e-5);
    EXPECT_EQ(s.cruise, 0);
    EXPECT_EQ(s.acceleration, 0);
}

// The path of corpora/timed/NAME.steps, a log of one chain.
void read_corpus_path(const std::string& name, TimedPath& p) {
    std::ifstream f(std::string(STEPZIP_SOURCE_DIR) + "/corpora/timed/" + name + ".steps", std::ios::binary);
    std::ostringstream ss;
    ss << f.rdbuf();
    auto chains = read_chains(InputFormat::timed, ss.str());
    ASSERT_TRUE(chains.ok());
    ASSERT_EQ(chains->size(), 1u);
    p = timed_path((*chains)[0]);
}

// corpora/timed/trapezoid-2axis.steps was planned at 500 mm/s² per axis,
// 80 steps/mm (40 000 steps/s² on the leading axis of every move), 30 µs
// ticks, axis rate limit 6000 mm/min (8000 steps/s): the moves of the path
// with long ramps (100 steps or more) give that acceleration back within
// 5 %, and no move is faster than the rate limit (3 % for the window).
TEST(TimedMoves, CorpusStreamGivesItsAccelerationBack) {
    TimedPath p;
    ASSERT_NO_FATAL_FAILURE(read_corpus_path("trapezoid-2axis", p));
    std::size_t checked = 0, within = 0;
    for (const TimedMove& m : timed_moves(p, 30e-6)) {
        std::int64_t lead = 0;
        for (int i = 0; i < p.path.axes; ++i) lead = std::max<std::int64_t>(lead, std::llabs(m.delta[static_cast<std::size_t>(i)]));
        const double share = static_cast<double>(lead) / m.length;  // path -> leading axis
        EXPECT_LE(m.speeds.cruise * share, 8000 * 1.03);
        if (m.speeds.ramp_steps < 100) continue;
        ++checked;
        if (std::fabs(m.speeds.acceleration * share - 40000) <= 0.05 * 40000) ++within;
    }
    ASSERT_GE(checked, 2u);
    EXPECT_EQ(within, checked);
}

// corpora/timed/trapezoid-{2,3}axis.moves hold the moves the generator
// planned (corpora/tools/regenerate.sh): timed_moves() finds about as many
// moves, and at least 85 % of the planned moves' ends are ends of its moves
// exactly (Douglas-Peucker alone, at 1 step: 475 moves for 62 and 8 ends,
// 1614 for 124 and 17).
TEST(TimedMoves, CorpusStreamsGiveTheirPlannedMovesBack) {
    for (const char* name : {"trapezoid-2axis", "trapezoid-3axis"}) {
        SCOPED_TRACE(name);
        TimedPath p;
        ASSERT_NO_FATAL_FAILURE(read_corpus_path(name, p));
        const int axes = p.path.axes;
        // Where each planned move ends, from the path's start.
        std::ifstream planned(std::string(STEPZIP_SOURCE_DIR) + "/corpora/timed/" + name + ".moves");
        std::vector<Point> ends;
        Point at{};
        for (std::string line; std::getline(planned, line);) {
            std::istringstream in(line);
            for (int i = 0; i < axes; ++i) {
                std::int64_t v = 0;
                ASSERT_TRUE(in >> v) << line;
                at[static_cast<std::size_t>(i)] += v;
            }
            ends.push_back(at);
        }
        ASSERT_GE(ends.size(), 50u);
        const std::vector<TimedMove> moves = timed_moves(p, 30e-6);
        std::vector<Point> found;
        Point to{};
        for (const TimedMove& m : moves) {
            for (int i = 0; i < axes; ++i) to[static_cast<std::size_t>(i)] += m.delta[static_cast<std::size_t>(i)];
            found.push_back(to);
        }
        std::sort(found.begin(), found.end());
        const auto hits = std::count_if(ends.begin(), ends.end(), [&](const Point& e) {
            return std::binary_search(found.begin(), found.end(), e);
        });
        EXPECT_LE(std::llabs(static_cast<long long>(moves.size()) - static_cast<long long>(ends.size())),
                  static_cast<long long>(ends.size() / 20 + 1));
        EXPECT_GE(static_cast<double>(hits), 0.85 * static_cast<double>(ends.size()));
    }
}

// corpora/timed/grbl-excerpt.steps: 5098 ticks of the Grbl 1.1h stream of
// ../shared/corpora-timed holding four moves of its job (.moves). Alone,
// each of the two inner corners comes to rest a step beside its end, each
// held there by the other; moving them together finds all four moves.
TEST(TimedMoves, NeighbouringCornersMoveTogether) {
    TimedPath p;
    ASSERT_NO_FATAL_FAILURE(read_corpus_path("grbl-excerpt", p));
    std::ifstream planned(std::string(STEPZIP_SOURCE_DIR) + "/corpora/timed/grbl-excerpt.moves");
    std::vector<Point> want;
    for (std::int64_t x = 0, y = 0; planned >> x >> y;) want.push_back(Point{x, y});
    ASSERT_EQ(want.size(), 4u);
    const std::vector<TimedMove> moves = timed_moves(p, 40e-6);
    ASSERT_EQ(moves.size(), want.size());
    for (std::size_t i = 0; i < moves.size(); ++i) {
        EXPECT_EQ(moves[i].delta[0], want[i][0]) << "move " << i;
        EXPECT_EQ(moves[i].delta[1], want[i][1]) << "move " << i;
    }
}

}  // namespace
}  // namespace stepzip
