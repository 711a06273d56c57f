// Container benchmarks: encode and decode speed (steps/s) and the payload
// layout measurements quoted in docs/FORMAT.md ("Rationale"), reported as
// bits/step counters. Run: build/bench/container_bench
#include <benchmark/benchmark.h>
#include <zstd.h>

#include <string>
#include <vector>

#include "../src/container/block_codec.hpp"
#include "container_corpus.hpp"
#include "stepzip/container.hpp"
#include "stepzip/segmenter.hpp"

namespace {

using namespace stepzip;

constexpr std::size_t kSteps = 300000;

const std::vector<Chain>& corpus(int which) {
    static const std::vector<Chain> c[3] = {corpus::contours(1, kSteps),
                                            corpus::plotter(2, kSteps, Profile::grbl),
                                            corpus::random_walk(3, kSteps)};
    return c[which];
}
const char* corpus_name(int which) {
    static const char* n[3] = {"contours", "plotter", "walk"};
    return n[which];
}
std::size_t count_steps(const std::vector<Chain>& cs) {
    std::size_t n = 0;
    for (const Chain& c : cs) n += c.steps.size();
    return n;
}

void BM_Compress(benchmark::State& state) {
    const auto& chains = corpus(static_cast<int>(state.range(0)));
    const std::string text = corpus::freeman_text(chains);
    CompressOptions opt;
    opt.profile = Profile::eval8;
    opt.level = static_cast<int>(state.range(1));
    opt.format = InputFormat::freeman;
    std::size_t size = 0;
    for (auto _ : state) {
        auto r = compress(text, opt);
        if (!r) state.SkipWithError(r.error().message.c_str());
        else size = r->size();
    }
    const double steps = static_cast<double>(count_steps(chains));
    state.SetLabel(corpus_name(static_cast<int>(state.range(0))));
    state.counters["steps/s"] = benchmark::Counter(steps, benchmark::Counter::kIsIterationInvariantRate);
    state.counters["bits/step"] = 8.0 * static_cast<double>(size) / steps;
}
BENCHMARK(BM_Compress)->ArgsProduct({{0, 1, 2}, {3, 19}})->Unit(benchmark::kMillisecond);

void BM_Decompress(benchmark::State& state) {
    const auto& chains = corpus(static_cast<int>(state.range(0)));
    const std::string text = corpus::freeman_text(chains);
    CompressOptions opt;
    opt.profile = Profile::eval8;
    opt.format = InputFormat::freeman;
    auto frame = compress(text, opt);
    if (!frame) {
        state.SkipWithError(frame.error().message.c_str());
        return;
    }
    for (auto _ : state) {
        auto r = decompress(*frame);
        if (!r || *r != text) state.SkipWithError("round trip failed");
    }
    state.SetLabel(corpus_name(static_cast<int>(state.range(0))));
    state.counters["steps/s"] = benchmark::Counter(static_cast<double>(count_steps(chains)),
                                                   benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_Decompress)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);

// Payload layouts: bits/step after zstd at the given level, for each variant.
void BM_PayloadLayouts(benchmark::State& state) {
    const int which = static_cast<int>(state.range(0));
    const int level = static_cast<int>(state.range(1));
    const auto& chains = corpus(which);
    const Profile p = which == 1 ? Profile::grbl : Profile::eval8;
    Block block;
    block.chains = chains;
    std::vector<std::vector<Segment>> segs(chains.size());
    for (std::size_t i = 0; i < chains.size(); ++i)
        (void)segment_steps(chains[i].steps, 2, p, SegmenterKind::greedy, segs[i]);
    std::size_t nseg = 0;
    for (const auto& s : segs) nseg += s.size();
    const double steps = static_cast<double>(count_steps(chains));
    auto bits = [&](std::string_view raw) {
        std::string z(ZSTD_compressBound(raw.size()), '\0');
        const std::size_t n = ZSTD_compress(z.data(), z.size(), raw.data(), raw.size(), level);
        return 8.0 * static_cast<double>(n) / steps;
    };
    stz::PayloadVariant v;
    for (auto _ : state) {
        v = {};
        state.counters["records"] = bits(stz::write_chain_payload(block, p, segs, v));
        v.interleaved = false;
        state.counters["streams"] = bits(stz::write_chain_payload(block, p, segs, v));
        v = {};
        v.start_from_end = false;
        state.counters["from_start"] = bits(stz::write_chain_payload(block, p, segs, v));
        v = {};
        v.octant_delta = false;
        state.counters["abs_octant"] = bits(stz::write_chain_payload(block, p, segs, v));
        Block heads = block;
        for (auto& c : heads.chains) c.steps.clear();
        std::vector<std::vector<Segment>> none(chains.size());
        state.counters["heads_only"] = bits(stz::write_chain_payload(heads, p, none));
        state.counters["text_zstd"] = bits(corpus::freeman_text(chains));
    }
    state.counters["seg/step"] = static_cast<double>(nseg) / steps;
    state.SetLabel(std::string(corpus_name(which)) + " L" + std::to_string(level));
}
BENCHMARK(BM_PayloadLayouts)->ArgsProduct({{0, 1, 2}, {3, 19}})->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace
