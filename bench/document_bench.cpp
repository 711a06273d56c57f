// Chain files: parsing (BlockReader) and rendering (BlockWriter) throughput in
// steps/s and bytes/s, for freeman text (long plotter-like lines and short
// contour-like lines) and the binary steps format.
#include <benchmark/benchmark.h>

#include <random>
#include <string>
#include <vector>

#include "stepzip/document.hpp"

namespace {

using namespace stepzip;

constexpr std::size_t kSteps = 1 << 20;

// Chains of `len` steps made of runs of one code (a pen moving in straight
// strokes), 8-connected, or one 4-axis chain for the steps format.
std::vector<Chain> make_chains(InputFormat f, std::size_t len) {
    std::mt19937_64 rng(9);
    std::vector<Chain> chains;
    std::size_t total = 0;
    Point at{};
    while (total < kSteps) {
        Chain c;
        c.axes = f == InputFormat::steps ? 4 : 2;
        c.start = at;
        const std::size_t n = f == InputFormat::steps ? kSteps : len;
        while (c.steps.size() < n) {
            const Step s = f == InputFormat::steps
                               ? static_cast<Step>(1u | ((rng() % 3) << 2) | (rng() % 2 ? 0x10u : 0u))
                               : freeman_to_step(static_cast<int>(rng() % 8));
            c.steps.insert(c.steps.end(), 1 + rng() % 6, s);
        }
        c.steps.resize(n);
        if (f == InputFormat::steps) {
            for (Step& s : c.steps)
                if (((s >> 2) & 3u) == 2u) s = static_cast<Step>(s & ~0xCu);  // no DIR on a rest
        }
        total += c.steps.size();
        at = c.end();
        chains.push_back(std::move(c));
    }
    return chains;
}

void counters(benchmark::State& state, std::size_t steps, std::size_t bytes) {
    state.counters["steps/s"] = benchmark::Counter(static_cast<double>(steps * state.iterations()),
                                                   benchmark::Counter::kIsRate);
    state.SetBytesProcessed(static_cast<std::int64_t>(bytes * state.iterations()));
}

void BM_Parse(benchmark::State& state) {
    const auto f = static_cast<InputFormat>(state.range(0));
    const auto text = write_chains(f, make_chains(f, static_cast<std::size_t>(state.range(1))));
    if (!text) {
        state.SkipWithError(text.error().message.c_str());
        return;
    }
    std::size_t steps = 0;
    for (auto _ : state) {
        BlockReader reader(f, "bench");
        // Fed in 1 MiB pieces, as the compressor does.
        for (std::size_t pos = 0; pos < text->size(); pos += 1 << 20) {
            const std::string_view piece = std::string_view(*text).substr(pos, 1 << 20);
            if (!reader.feed(piece, pos + piece.size() == text->size())) state.SkipWithError("parse");
        }
        Block b;
        steps = 0;
        while (reader.next(b))
            for (const Chain& c : b.chains) steps += c.steps.size();
        benchmark::DoNotOptimize(steps);
    }
    counters(state, steps, text->size());
    state.SetLabel(std::string(format_name(f)));
}

void BM_Render(benchmark::State& state) {
    const auto f = static_cast<InputFormat>(state.range(0));
    const auto text = write_chains(f, make_chains(f, static_cast<std::size_t>(state.range(1))));
    if (!text) {
        state.SkipWithError(text.error().message.c_str());
        return;
    }
    BlockReader reader(f, "bench");
    (void)reader.feed(*text, true);
    std::vector<Block> blocks;
    Block b;
    std::size_t steps = 0;
    while (reader.next(b)) {
        for (const Chain& c : b.chains) steps += c.steps.size();
        blocks.push_back(std::move(b));
        b = Block{};
    }
    BlockWriter writer(f);
    std::string out;
    for (auto _ : state) {
        out.clear();
        for (const Block& blk : blocks)
            if (!writer.write(blk, out)) state.SkipWithError("render");
        benchmark::DoNotOptimize(out.data());
    }
    counters(state, steps, out.size());
    state.SetLabel(std::string(format_name(f)));
}

// (format, steps per chain): freeman long lines, freeman short contours, steps
BENCHMARK(BM_Parse)->Args({0, 100000})->Args({0, 80})->Args({2, 0})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Render)->Args({0, 100000})->Args({0, 80})->Args({2, 0})->Unit(benchmark::kMillisecond);

}  // namespace
