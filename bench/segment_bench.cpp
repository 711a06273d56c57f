// Reverse interpolation: steps segmented per second, greedy and optimal, on a
// random-slope polyline (long exact segments), on a random walk (short ones)
// and on digital circles (short segments in long runs of one quadrant, as
// traced glyph contours have: the patent profile reads a quadrant's run
// ahead and checks its candidates from the longest down).
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "stepzip/profile.hpp"
#include "stepzip/segmenter.hpp"

namespace {

using namespace stepzip;

constexpr std::size_t kSteps = 200000;

// Lines of random slope and length 1..400, each drawn by the profile's own
// interpolator at a random phase; the direction turns by one octant at most.
std::vector<Step> polyline(Profile p) {
    std::mt19937_64 rng(1);
    const Profile draw = profile_eight_connected(p) ? Profile::eval8 : p;
    std::vector<Step> steps;
    int sx = 1, sy = 1;
    while (steps.size() < kSteps) {
        Point d{};
        d[0] = sx * std::uniform_int_distribution<int>(0, 200)(rng);
        d[1] = sy * std::uniform_int_distribution<int>(0, 200)(rng);
        if (d[0] == 0 && d[1] == 0) continue;
        Segment seg = default_segment(draw, d, 2);
        const auto ab = *phase_arguments(draw, seg, 2, 0);
        const PhaseRange r = phase_range(draw, ab.first, ab.second);
        seg.phase[0] = std::uniform_int_distribution<std::int64_t>(r.lo, r.hi - 1)(rng);
        expand_segment(draw, seg, 2, steps);
        if (rng() % 3 == 0) sx = -sx;
        if (rng() % 3 == 0) sy = -sy;
    }
    steps.resize(kSteps);
    return steps;
}

// A walk that keeps its heading with probability 1/2, else turns by one
// code (8-connected) or one quarter (4-connected).
std::vector<Step> random_walk(Profile p) {
    std::mt19937_64 rng(2);
    const bool eight = profile_eight_connected(p);
    std::vector<Step> steps;
    int code = 0;
    while (steps.size() < kSteps) {
        const auto r = rng() % 4;
        if (r == 2) code += eight ? 1 : 2;
        if (r == 3) code += eight ? 7 : 6;
        code &= 7;
        steps.push_back(freeman_to_step(code));
    }
    return steps;
}

// Circles of radius 20..400 around the origin, each traced from (r, 0)
// counter-clockwise by the step (one axis, or on 8-connected profiles both)
// that keeps x^2 + y^2 nearest r^2.
std::vector<Step> circles(Profile p) {
    std::mt19937_64 rng(3);
    const bool eight = profile_eight_connected(p);
    // per quadrant: its two axis moves and where it ends, in radii
    static constexpr int kDx[4] = {-1, -1, 1, 1}, kDy[4] = {1, -1, -1, 1};
    static constexpr int kEndX[4] = {0, -1, 0, 1}, kEndY[4] = {1, 0, -1, 0};
    std::vector<Step> steps;
    while (steps.size() < kSteps) {
        const std::int64_t r = std::uniform_int_distribution<std::int64_t>(20, 400)(rng);
        auto err = [r](std::int64_t a, std::int64_t b) { return std::llabs(a * a + b * b - r * r); };
        std::int64_t x = r, y = 0;
        for (int q = 0; q < 4; ++q) {
            const std::int64_t ex = kEndX[q] * r, ey = kEndY[q] * r;
            while (x != ex || y != ey) {
                int mx = x != ex ? kDx[q] : 0, my = y != ey ? kDy[q] : 0;
                if (mx != 0 && my != 0) {
                    const std::int64_t e_x = err(x + mx, y), e_y = err(x, y + my), e_xy = err(x + mx, y + my);
                    const bool diagonal = eight && e_xy <= e_x && e_xy <= e_y;
                    if (!diagonal) (e_x <= e_y ? my : mx) = 0;
                }
                x += mx;
                y += my;
                steps.push_back(make_step2(mx, my));
            }
        }
    }
    steps.resize(kSteps);
    return steps;
}

void run(benchmark::State& state, int input) {
    const auto profile = static_cast<Profile>(state.range(0));
    const auto kind = static_cast<SegmenterKind>(state.range(1));
    const std::vector<Step> steps = input == 1 ? random_walk(profile) : input == 2 ? circles(profile) : polyline(profile);
    std::vector<Segment> out;
    std::int64_t done = 0;
    for (auto _ : state) {
        out.clear();
        auto r = segment_steps(steps, 2, profile, kind, out);
        if (!r) state.SkipWithError(r.error().message.c_str());
        benchmark::DoNotOptimize(out.data());
        done += static_cast<std::int64_t>(steps.size());
    }
    state.counters["steps/s"] =
        benchmark::Counter(static_cast<double>(done), benchmark::Counter::kIsRate);
    state.counters["steps/segment"] =
        static_cast<double>(steps.size()) / static_cast<double>(out.size());
    state.SetLabel(std::string(profile_name(profile)) + " " + std::string(segmenter_name(kind)));
}

void BM_SegmentPolyline(benchmark::State& state) { run(state, 0); }
void BM_SegmentRandomWalk(benchmark::State& state) { run(state, 1); }
void BM_SegmentCircles(benchmark::State& state) { run(state, 2); }

BENCHMARK(BM_SegmentPolyline)
    ->ArgsProduct({{0, 1, 2, 3, 4}, {0, 1}})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SegmentRandomWalk)
    ->ArgsProduct({{0, 1, 2, 3, 4}, {0, 1}})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SegmentCircles)
    ->ArgsProduct({{0, 1, 2, 3, 4}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

}  // namespace
