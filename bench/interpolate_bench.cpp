// Forward interpolators: steps produced per second and time per step, next
// to memcpy of the same output bytes (2 bytes per step; the physical limit).
// Lines: 4096 random vectors (each axis uniform in [-400, 400]), expanded
// one after another into one reused vector, under every profile
// (expand_segment at the default phase, 2 to 6 axes where the profile takes
// them) and by every linear interpolator of interpolate/linear.hpp and
// interpolate/arc.hpp. Arcs and the DDA/carrier lines: circular_bench.
// Run: build/bench/interpolate_bench --benchmark_min_time=0.3
#include <benchmark/benchmark.h>

#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "stepzip/interpolate/arc.hpp"
#include "stepzip/interpolate/linear.hpp"
#include "stepzip/interpolate/segment.hpp"
#include "stepzip/profile.hpp"

namespace {

using namespace stepzip;

constexpr int kVectors = 4096;

std::vector<Point> vectors(int axes) {
    std::mt19937_64 rng(static_cast<std::uint64_t>(axes));
    std::uniform_int_distribution<int> d(-400, 400);
    std::vector<Point> out;
    while (out.size() < kVectors) {
        Point p{};
        bool any = false;
        for (int a = 0; a < axes; ++a) {
            p[a] = d(rng);
            any = any || p[a] != 0;
        }
        if (any) out.push_back(p);
    }
    return out;
}

void counters(benchmark::State& state, std::size_t steps) {
    const auto n = static_cast<double>(steps) * static_cast<double>(state.iterations());
    state.counters["per_step"] = benchmark::Counter(n, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    state.counters["steps/s"] = benchmark::Counter(n, benchmark::Counter::kIsRate);
    state.SetBytesProcessed(static_cast<std::int64_t>(steps * sizeof(Step)) * state.iterations());
}

// Runs `emit(vector, out)` over the vectors of `axes` axes.
template <class Emit>
void run(benchmark::State& state, int axes, Emit emit) {
    const std::vector<Point> v = vectors(axes);
    std::vector<Step> out;
    for (const Point& p : v) emit(p, out);
    const std::size_t steps = out.size();
    for (auto _ : state) {
        out.clear();
        for (const Point& p : v) emit(p, out);
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    counters(state, steps);
}

// The physical limit: memcpy of `steps` Steps (arg: log2 of the byte count;
// 20 = 1 MiB in cache, as the benchmarks below write; 28 = 256 MiB, DRAM).
void BM_Memcpy(benchmark::State& state) {
    const std::size_t bytes = std::size_t{1} << state.range(0);
    std::vector<char> src(bytes, 1), dst(bytes);
    for (auto _ : state) {
        std::memcpy(dst.data(), src.data(), bytes);
        benchmark::DoNotOptimize(dst.data());
        benchmark::ClobberMemory();
    }
    counters(state, bytes / sizeof(Step));
}
BENCHMARK(BM_Memcpy)->Arg(20)->Arg(28);

// expand_segment under each profile (args: profile, axes).
void BM_ExpandSegment(benchmark::State& state) {
    const auto p = static_cast<Profile>(state.range(0));
    const int axes = static_cast<int>(state.range(1));
    if (axes > profile_max_axes(p)) {
        state.SkipWithError("the profile does not take this axis count");
        return;
    }
    run(state, axes, [&](const Point& d, std::vector<Step>& out) {
        expand_segment(p, default_segment(p, d, axes), axes, out);
    });
    state.SetLabel(std::string(profile_name(p)) + " " + std::to_string(axes) + " axes");
}
BENCHMARK(BM_ExpandSegment)
    ->Args({0, 2})
    ->Args({1, 2})
    ->Args({2, 2})
    ->Args({3, 2})
    ->Args({4, 2})
    ->Args({1, 3})
    ->Args({1, 4})
    ->Args({1, 6});

// The linear interpolators themselves (arg selects one).
void BM_Linear(benchmark::State& state) {
    const int which = static_cast<int>(state.range(0));
    const char* names[] = {"eval_linear",  "accelerated_linear", "patent_forward (F00 = Y - X)",
                           "multiaxis_linear first_step_all_axes 3 axes", "interpolate_line dda",
                           "interpolate_line carrier"};
    const int axes = which == 3 ? 3 : 2;
    run(state, axes, [&](const Point& d, std::vector<Step>& out) {
        switch (which) {
            case 0: eval_linear(d[0], d[1], 0, out); break;
            case 1: accelerated_linear(d[0], d[1], 0, out); break;
            case 2: patent_forward(d[0], d[1], std::llabs(d[1]) - std::llabs(d[0]), out); break;
            case 3: {
                const std::int64_t ph[kMaxAxes - 1] = {};
                multiaxis_linear(d, 3, ph, out, MultiAxisVariant::first_step_all_axes);
                break;
            }
            case 4: (void)interpolate_line(LineMethod::dda, d[0], d[1], out); break;
            case 5: (void)interpolate_line(LineMethod::carrier, d[0], d[1], out); break;
        }
    });
    state.SetLabel(names[which]);
}
BENCHMARK(BM_Linear)->DenseRange(0, 5);

}  // namespace
