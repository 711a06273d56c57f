// Forward interpolators: steps produced per second.
#include <benchmark/benchmark.h>

#include <vector>

#include "stepzip/interpolate/segment.hpp"
#include "stepzip/profile.hpp"

namespace {

void BM_ExpandSegment(benchmark::State& state) {
    const auto profile = static_cast<stepzip::Profile>(state.range(0));
    const int axes = 2;
    stepzip::Point delta{};
    delta[0] = 1000;
    delta[1] = 377;
    const stepzip::Segment seg = stepzip::default_segment(profile, delta, axes);
    std::vector<stepzip::Step> out;
    std::int64_t steps = 0;
    for (auto _ : state) {
        out.clear();
        stepzip::expand_segment(profile, seg, axes, out);
        benchmark::DoNotOptimize(out.data());
        steps += static_cast<std::int64_t>(out.size());
    }
    state.counters["steps/s"] = benchmark::Counter(static_cast<double>(steps),
                                                   benchmark::Counter::kIsRate);
    state.SetLabel(std::string(stepzip::profile_name(profile)));
}
BENCHMARK(BM_ExpandSegment)->DenseRange(0, 4);

}  // namespace
