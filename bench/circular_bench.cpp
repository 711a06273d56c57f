// Forward circular and DDA/carrier line interpolators: steps produced per
// second and time per step (full circles of radius 1000 and 50 / line
// (1000, 377)); bytes/s counts 2 bytes per step, as memcpy's in
// interpolate_bench.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "stepzip/interpolate/arc.hpp"

namespace {

void rates(benchmark::State& state, std::int64_t steps) {
    const auto n = static_cast<double>(steps);
    state.counters["steps/s"] = benchmark::Counter(n, benchmark::Counter::kIsRate);
    state.counters["per_step"] = benchmark::Counter(n, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    state.SetBytesProcessed(steps * static_cast<std::int64_t>(sizeof(stepzip::Step)));
}

void BM_FullCircle(benchmark::State& state) {
    const auto method = static_cast<stepzip::ArcMethod>(state.range(0));
    // Radius 1000 from (600, 800), or radius 50 from (30, 40).
    const std::int64_t x0 = state.range(1) == 1000 ? 600 : 30, y0 = state.range(1) == 1000 ? 800 : 40;
    std::vector<stepzip::Step> out;
    std::int64_t steps = 0;
    for (auto _ : state) {
        out.clear();
        if (!stepzip::interpolate_arc(method, x0, y0, x0, y0, true, out))
            state.SkipWithError("interpolate_arc failed");
        benchmark::DoNotOptimize(out.data());
        steps += static_cast<std::int64_t>(out.size());
    }
    rates(state, steps);
    state.SetLabel(std::string(stepzip::arc_method_name(method)) + " r=" + std::to_string(state.range(1)));
}
BENCHMARK(BM_FullCircle)->ArgsProduct({{0, 1, 2, 3, 4}, {1000, 50}});

void BM_Line(benchmark::State& state) {
    const auto method = static_cast<stepzip::LineMethod>(state.range(0));
    std::vector<stepzip::Step> out;
    std::int64_t steps = 0;
    for (auto _ : state) {
        out.clear();
        if (!stepzip::interpolate_line(method, 1000, 377, out))
            state.SkipWithError("interpolate_line failed");
        benchmark::DoNotOptimize(out.data());
        steps += static_cast<std::int64_t>(out.size());
    }
    rates(state, steps);
    state.SetLabel(std::string(stepzip::line_method_name(method)));
}
BENCHMARK(BM_Line)->DenseRange(0, 1);

}  // namespace
