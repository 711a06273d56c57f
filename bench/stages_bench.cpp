// Per-stage speed, in time per step next to memcpy of the same bytes (the
// physical limit): parsing of freeman text, points text and STEP/DIR bytes,
// segmentation (greedy and default-phase cut), expansion of the segments
// into steps under every profile (appended to a vector, and written into
// the chain's buffer as the table block's decoder does), rendering back to text/bytes, and the
// whole compress/decompress pipeline. Inputs are built from the files of
// corpora/ (run from the source root, or set STEPZIP_CORPORA):
//   text8 / text4: the 8-connected / 4-connected freeman files concatenated
//     (about 1.4 M steps each), "freeman" the eleven files repeated to
//     about 8 MB, "points" the same chains once as points text, "steps"
//     corpora/stepper/engrave-4axis.steps repeated to about 8 MB.
// Every benchmark reports `per_step` (seconds per step; "2.5n" = 2.5 ns),
// `steps/s` and bytes/s of the bytes it reads or writes. Run:
//   build/bench/stages_bench --benchmark_min_time=0.3
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../src/interpolate/expand_into.hpp"
#include "stepzip/container.hpp"
#include "stepzip/document.hpp"
#include "stepzip/interpolate/segment.hpp"
#include "stepzip/segment/block_cut.hpp"

namespace {

using namespace stepzip;

std::string slurp(const std::string& rel) {
    const char* dir = std::getenv("STEPZIP_CORPORA");
    std::ifstream f(std::string(dir ? dir : "corpora") + "/" + rel, std::ios::binary);
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}

const char* const kFiles8[] = {"glyphs/dejavu-8.fc",      "plotter/gnuplot-grbl.fc",
                               "plotter/hershey-eval8.fc", "plotter/hershey-grbl.fc",
                               "plotter/hershey-marlin.fc", "random/walk-8.fc"};
const char* const kFiles4[] = {"glyphs/dejavu-4.fc", "plotter/gnuplot-eval4.fc",
                               "plotter/hershey-eval4.fc", "plotter/hershey-patent.fc",
                               "random/walk-4.fc"};

struct Input {
    InputFormat format = InputFormat::freeman;
    std::string bytes;
    std::vector<Block> blocks;  // as the reader cuts it
    std::size_t steps = 0;
    std::string error;
};

void parse_all(Input& in) {
    BlockReader reader(in.format, "bench");
    if (auto r = reader.feed(in.bytes, true); !r) {
        in.error = r.error().message;
        return;
    }
    Block b;
    while (reader.next(b)) {
        for (const Chain& c : b.chains) in.steps += c.steps.size();
        in.blocks.push_back(std::move(b));
        b = Block{};
    }
    if (in.steps == 0) in.error = "no steps read (run from the source root or set STEPZIP_CORPORA)";
}

Input make_input(InputFormat f, std::string bytes) {
    Input in;
    in.format = f;
    in.bytes = std::move(bytes);
    parse_all(in);
    return in;
}

std::string concat(const char* const* files, std::size_t n) {
    std::string s;
    for (std::size_t i = 0; i < n; ++i) s += slurp(files[i]);
    return s;
}

std::string repeat_to(const std::string& s, std::size_t bytes) {
    std::string r;
    if (s.empty()) return r;
    while (r.size() < bytes) r += s;
    return r;
}

// Inputs: 0 freeman (~8 MB), 1 points, 2 steps (~8 MB), 3 text8, 4 text4.
const Input& input(int which) {
    static const Input in[5] = {
        make_input(InputFormat::freeman,
                   repeat_to(concat(kFiles8, std::size(kFiles8)) + concat(kFiles4, std::size(kFiles4)),
                             8u << 20)),
        [] {
            const std::string all = concat(kFiles8, std::size(kFiles8)) + concat(kFiles4, std::size(kFiles4));
            auto chains = read_chains(InputFormat::freeman, all);
            auto text = chains ? write_chains(InputFormat::points, *chains) : Result<std::string>(chains.error());
            return make_input(InputFormat::points, text ? *text : std::string());
        }(),
        make_input(InputFormat::steps, repeat_to(slurp("stepper/engrave-4axis.steps"), 8u << 20)),
        make_input(InputFormat::freeman, concat(kFiles8, std::size(kFiles8))),
        make_input(InputFormat::freeman, concat(kFiles4, std::size(kFiles4))),
    };
    return in[which];
}

const char* const kInputNames[] = {"freeman", "points", "steps", "text8", "text4"};

void counters(benchmark::State& state, std::size_t steps, std::size_t bytes) {
    const auto it = static_cast<double>(state.iterations());
    state.counters["per_step"] = benchmark::Counter(static_cast<double>(steps) * it,
                                                    benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    state.counters["steps/s"] = benchmark::Counter(static_cast<double>(steps) * it, benchmark::Counter::kIsRate);
    state.SetBytesProcessed(static_cast<std::int64_t>(bytes * state.iterations()));
}

bool usable(benchmark::State& state, const Input& in) {
    if (!in.error.empty()) {
        state.SkipWithError(in.error.c_str());
        return false;
    }
    return true;
}

// The physical limit: memcpy of an input's bytes (arg 0..4 as input()), or
// of its steps as the 2-byte Step array the stages pass on (arg + 10).
void BM_Memcpy(benchmark::State& state) {
    const bool as_steps = state.range(0) >= 10;
    const Input& in = input(static_cast<int>(state.range(0) % 10));
    if (!usable(state, in)) return;
    const std::size_t n = as_steps ? in.steps * sizeof(Step) : in.bytes.size();
    std::vector<char> src(n, 1), dst(n);
    if (!as_steps) std::memcpy(src.data(), in.bytes.data(), n);
    for (auto _ : state) {
        std::memcpy(dst.data(), src.data(), n);
        benchmark::DoNotOptimize(dst.data());
        benchmark::ClobberMemory();
    }
    counters(state, in.steps, n);
    state.SetLabel(std::string(kInputNames[state.range(0) % 10]) + (as_steps ? " Step array" : " bytes"));
}
BENCHMARK(BM_Memcpy)->Arg(0)->Arg(1)->Arg(2)->Arg(13)->Arg(14)->Unit(benchmark::kMillisecond);

// Parsing: the reader fed in 1 MiB pieces as the compressor feeds it,
// blocks drained as they come.
void BM_Parse(benchmark::State& state) {
    const Input& in = input(static_cast<int>(state.range(0)));
    if (!usable(state, in)) return;
    for (auto _ : state) {
        BlockReader reader(in.format, "bench");
        Block b;
        std::size_t steps = 0;
        for (std::size_t pos = 0; pos < in.bytes.size(); pos += 1 << 20) {
            const std::string_view piece = std::string_view(in.bytes).substr(pos, 1 << 20);
            if (!reader.feed(piece, pos + piece.size() == in.bytes.size())) state.SkipWithError("parse");
            while (reader.next(b))
                for (const Chain& c : b.chains) steps += c.steps.size();
        }
        benchmark::DoNotOptimize(steps);
    }
    counters(state, in.steps, in.bytes.size());
    state.SetLabel(kInputNames[state.range(0)]);
}
BENCHMARK(BM_Parse)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);

// Rendering: the parsed blocks written back to the identical bytes.
void BM_Render(benchmark::State& state) {
    const Input& in = input(static_cast<int>(state.range(0)));
    if (!usable(state, in)) return;
    BlockWriter writer(in.format);
    std::string out;
    out.reserve(in.bytes.size());
    for (auto _ : state) {
        out.clear();
        for (const Block& b : in.blocks)
            if (!writer.write(b, out)) state.SkipWithError("render");
        benchmark::DoNotOptimize(out.data());
    }
    if (out != in.bytes) state.SkipWithError("rendering differs from the input");
    counters(state, in.steps, out.size());
    state.SetLabel(kInputNames[state.range(0)]);
}
BENCHMARK(BM_Render)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);

