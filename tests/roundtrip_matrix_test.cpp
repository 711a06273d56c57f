// The round-trip matrix: decompress(compress(x)) == x over every profile
// (auto and the five named ones) x segmenter (greedy, optimal, patent) x
// input format (freeman, points, steps) x axes (2..6 where the format and the
// profile take them) x level (1, the default 3, 19) x threads (1 and 2, which
// must give identical bytes), on random chains and on chains from corpora/.
//
// Every combination runs on a small input (a few thousand steps, several
// chains and blocks). The large inputs (up to 10^5 steps: corpus files and
// random chains) run on a sample: one (segmenter, level) per profile,
// format and axis count, chosen by rotation so that every segmenter and
// level meets every profile and format. STEPZIP_MATRIX_FULL=1 runs every
// combination on the large inputs too (the `long` ctest label, a CI stage of
// its own: it takes several minutes).
//
// Besides the bytes, each case checks what the frame says about itself
// (profile, segmenter, axes, steps, chains) and that no segmenter fell back
// (src/segment/internal.hpp).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include "../src/segment/internal.hpp"
#include "../src/container/memory_io.hpp"
#include "stepzip/container.hpp"
#include "stepzip/document.hpp"

namespace stepzip {
namespace {

namespace fs = std::filesystem;

constexpr int kLevels[] = {1, 3, 19};
constexpr SegmenterKind kSegmenters[] = {SegmenterKind::greedy, SegmenterKind::optimal,
                                         SegmenterKind::patent};
constexpr InputFormat kFormats[] = {InputFormat::freeman, InputFormat::points, InputFormat::steps};

int max_axes(InputFormat f) {
    switch (f) {
        case InputFormat::freeman: return 2;
        case InputFormat::steps: return 4;  // one byte per tick: axes 0-3
        default: return 6;
    }
}

bool full_matrix() {
    const char* v = std::getenv("STEPZIP_MATRIX_FULL");
    return v != nullptr && std::string(v) == "1";
}

std::string slurp(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}

Step random_step(std::mt19937_64& rng, bool four, int axes) {
    Step s = 0;
    do {
        int d[kMaxAxes] = {};
        if (four) {
            d[rng() % static_cast<unsigned>(axes)] = rng() % 2 ? 1 : -1;
        } else {
            for (int a = 0; a < axes; ++a) d[a] = static_cast<int>(rng() % 3) - 1;
        }
        s = make_step(d, axes);
    } while (s == 0);
    return s;
}

// Random chains of `total` steps in all: runs of one direction (so segments
// are longer than a step), lines of two alternating directions (digital
// straight lines, as a controller draws them) and single turns.
std::vector<Chain> random_chains(std::uint64_t seed, std::size_t total, std::size_t chains,
                                 bool four, int axes) {
    std::mt19937_64 rng(seed);
    std::vector<Chain> out;
    for (std::size_t i = 0; i < chains; ++i) {
        Chain c;
        c.axes = axes;
        for (int a = 0; a < axes; ++a) c.start[a] = static_cast<std::int64_t>(rng() % 20001) - 10000;
        const std::size_t n = total / chains;
        while (c.steps.size() < n) {
            const Step a = random_step(rng, four, axes);
            const Step b = random_step(rng, four, axes);
            const std::size_t len = 1 + rng() % 40;
            switch (rng() % 3) {
                case 0: c.steps.insert(c.steps.end(), len, a); break;
                case 1: {  // a line: b every `every` steps
                    const std::size_t every = 1 + rng() % 5;
                    for (std::size_t k = 0; k < len; ++k) c.steps.push_back(k % every == every - 1 ? b : a);
                    break;
                }
                default: c.steps.push_back(a);
            }
        }
        c.steps.resize(n);
        out.push_back(std::move(c));
    }
    return out;
}

// The chains of a corpus file, cut to at most `limit` steps.
std::vector<Chain> corpus_chains(const char* rel, InputFormat f, std::size_t limit) {
    const std::string text = slurp(fs::path(STEPZIP_SOURCE_DIR) / "corpora" / rel);
    EXPECT_FALSE(text.empty()) << rel;
    auto chains = read_chains(f, text, rel);
    EXPECT_TRUE(chains.ok()) << rel << ": " << (chains.ok() ? "" : chains.error().message);
    std::vector<Chain> out;
    if (!chains.ok()) return out;
    std::size_t total = 0;
    for (Chain& c : *chains) {
        if (total >= limit) break;
        if (c.steps.size() > limit - total) c.steps.resize(limit - total);
        total += c.steps.size();
        out.push_back(std::move(c));
    }
    return out;
}

// Chains -> the text of `format`: the steps format holds one chain from the
// origin, so there the chains are joined end to end.
std::string render(InputFormat format, const std::vector<Chain>& chains, int axes) {
    std::vector<Chain> in = chains;
    for (Chain& c : in) c.axes = axes;
    if (format == InputFormat::steps) {
        Chain one;
        one.axes = axes;
        for (const Chain& c : in) one.steps.insert(one.steps.end(), c.steps.begin(), c.steps.end());
        in = {one};
    }
    auto t = write_chains(format, in);
    EXPECT_TRUE(t.ok()) << (t.ok() ? "" : t.error().message);
    return t.ok() ? *t : std::string();
}

struct Input {
    std::string name;
    std::string text;
    std::size_t steps = 0;
    std::size_t chains = 0;
};

Input make_input(std::string name, InputFormat format, const std::vector<Chain>& chains, int axes) {
    Input in;
    in.name = std::move(name);
    in.text = render(format, chains, axes);
    for (const Chain& c : chains) in.steps += c.steps.size();
    in.chains = format == InputFormat::steps ? 1 : chains.size();
    return in;
}

// Inputs for one (format, axes, connectivity): a small random one, and
// large ones (corpus chains where corpora/ has them, random otherwise).
struct Inputs {
    Input small;
    std::vector<Input> large;
};

const Inputs& inputs_for(InputFormat format, int axes, bool four) {
    static std::map<std::tuple<int, int, bool>, Inputs> cache;
    const auto key = std::make_tuple(static_cast<int>(format), axes, four);
    if (auto it = cache.find(key); it != cache.end()) return it->second;
    Inputs in;
    const std::uint64_t seed = 1000 * static_cast<std::uint64_t>(format) + 10 * static_cast<std::uint64_t>(axes) + four;
    in.small = make_input("random 3000 steps", format, random_chains(seed, 3000, 6, four, axes), axes);
    constexpr std::size_t kLarge = 100000;
    if (axes == 2) {
        in.large.push_back(make_input(four ? "corpora/random/walk-4.fc" : "corpora/random/walk-8.fc", format,
                                      corpus_chains(four ? "random/walk-4.fc" : "random/walk-8.fc",
                                                    InputFormat::freeman, kLarge),
                                      axes));
        in.large.push_back(make_input(four ? "corpora/plotter/hershey-eval4.fc" : "corpora/plotter/hershey-grbl.fc",
                                      format,
                                      corpus_chains(four ? "plotter/hershey-eval4.fc" : "plotter/hershey-grbl.fc",
                                                    InputFormat::freeman, kLarge),
                                      axes));
    } else if (axes == 4 && !four) {
        in.large.push_back(make_input("corpora/stepper/engrave-4axis.steps", format,
                                      corpus_chains("stepper/engrave-4axis.steps", InputFormat::steps, kLarge),
                                      axes));
    } else {
        in.large.push_back(make_input("random 10^5 steps", format, random_chains(seed + 1, kLarge, 40, four, axes), axes));
    }
    return cache.emplace(key, std::move(in)).first->second;
}

Result<FrameInfo> inspect(const std::string& frame) {
    return inspect_stream(stz::memory_reader(frame), "matrix");
}

struct Case {
    std::optional<Profile> profile;
    SegmenterKind segmenter;
    InputFormat format;
    int axes;
    int level;
};

std::string describe(const Case& c, const Input& in) {
    std::ostringstream s;
    s << (c.profile ? profile_name(*c.profile) : "auto") << " / " << segmenter_name(c.segmenter) << " / "
      << format_name(c.format) << " / " << c.axes << " axes / level " << c.level << " / " << in.name;
    return s.str();
}

// One cell: compress with 1 and 2 threads (identical bytes), decompress
// (identical input), the frame's own account of itself.
void run_case(const Case& c, const Input& in, std::size_t block_steps) {
    const std::string what = describe(c, in);
    SCOPED_TRACE(what);
    const std::uint64_t fallbacks = segmenter_fallbacks();
    CompressOptions opt;
    opt.profile = c.profile;
    opt.segmenter = c.segmenter;
    opt.format = c.format;
    opt.level = c.level;
    opt.block_steps = block_steps;
    opt.threads = 1;
    auto one = compress(in.text, opt);
    ASSERT_TRUE(one.ok()) << one.error().message;
    opt.threads = 2;
    auto two = compress(in.text, opt);
    ASSERT_TRUE(two.ok()) << two.error().message;
    EXPECT_TRUE(*one == *two) << "threads 1 and 2 give different bytes";
    auto back = decompress(*two, "matrix");
    ASSERT_TRUE(back.ok()) << back.error().message;
    EXPECT_TRUE(*back == in.text) << "decompress(compress(x)) != x";
    auto info = inspect(*one);
    ASSERT_TRUE(info.ok()) << info.error().message;
    if (c.profile) EXPECT_EQ(info->profile, *c.profile);
    EXPECT_EQ(info->segmenter, c.segmenter);
    EXPECT_EQ(info->format, c.format);
    EXPECT_EQ(info->decoded_bytes, in.text.size());
    if (info->raw_blocks == 0) {  // raw blocks carry bytes, not counted chains
        EXPECT_EQ(info->axes, c.axes);
        EXPECT_EQ(info->steps, in.steps);
        EXPECT_EQ(info->chains, in.chains);
    }
    EXPECT_EQ(segmenter_fallbacks(), fallbacks) << "a segmenter fell back";
}

// Does the cell exist? eval4 and patent take two axes and 4-connected
// chains; the patent segmenter reads two-axis 4-connected chains.
bool valid(std::optional<Profile> p, SegmenterKind k, int axes) {
    if (p && axes > profile_max_axes(*p)) return false;
    if (k == SegmenterKind::patent && axes != 2) return false;
    return true;
}
bool needs_four(std::optional<Profile> p, SegmenterKind k) {
    return (p && !profile_eight_connected(*p)) || k == SegmenterKind::patent;
}

class RoundTripMatrix : public ::testing::TestWithParam<int> {};

std::optional<Profile> profile_of(int i) {
    if (i == 0) return std::nullopt;
    return kAllProfiles[i - 1];
}

TEST_P(RoundTripMatrix, EveryCombinationOnSmallInputsAndASampleOfLargeOnes) {
    const std::optional<Profile> p = profile_of(GetParam());
    int cells = 0, large = 0;
    std::size_t rotation = static_cast<std::size_t>(GetParam());
    for (InputFormat f : kFormats)
        for (int axes = 2; axes <= max_axes(f); ++axes) {
            if (p && axes > profile_max_axes(*p)) continue;
            for (SegmenterKind k : kSegmenters) {
                if (!valid(p, k, axes)) continue;
                const Inputs& in = inputs_for(f, axes, needs_four(p, k));
                for (int level : kLevels) {
                    run_case({p, k, f, axes, level}, in.small, 700);
                    ++cells;
                    if (full_matrix())
                        for (const Input& big : in.large) {
                            run_case({p, k, f, axes, level}, big, std::size_t{1} << 14);
                            ++large;
                        }
                }
            }
            if (full_matrix()) continue;
            // The sample: one (segmenter, level) of the valid ones for this
            // format and axis count, by rotation, on one of the large inputs.
            std::vector<std::pair<SegmenterKind, int>> options;
            for (SegmenterKind k : kSegmenters)
                if (valid(p, k, axes))
                    for (int level : kLevels) options.emplace_back(k, level);
            ASSERT_FALSE(options.empty());
            const auto [k, level] = options[(rotation * 7) % options.size()];
            const Inputs& in = inputs_for(f, axes, needs_four(p, k));
            run_case({p, k, f, axes, level}, in.large[rotation % in.large.size()], std::size_t{1} << 14);
            ++rotation;
            ++large;
        }
    // Two axes in three formats, three segmenters, three levels; the
    // 8-connected profiles (and auto) also take points on 3..6 axes and
    // steps on 3..4 with greedy and optimal.
    const bool two_axes_only = p && !profile_eight_connected(*p);
    EXPECT_EQ(cells, two_axes_only ? 27 : 27 + 6 * 2 * 3);
    if (!full_matrix()) EXPECT_EQ(large, two_axes_only ? 3 : 9);
}

INSTANTIATE_TEST_SUITE_P(Profiles, RoundTripMatrix, ::testing::Range(0, 6), [](const auto& info) {
    const std::optional<Profile> p = profile_of(info.param);
    return std::string(p ? profile_name(*p) : "auto");
});

}  // namespace
}  // namespace stepzip
