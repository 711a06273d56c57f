// The .stz container's lossless contract: decompress(compress(x)) == x for
// random chains under every profile and segmenter, any block size, any
// thread count (and -T 1 / -T 2 give identical bytes); golden files made by
// earlier versions keep decoding.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "../src/container/memory_io.hpp"
#include "stepzip/container.hpp"
#include "stepzip/document.hpp"
#include "support/files.hpp"

namespace stepzip {
namespace {

// Random chains: `four` = 4-connected; runs of a direction (so segments are
// longer than a step) mixed with turns.
std::vector<Chain> random_chains(std::uint64_t seed, int count, bool four, int axes = 2) {
    std::mt19937_64 rng(seed);
    std::vector<Chain> out;
    for (int i = 0; i < count; ++i) {
        Chain c;
        c.axes = axes;
        for (int a = 0; a < axes; ++a) c.start[a] = static_cast<std::int64_t>(rng() % 200) - 100;
        const int n = static_cast<int>(rng() % 120);
        Step cur = 0;
        for (int k = 0; k < n; ++k) {
            if (cur == 0 || rng() % 4 == 0) {
                do {
                    int d[kMaxAxes] = {};
                    if (four) {
                        d[rng() % axes] = rng() % 2 ? 1 : -1;
                    } else {
                        for (int a = 0; a < axes; ++a) d[a] = static_cast<int>(rng() % 3) - 1;
                    }
                    cur = make_step(d, axes);
                } while (cur == 0);
            }
            c.steps.push_back(cur);
        }
        out.push_back(std::move(c));
    }
    return out;
}

std::string must_text(InputFormat f, const std::vector<Chain>& chains) {
    auto t = write_chains(f, chains);
    EXPECT_TRUE(t.ok()) << (t.ok() ? "" : t.error().message);
    return t.ok() ? *t : std::string();
}

void expect_round_trip(const std::string& input, const CompressOptions& opt, const char* what) {
    auto z = compress(input, opt);
    ASSERT_TRUE(z.ok()) << what << ": " << z.error().message;
    auto back = decompress(*z);
    ASSERT_TRUE(back.ok()) << what << ": " << back.error().message;
    EXPECT_EQ(*back, input) << what;
}

TEST(ContainerRoundTrip, EveryProfileAndSegmenterOnRandomChains) {
    const std::string eight = must_text(InputFormat::freeman, random_chains(1, 40, false));
    const std::string four = must_text(InputFormat::freeman, random_chains(2, 40, true));
    for (Profile p : kAllProfiles)
        for (SegmenterKind k : {SegmenterKind::greedy, SegmenterKind::optimal, SegmenterKind::patent})
            for (std::size_t block : {std::size_t{5}, std::size_t{64}, kDefaultBlockSteps}) {
                CompressOptions opt;
                opt.profile = p;
                opt.segmenter = k;
                opt.block_steps = block;
                opt.allow_raw = false;  // exercise the segment path and its proof
                const std::string what = std::string(profile_name(p)) + "/" +
                                         std::string(segmenter_name(k)) + "/" + std::to_string(block);
                expect_round_trip(four, opt, what.c_str());
                if (profile_eight_connected(p) && k != SegmenterKind::patent)
                    expect_round_trip(eight, opt, what.c_str());  // patent reads 4-connected only
            }
}

TEST(ContainerRoundTrip, NamedFourConnectedProfileRefusesDiagonals) {
    CompressOptions opt;
    opt.profile = Profile::eval4;
    auto z = compress("0 0 0011\n", opt);
    ASSERT_FALSE(z.ok());
    EXPECT_EQ(z.error().code, Errc::connectivity) << z.error().message;
}

TEST(ContainerRoundTrip, AutoProfileAndLevels) {
    const std::string input = must_text(InputFormat::freeman, random_chains(3, 60, false));
    for (int level : {1, 3, 19}) {
        CompressOptions opt;
        opt.level = level;
        opt.block_steps = 300;
        expect_round_trip(input, opt, "auto");
    }
}

TEST(ContainerRoundTrip, ThreadCountDoesNotChangeTheBytes) {
    const std::string input = must_text(InputFormat::freeman, random_chains(4, 200, false));
    CompressOptions opt;
    opt.block_steps = 97;
    opt.threads = 1;
    auto one = compress(input, opt);
    opt.threads = 2;
    auto two = compress(input, opt);
    opt.threads = 5;
    auto five = compress(input, opt);
    ASSERT_TRUE(one.ok() && two.ok() && five.ok());
    EXPECT_EQ(*one, *two);
    EXPECT_EQ(*one, *five);
    auto back = decompress(*two);
    ASSERT_TRUE(back.ok()) << back.error().message;
    EXPECT_EQ(*back, input);
}

TEST(ContainerRoundTrip, EmptyInputAndEmptyChains) {
    expect_round_trip("", {}, "empty");
    CompressOptions opt;
    opt.format = InputFormat::freeman;
    expect_round_trip("3 4\n", opt, "chain without steps");
}

TEST(ContainerRoundTrip, PointsAndStepsFormatsOnSeveralAxes) {
    for (int axes : {2, 3, 4}) {
        // Points: dozens of chains, thousands of steps, over several blocks.
        const auto chains = random_chains(10 + axes, 60, false, axes);
        std::size_t total = 0;
        for (const Chain& c : chains) total += c.steps.size();
        ASSERT_GT(total, 2000u);
        CompressOptions opt;
        opt.format = InputFormat::points;
        opt.block_steps = 500;
        expect_round_trip(must_text(InputFormat::points, chains), opt, "points");
        // Steps: the file is one chain from the origin; these chains joined
        // end to end make a log of thousands of ticks that continues across
        // blocks, coded as chain blocks and with raw blocks allowed.
        Chain joined;
        joined.axes = axes;
        for (const Chain& c : chains) joined.steps.insert(joined.steps.end(), c.steps.begin(), c.steps.end());
        opt.format = InputFormat::steps;
        for (bool raw : {false, true})
            for (std::size_t block : {std::size_t{333}, kDefaultBlockSteps}) {
                opt.allow_raw = raw;
                opt.block_steps = block;
                expect_round_trip(must_text(InputFormat::steps, {joined}), opt, "steps");
            }
    }
}

TEST(ContainerRoundTrip, StepsFormatLogsWithIdleTicksAndDirNoise) {
    // Every byte is a valid tick (docs/formats.md, steps): random logs with
    // runs, idle ticks and DIR changes on resting axes, on 1..4 axes, carry
    // much of themselves in the layout; they must round-trip as they are.
    std::mt19937_64 rng(23);
    for (int axes : {1, 2, 3, 4}) {
        std::string log;
        while (log.size() < 6000) {
            unsigned char tick = 0;
            for (int a = 0; a < axes; ++a) {
                if (rng() % 3 != 0) tick |= static_cast<unsigned char>(1u << (2 * a));
                if (rng() % 2) tick |= static_cast<unsigned char>(2u << (2 * a));
            }
            if (rng() % 11 == 0) tick &= 0xAA;  // an idle tick, DIR levels only
            log.append(1 + rng() % 20, static_cast<char>(tick));
        }
        CompressOptions opt;
        opt.format = InputFormat::steps;
        for (std::size_t block : {std::size_t{400}, kDefaultBlockSteps}) {
            opt.block_steps = block;
            expect_round_trip(log, opt, "steps log");
        }
    }
}

TEST(ContainerRoundTrip, ControllerLinesCostOneSegmentPerVectorWithoutPhase) {
    // Vectors expanded by GRBL's interpolator: one segment per vector under --profile grbl.
    std::mt19937_64 rng(7);
    Chain c;
    int vectors = 0;
    for (int i = 0; i < 50; ++i) {
        Point d{};
        d[0] = static_cast<std::int64_t>(rng() % 400) + 1;
        d[1] = static_cast<std::int64_t>(rng() % 400) - 200;
        if (i % 2) d[0] = -d[0];
        expand_segment(Profile::grbl, default_segment(Profile::grbl, d, 2), 2, c.steps);
        ++vectors;
    }
    const std::string input = must_text(InputFormat::freeman, {c});
    CompressOptions opt;
    opt.profile = Profile::grbl;
    auto z = compress(input, opt);
    ASSERT_TRUE(z.ok()) << z.error().message;
    auto info = inspect_stream(stz::memory_reader(*z));
    ASSERT_TRUE(info.ok()) << info.error().message;
    EXPECT_EQ(info->raw_blocks, 0u);
    EXPECT_EQ(info->chains, 1u);
    EXPECT_EQ(info->steps, c.steps.size());
    EXPECT_LE(info->segments, static_cast<std::uint64_t>(vectors));
    EXPECT_LT(z->size() * 8, c.steps.size() / 4);  // far below a bit per step
}

TEST(ContainerRoundTrip, PatentStatisticsAreStoredInTheFrame) {
    const std::string input = "0 0 02002002000\n0 0 222000\n";
    CompressOptions opt;
    opt.profile = Profile::patent;
    opt.segmenter = SegmenterKind::patent;
    // Count through compress_stream, read back through inspect_stream.
    std::string frame;
    auto made = compress_stream(stz::memory_reader(input), stz::string_writer(frame), opt);
    ASSERT_TRUE(made.ok()) << made.error().message;
    EXPECT_GT(made->stats.patent_segments, 0u);
    auto seen = inspect_stream(stz::memory_reader(frame));
    ASSERT_TRUE(seen.ok()) << seen.error().message;
    EXPECT_EQ(seen->segmenter, SegmenterKind::patent);
    EXPECT_EQ(seen->stats.patent_segments, made->stats.patent_segments);
    EXPECT_EQ(seen->stats.patent_exact, made->stats.patent_exact);
    EXPECT_EQ(seen->stats.patent_max_deviation, made->stats.patent_max_deviation);
    EXPECT_EQ(seen->checksum, made->checksum);
}

// -L 19 implies the optimal segmenter on two-axis frames only; frames of
// more axes are cut greedily (the frame header says so), and a segmenter
// named is used whatever the axes.
TEST(ContainerRoundTrip, LevelNineteenCutsMoreThanTwoAxesGreedily) {
    for (int axes : {2, 3, 4}) {
        Chain joined;
        joined.axes = axes;
        for (const Chain& c : random_chains(20 + axes, 30, false, axes))
            joined.steps.insert(joined.steps.end(), c.steps.begin(), c.steps.end());
        const std::string input = must_text(InputFormat::steps, {joined});
        for (bool named : {false, true}) {
            CompressOptions opt;
            opt.format = InputFormat::steps;
            opt.level = 19;
            if (named) opt.segmenter = SegmenterKind::optimal;
            std::string frame;
            auto made = compress_stream(stz::memory_reader(input), stz::string_writer(frame), opt);
            ASSERT_TRUE(made.ok()) << made.error().message;
            const SegmenterKind want = named || axes == 2 ? SegmenterKind::optimal : SegmenterKind::greedy;
            EXPECT_EQ(made->segmenter, want) << axes << (named ? " named" : "");
            auto seen = inspect_stream(stz::memory_reader(frame));
            ASSERT_TRUE(seen.ok()) << seen.error().message;
            EXPECT_EQ(seen->segmenter, want) << axes << (named ? " named" : "");
            auto back = decompress(frame);
            ASSERT_TRUE(back.ok()) << back.error().message;
            EXPECT_EQ(*back, input) << axes;
        }
    }
}

using test::slurp;

TEST(ContainerGolden, EveryGoldenFileDecodesToItsOriginal) {
    // tests/golden/NAME.stz (format version 1) and tests/golden/v2/NAME.stz
    // (version 2); the original is next to the .stz file or, for v2/, in
    // tests/golden/.
    const std::filesystem::path dir = std::filesystem::path(STEPZIP_SOURCE_DIR) / "tests" / "golden";
    int seen[3] = {0, 0, 0};
    for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
        if (e.path().extension() != ".stz") continue;
        std::filesystem::path original = e.path();
        original.replace_extension();
        if (!std::filesystem::exists(original)) original = dir / original.filename();
        ASSERT_TRUE(std::filesystem::exists(original)) << original;
        const std::string frame = slurp(e.path());
        auto back = decompress(frame, e.path().filename().string());
        ASSERT_TRUE(back.ok()) << e.path() << ": " << back.error().message;
        EXPECT_EQ(*back, slurp(original)) << e.path();
        ASSERT_GT(frame.size(), 4u);
        const int version = frame[4];
        ASSERT_TRUE(version == 1 || version == 2) << e.path();
        EXPECT_EQ(e.path().parent_path().filename() == "v2", version == 2) << e.path();
        ++seen[version];
    }
    EXPECT_GE(seen[1], 5);
    EXPECT_GE(seen[2], 8);
}

}  // namespace
}  // namespace stepzip