// The chains of text8 (8-connected profiles) or text4 (eval4, patent).
const Input& chains_for(Profile p) { return input(profile_eight_connected(p) ? 3 : 4); }

std::vector<std::vector<Segment>> cut_all(const Input& in, Profile p, BlockCut kind, std::string& error) {
    std::vector<std::vector<Segment>> all;
    for (const Block& b : in.blocks) {
        std::vector<std::vector<Segment>> segs;
        if (auto r = cut_block(b.chains, b.axes, p, kind, segs); !r) {
            error = r.error().message;
            return {};
        }
        for (auto& s : segs) all.push_back(std::move(s));
    }
    return all;
}

// Segmentation: every chain cut into exact segments (args: profile, cut).
void BM_Segment(benchmark::State& state) {
    const auto p = static_cast<Profile>(state.range(0));
    const auto kind = static_cast<BlockCut>(state.range(1));
    const Input& in = chains_for(p);
    if (!usable(state, in)) return;
    std::vector<std::vector<Segment>> segs;
    std::size_t nsegs = 0;
    for (auto _ : state) {
        nsegs = 0;
        for (const Block& b : in.blocks) {
            segs.clear();
            if (auto r = cut_block(b.chains, b.axes, p, kind, segs); !r) {
                state.SkipWithError(r.error().message.c_str());
                return;
            }
            for (const auto& s : segs) nsegs += s.size();
        }
        benchmark::DoNotOptimize(nsegs);
    }
    counters(state, in.steps, in.steps * sizeof(Step));
    state.counters["steps/segment"] = static_cast<double>(in.steps) / static_cast<double>(nsegs);
    state.SetLabel(std::string(profile_name(p)) +
                   (kind == BlockCut::greedy ? " greedy" : kind == BlockCut::default_phase ? " default-phase" : " optimal"));
}
BENCHMARK(BM_Segment)
    ->Args({0, 0})
    ->Args({1, 0})
    ->Args({2, 0})
    ->Args({3, 0})
    ->Args({4, 0})
    ->Args({1, 3})
    ->Args({3, 3})
    ->Args({4, 3})
    ->Unit(benchmark::kMillisecond);

// Expansion: the greedy segments of every chain expanded back into steps,
// one chain at a time (args: profile; 0: appended to a reused vector by
// expand_segment, 1: written straight into the chain's buffer as the table
// block's decoder does it, detail::expand_segment_into, a segment without
// a fast path through expand_segment and a copy).
void BM_Expand(benchmark::State& state) {
    const auto p = static_cast<Profile>(state.range(0));
    const bool into = state.range(1) != 0;
    const Input& in = chains_for(p);
    if (!usable(state, in)) return;
    std::string error;
    const auto segs = cut_all(in, p, BlockCut::greedy, error);
    if (!error.empty()) {
        state.SkipWithError(error.c_str());
        return;
    }
    std::size_t nsegs = 0;
    for (const auto& s : segs) nsegs += s.size();
    const bool eight = profile_eight_connected(p);
    std::vector<Step> out, spill;
    if (into) out.resize(in.steps);
    else out.reserve(1 << 20);
    std::size_t steps = 0;
    for (auto _ : state) {
        steps = 0;
        for (const auto& chain : segs) {
            if (!into) {
                out.clear();
                for (const Segment& s : chain) expand_segment(p, s, 2, out);
                steps += out.size();
            } else {
                Step* o = out.data();
                for (const Segment& s : chain) {
                    const auto n = static_cast<std::size_t>(segment_length(s.delta, 2, eight));
                    if (!detail::expand_segment_into(p, s, 2, o)) {
                        spill.clear();
                        expand_segment(p, s, 2, spill);
                        std::memcpy(o, spill.data(), n * sizeof(Step));
                    }
                    o += n;
                }
                steps += static_cast<std::size_t>(o - out.data());
            }
            benchmark::DoNotOptimize(out.data());
        }
    }
    if (steps != in.steps) state.SkipWithError("expansion gives another step count");
    counters(state, in.steps, in.steps * sizeof(Step));
    state.counters["steps/segment"] = static_cast<double>(in.steps) / static_cast<double>(nsegs);
    state.SetLabel(std::string(profile_name(p)) + (into ? " into the chain's buffer" : ""));
}
BENCHMARK(BM_Expand)->ArgsProduct({{0, 1, 2, 3, 4}, {0, 1}})->Unit(benchmark::kMillisecond);

// The whole pipeline in memory, one thread (args: input text8/text4, level).
void BM_Compress(benchmark::State& state) {
    const Input& in = input(static_cast<int>(state.range(0)));
    if (!usable(state, in)) return;
    CompressOptions opt;
    opt.level = static_cast<int>(state.range(1));
    opt.threads = 1;
    std::size_t size = 0;
    for (auto _ : state) {
        auto z = compress(in.bytes, opt);
        if (!z) {
            state.SkipWithError(z.error().message.c_str());
            return;
        }
        size = z->size();
    }
    counters(state, in.steps, in.bytes.size());
    state.counters["bits/step"] = 8.0 * static_cast<double>(size) / static_cast<double>(in.steps);
    state.SetLabel(std::string(kInputNames[state.range(0)]) + " -L " + std::to_string(state.range(1)));
}
BENCHMARK(BM_Compress)->ArgsProduct({{3, 4}, {1, 3}})->Unit(benchmark::kMillisecond);

void BM_Decompress(benchmark::State& state) {
    const Input& in = input(static_cast<int>(state.range(0)));
    if (!usable(state, in)) return;
    CompressOptions opt;
    opt.level = static_cast<int>(state.range(1));
    opt.threads = 1;
    const auto z = compress(in.bytes, opt);
    if (!z) {
        state.SkipWithError(z.error().message.c_str());
        return;
    }
    for (auto _ : state) {
        auto d = decompress(*z);
        if (!d || d->size() != in.bytes.size()) {
            state.SkipWithError("decompress");
            return;
        }
        benchmark::DoNotOptimize(d->data());
    }
    counters(state, in.steps, in.bytes.size());
    state.SetLabel(std::string(kInputNames[state.range(0)]) + " -L " + std::to_string(state.range(1)));
}
BENCHMARK(BM_Decompress)->ArgsProduct({{3, 4}, {1, 3}})->Unit(benchmark::kMillisecond);

}  // namespace
