// Container benchmarks: encode and decode speed (steps/s) and the payload
// layout measurements quoted in docs/FORMAT.md ("Rationale"), reported as
// bits/step counters. Run: build/bench/container_bench
#include <benchmark/benchmark.h>
#include <zstd.h>

#include <string>
#include <vector>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "../src/container/bench_hooks.hpp"
#include "../src/container/block_codec.hpp"
#include "../src/container/modeled_block.hpp"
#include "container_corpus.hpp"
#include "stepzip/container.hpp"
#include "stepzip/segment/block_cut.hpp"
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
        state.counters["records"] = bits(stz::write_chain_payload(block, p, segs));
        v.interleaved = false;
        state.counters["streams"] = bits(stz::write_chain_payload_variant(block, p, segs, v));
        v = {};
        v.start_from_end = false;
        state.counters["from_start"] = bits(stz::write_chain_payload_variant(block, p, segs, v));
        v = {};
        v.octant_delta = false;
        state.counters["abs_octant"] = bits(stz::write_chain_payload_variant(block, p, segs, v));
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

// The block encodings on the real corpora (docs/FORMAT.md "Rationale"):
// bytes of the first block of each file under the profile `--profile auto`
// would pick for it, greedy segmenter, level 3: segment records + zstd,
// segment model (segmenter's cut, default-phase cut), step model, and the
// decoding time of the whole frame. Run from the source root (or set
// STEPZIP_CORPORA): build/bench/container_bench --benchmark_filter=Corpus
const char* const kCorpusFiles[] = {
    "plotter/gnuplot-eval4.fc", "plotter/gnuplot-grbl.fc", "plotter/hershey-eval4.fc",
    "plotter/hershey-grbl.fc",  "plotter/hershey-patent.fc", "glyphs/dejavu-4.fc",
    "glyphs/dejavu-8.fc",       "random/walk-4.fc",        "random/walk-8.fc"};

void BM_CorpusEncodings(benchmark::State& state) {
    const char* rel = kCorpusFiles[state.range(0)];
    const char* dir = std::getenv("STEPZIP_CORPORA");  // default: run from the source root
    std::ifstream f(std::string(dir ? dir : "corpora") + "/" + rel, std::ios::binary);
    std::ostringstream ss;
    ss << f.rdbuf();
    const std::string text = ss.str();
    BlockReader reader(InputFormat::freeman, rel);
    Block block;
    if (!reader.feed(text, true) || !reader.next(block)) {
        state.SkipWithError("cannot read the corpus file");
        return;
    }
    auto frame = compress(text);
    if (!frame) {
        state.SkipWithError(frame.error().message.c_str());
        return;
    }
    // Frame header byte 5, bits 0-2: the profile (docs/FORMAT.md 1.1).
    const Profile p = static_cast<Profile>(static_cast<unsigned char>((*frame)[5]) & 7u);
    std::vector<std::vector<Segment>> segs, aligned;
    (void)cut_block(block.chains, 2, p, BlockCut::greedy, segs);
    const bool aligned_ok = cut_block(block.chains, 2, p, BlockCut::default_phase, aligned).ok();
    for (auto _ : state) {
        auto r = decompress(*frame);
        if (!r || *r != text) state.SkipWithError("round trip failed");
    }
    state.counters["records"] = static_cast<double>(
        stz::make_block_record(stz::kChains, 0, stz::write_chain_payload(block, p, segs), 3).size());
    state.counters["seg_model"] = static_cast<double>(stz::write_segment_model(block, p, segs).size());
    if (aligned_ok)
        state.counters["seg_aligned"] = static_cast<double>(stz::write_segment_model(block, p, aligned).size());
    state.counters["step_model"] = static_cast<double>(stz::write_step_model(block).size());
    // Bytes per field of the segment model (default-phase cut when there is one).
    const auto costs = stz::segment_model_costs(block, p, aligned_ok ? aligned : segs);
    for (int f = 0; f < stz::kSegmentModelFields; ++f)
        state.counters[std::string("seg_") + stz::kSegmentModelFieldNames[f]] = costs[f] / 8;
    state.counters["frame"] = static_cast<double>(frame->size());
    state.SetLabel(std::string(rel) + " " + std::string(profile_name(p)));
}
BENCHMARK(BM_CorpusEncodings)->DenseRange(0, 8)->Unit(benchmark::kMillisecond);

}  // namespace
