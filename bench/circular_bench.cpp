// Forward circular and DDA/carrier line interpolators: steps produced per
// second (full circle of radius 1000 / line (1000, 377)).
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "stepzip/interpolate/arc.hpp"

namespace {

void BM_FullCircle(benchmark::State& state) {
    const auto method = static_cast<stepzip::ArcMethod>(state.range(0));
    std::vector<stepzip::Step> out;
    std::int64_t steps = 0;
    for (auto _ : state) {
        out.clear();
        if (!stepzip::interpolate_arc(method, 600, 800, 600, 800, true, out))
            state.SkipWithError("interpolate_arc failed");
        benchmark::DoNotOptimize(out.data());
        steps += static_cast<std::int64_t>(out.size());
    }
    state.counters["steps/s"] =
        benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate);
    state.SetLabel(std::string(stepzip::arc_method_name(method)));
}
BENCHMARK(BM_FullCircle)->DenseRange(0, 4);

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
    state.counters["steps/s"] =
        benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate);
    state.SetLabel(std::string(stepzip::line_method_name(method)));
}
BENCHMARK(BM_Line)->DenseRange(0, 1);

}  // namespace
