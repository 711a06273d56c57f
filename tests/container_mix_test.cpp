// Block type 6, mixed predictions (docs/FORMAT.md 1.11): the squash and
// stretch tables follow their definitions; both models round-trip with
// mixed predictions, with and without a window, and the decoder errors name
// the payload byte; the payload bytes of small fixed inputs are pinned; the
// strong levels write type 6 blocks only where they are smaller, and the
// frames decode; the sample that decides whether a large block tries the
// mixed step model; -L 19's cut (optimal on chains of short segments,
// greedy on long lines) round-trips; the hashed tables a thread keeps
// between predictors come back all zero, and a predictor made while they
// are taken predicts the same; the profile ranking's trial of the first
// block gives the bytes the block's own choice gives.
#include <gtest/gtest.h>

#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "../src/container/block_codec.hpp"
#include "../src/container/encoder.hpp"
#include "../src/container/memory_io.hpp"
#include "../src/container/mix.hpp"
#include "../src/container/modeled_block.hpp"
#include "../src/container/window.hpp"
#include "stepzip/container.hpp"
#include "stepzip/document.hpp"
#include "stepzip/segmenter.hpp"
#include "support/pinned_bytes.hpp"

namespace stepzip::stz {
namespace {

using test::fixed_block;
using test::greedy_cut;
using test::hex;

// Closed contours (squares and diamonds of random sizes, some repeated) and
// plotter-like strokes, from a fixed seed.
std::string contours(std::uint64_t seed, int count) {
    std::mt19937_64 rng(seed);
    std::vector<Chain> chains;
    for (int i = 0; i < count; ++i) {
        Chain c;
        c.axes = 2;
        c.start = {static_cast<std::int64_t>(rng() % 500), static_cast<std::int64_t>(rng() % 500)};
        if (rng() % 3 != 0) {
            const int a = 2 + static_cast<int>(rng() % 9), b = 2 + static_cast<int>(rng() % 9);
            const int base = static_cast<int>(rng() % 2);  // 0: square, 1: diamond
            for (int side = 0; side < 4; ++side)
                for (int k = 0; k < (side % 2 ? b : a); ++k) c.steps.push_back(freeman_to_step(base + 2 * side));
        } else {
            int code = static_cast<int>(rng() % 8);
            const int n = 10 + static_cast<int>(rng() % 40);
            for (int k = 0; k < n; ++k) {
                if (rng() % 5 == 0) code = (code + 1 + static_cast<int>(rng() % 7)) % 8;
                c.steps.push_back(freeman_to_step(code));
            }
        }
        chains.push_back(std::move(c));
    }
    auto t = write_chains(InputFormat::freeman, chains);
    EXPECT_TRUE(t.ok());
    return t.ok() ? *t : std::string();
}

TEST(MixTables, SquashFollowsItsPointsAndStretchInvertsIt) {
    EXPECT_EQ(mixdetail::squash(0), 32768);
    EXPECT_EQ(mixdetail::squash(-2048), mixdetail::squash(-2047));  // clamped
    EXPECT_EQ(mixdetail::squash(5000), mixdetail::squash(2047));
    // Between two points: the linear interpolation, rounded.
    EXPECT_EQ(mixdetail::squash(64), (32768 * 64 + 40793 * 64 + 64) >> 7);
    for (std::int32_t x = -2047; x < 2047; ++x) ASSERT_LE(mixdetail::squash(x), mixdetail::squash(x + 1)) << x;
    // stretch(p): the smallest x whose squash reaches p's 12-bit bucket.
    for (std::uint32_t p = 1; p < 65536; p += 7) {
        const std::int32_t x = stretch(p);
        if (x < 2047) EXPECT_GE(mixdetail::squash(x) >> 4, static_cast<std::int32_t>(p >> 4)) << p;
        if (x > -2047) EXPECT_LT(mixdetail::squash(x - 1) >> 4, static_cast<std::int32_t>(p >> 4)) << p;
    }
    EXPECT_EQ(stretch(32768), 0);
}

TEST(MixedModels, SegmentModelRoundTripsWithAndWithoutWindow) {
    const Block first = fixed_block(contours(1, 60)), b = fixed_block(contours(2, 60));
    const auto cut_first = greedy_cut(first, Profile::eval8), cut = greedy_cut(b, Profile::eval8);
    auto w = std::make_shared<WindowBlock>();
    w->items = segment_items(first, cut_first);
    const WindowView window{w};
    for (const WindowView* view : {static_cast<const WindowView*>(nullptr), &window}) {
        const std::string payload = write_segment_model(b, Profile::eval8, cut, view, false, true);
        ASSERT_FALSE(payload.empty());
        EXPECT_EQ(static_cast<unsigned char>(payload[0]), kMixedSegment | kMixedCurvature);
        Block out;
        BlockCounts counts;
        auto r = read_segment_model(payload, Profile::eval8, 2, true, out, counts, "t", view, nullptr, false, true);
        ASSERT_TRUE(r.ok()) << r.error().message;
        EXPECT_EQ(out.chains, b.chains);
        // Read as a type 3 payload, the same bytes do not decode to the block.
        Block plain;
        BlockCounts unused;
        auto p = read_segment_model(payload.substr(1), Profile::eval8, 2, true, plain, unused, "t", view);
        EXPECT_TRUE(!p.ok() || plain.chains != b.chains);
    }
}

TEST(MixedModels, StepModelRoundTripsWithAndWithoutWindow) {
    const Block first = fixed_block(contours(3, 40)), b = fixed_block(contours(4, 40));
    auto w = std::make_shared<WindowBlock>();
    add_steps(*w, first);
    const WindowView window{w};
    for (const WindowView* view : {static_cast<const WindowView*>(nullptr), &window})
        for (int order = 0; order <= 4; ++order) {
            const std::string payload = write_mixed_step_model(b, order, view);
            ASSERT_FALSE(payload.empty());
            EXPECT_EQ(static_cast<unsigned char>(payload[0]), kMixedStep | kMixedCurvature);
            Block out;
            BlockCounts counts;
            auto r = read_step_model(payload, 2, true, out, counts, "t", view, kFormatVersion, nullptr, true);
            ASSERT_TRUE(r.ok()) << r.error().message;
            EXPECT_EQ(out.chains, b.chains);
            EXPECT_EQ(counts.chains, b.chains.size());
        }
}

TEST(MixedModels, DecoderErrorsNameThePayloadByte) {
    const Block b = fixed_block(contours(5, 30));
    const std::string seg = write_segment_model(b, Profile::eval8, greedy_cut(b, Profile::eval8), nullptr, false, true);
    const std::string step = write_mixed_step_model(b, 2);
    Block out;
    BlockCounts counts;
    // The model byte names the other model.
    auto r = read_segment_model(step, Profile::eval8, 2, true, out, counts, "blk", nullptr, nullptr, false, true);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, Errc::corrupt);
    EXPECT_EQ(r.error().message.rfind("blk byte 0: ", 0), 0u) << r.error().message;
    r = read_step_model(seg, 2, true, out, counts, "blk", nullptr, kFormatVersion, nullptr, true);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message.rfind("blk byte 0: ", 0), 0u) << r.error().message;
    // The stream cut short: the error is at or before the payload's end.
    for (const std::string* p : {&seg, &step}) {
        const std::string cut = p->substr(0, p->size() - 1);
        auto e = p == &seg ? read_segment_model(cut, Profile::eval8, 2, true, out, counts, "blk", nullptr, nullptr,
                                                false, true)
                           : read_step_model(cut, 2, true, out, counts, "blk", nullptr, kFormatVersion, nullptr, true);
        ASSERT_FALSE(e.ok());
        EXPECT_EQ(e.error().code, Errc::corrupt);
        EXPECT_EQ(e.error().message.rfind("blk byte ", 0), 0u) << e.error().message;
    }
}

// Pinned: a change of these bytes is a format change (docs/FORMAT.md 1.11;
// model bytes 2 and 3, the curvature models, 1.11.1).
constexpr const char* kTwoChains = "0 0 0000100001000010000\n5 -3 22223222232222\n";
constexpr const char* kArc =
    "0 0 00000000100000001000000100000100001000100010010010101010101011011011101110111101111101111110\n";

TEST(MixedModels, PayloadBytesArePinned) {
    const Block b = fixed_block(kTwoChains);
    const auto cut = greedy_cut(b, Profile::eval8);
    EXPECT_EQ(hex(write_segment_model(b, Profile::eval8, cut, nullptr, false, true, false, false)),
              "00 02 04 21 02 00 00 01 e4 cd 11 64 15 4a 22 e7 d3 82 39 8a bc");
    EXPECT_EQ(hex(write_mixed_step_model(b, 2, nullptr, false)),
              "01 02 21 02 00 00 00 67 71 a3 69 a3 57 77 27 1b 35 1c bd 88");
    EXPECT_EQ(hex(write_mixed_step_model(b, 2)), "03 02 21 02 00 00 00 98 d6 bd 0d 89 65 9b 1a 10 8c 3a 81 f0");
    // An arc (slopes turning slowly): the curvature models change the bytes.
    const Block arc = fixed_block(kArc);
    const auto arc_cut = greedy_cut(arc, Profile::eval8);
    EXPECT_EQ(hex(write_segment_model(arc, Profile::eval8, arc_cut, nullptr, false, true, false, false)),
              "00 01 08 5c 01 00 00 01 e5 be c3 34 67 5b 82 23 28 23 12 2d 34 a0 7a ce 6d b6 76 00 00");
    EXPECT_EQ(hex(write_segment_model(arc, Profile::eval8, arc_cut, nullptr, false, true)),
              "02 01 08 5c 01 00 00 01 e5 be c3 34 67 5b 82 23 28 1d 0d 2c ce 66 b3 02 30 c4 d9 4c 00");
}

// Both codings decode (model bytes 0-3); the curvature flag is part of the
// coding (the same bytes under the other flag do not give the block back);
// a model byte above 6 (4-6: the context-mixing step models, tested in
// container_mix_cm_test.cpp) is corrupt at payload byte 0.
TEST(MixedModels, CurvatureFlagSelectsTheCodingAndOtherModelBytesAreCorrupt) {
    const Block b = fixed_block(contours(9, 60));
    const auto cut = greedy_cut(b, Profile::eval8);
    for (const bool curvature : {false, true}) {
        std::string seg = write_segment_model(b, Profile::eval8, cut, nullptr, false, true, false, curvature);
        std::string step = write_mixed_step_model(b, 2, nullptr, curvature);
        ASSERT_FALSE(seg.empty());
        ASSERT_FALSE(step.empty());
        EXPECT_EQ(static_cast<unsigned char>(seg[0]), curvature ? 2u : 0u);
        EXPECT_EQ(static_cast<unsigned char>(step[0]), curvature ? 3u : 1u);
        Block out;
        BlockCounts counts;
        auto r = read_segment_model(seg, Profile::eval8, 2, true, out, counts, "t", nullptr, nullptr, false, true);
        ASSERT_TRUE(r.ok()) << r.error().message;
        EXPECT_EQ(out.chains, b.chains);
        r = read_step_model(step, 2, true, out, counts, "t", nullptr, kFormatVersion, nullptr, true);
        ASSERT_TRUE(r.ok()) << r.error().message;
        EXPECT_EQ(out.chains, b.chains);
        // The other flag: an error or other chains.
        seg[0] = static_cast<char>(seg[0] ^ kMixedCurvature);
        step[0] = static_cast<char>(step[0] ^ kMixedCurvature);
        Block other;
        r = read_segment_model(seg, Profile::eval8, 2, true, other, counts, "t", nullptr, nullptr, false, true);
        EXPECT_TRUE(!r.ok() || other.chains != b.chains);
        r = read_step_model(step, 2, true, other, counts, "t", nullptr, kFormatVersion, nullptr, true);
        EXPECT_TRUE(!r.ok() || other.chains != b.chains);
        for (const unsigned bad : {8u, 9u, 128u, 255u}) {
            seg[0] = static_cast<char>(bad);
            step[0] = static_cast<char>(bad);
            r = read_segment_model(seg, Profile::eval8, 2, true, other, counts, "blk", nullptr, nullptr, false, true);
            ASSERT_FALSE(r.ok());
            EXPECT_EQ(r.error().code, Errc::corrupt);
            EXPECT_EQ(r.error().message.rfind("blk byte 0: ", 0), 0u) << r.error().message;
            r = read_step_model(step, 2, true, other, counts, "blk", nullptr, kFormatVersion, nullptr, true);
            ASSERT_FALSE(r.ok());
            EXPECT_EQ(r.error().message.rfind("blk byte 0: ", 0), 0u) << r.error().message;
        }
    }
}

std::size_t count_blocks(const std::string& frame, unsigned type) {
    std::size_t n = 0, pos = kFrameHeaderSize;
    while (pos < frame.size() && frame[pos] != 0) {
        const unsigned t = static_cast<unsigned char>(frame[pos++]) & 7u;
        auto varint = [&] {
            std::uint64_t v = 0;
            for (int shift = 0;; shift += 7) {
                const auto c = static_cast<unsigned char>(frame.at(pos++));
                v |= static_cast<std::uint64_t>(c & 0x7F) << shift;
                if (c < 0x80) return v;
            }
        };
        const std::uint64_t csize = varint();
        if (t == kChains || t == kRaw) varint();
        pos += static_cast<std::size_t>(csize) + kBlockChecksumSize;
        if (t == type) ++n;
    }
    return n;
}

TEST(MixedModels, StrongLevelsWriteTypeSixWhereSmallerAndTheFrameDecodes) {
    const std::string input = contours(6, 400) + contours(7, 400);
    for (int level : {3, 10, 19}) {
        CompressOptions opt;
        opt.level = level;
        opt.block_steps = 8192;
        opt.window_log = 16;
        auto z = compress(input, opt);
        ASSERT_TRUE(z.ok()) << z.error().message;
        auto back = decompress(*z);
        ASSERT_TRUE(back.ok()) << back.error().message;
        EXPECT_EQ(*back, input);
        // (level 3 writes type 6 blocks of the light step model only:
        // container_mix_cm_test.cpp)
        if (level >= 10) EXPECT_GT(count_blocks(*z, kMixedModel), 0u) << "level " << level;
    }
}

TEST(MixedModels, MixedStepModelIsTriedWhereItsSamplePays) {
    // Glyph contours: mixing saves 10-25 %; a uniform random walk: about 1 %.
    EXPECT_TRUE(mixed_step_model_pays(test::corpus_block("glyphs/dejavu-8.fc", 1u << 18)));
    Block walk = test::corpus_block("random/walk-8.fc", 1u << 17);
    EXPECT_FALSE(mixed_step_model_pays(walk));
    // Up to twice the sample the block is coded as it is, walk or not.
    ASSERT_EQ(walk.chains.size(), 1u);
    walk.chains[0].steps.resize(2 * kMixSampleSteps);
    EXPECT_TRUE(mixed_step_model_pays(walk));
}

TEST(MixedModels, LevelNineteenCutRoundTripsLongLinesAndShortSegments) {
    // Long Bresenham lines (segments of hundreds of steps: the greedy cut
    // is kept) and contours of short segments (recut by the optimal
    // segmenter) in the same blocks, under every profile that takes them.
    std::mt19937_64 rng(19);
    std::vector<Chain> lines;
    for (int i = 0; i < 60; ++i) {
        Chain c;
        c.axes = 2;
        c.start = {static_cast<std::int64_t>(rng() % 1000), static_cast<std::int64_t>(rng() % 1000)};
        for (int seg = 0; seg < 3; ++seg) {
            const std::int64_t dx = 200 + static_cast<std::int64_t>(rng() % 300), dy = static_cast<std::int64_t>(rng() % 200);
            std::int64_t err = 0;
            for (std::int64_t k = 0; k < dx; ++k) {
                err += dy;
                const bool diag = 2 * err >= dx;
                if (diag) err -= dx;
                c.steps.push_back(freeman_to_step(seg % 2 ? (diag ? 7 : 0) : (diag ? 1 : 0)));
            }
        }
        lines.push_back(std::move(c));
    }
    auto text = write_chains(InputFormat::freeman, lines);
    ASSERT_TRUE(text.ok());
    const std::string input = *text + contours(8, 300);
    for (const std::optional<Profile> profile :
         {std::optional<Profile>{}, std::optional(Profile::eval8), std::optional(Profile::grbl)}) {
        CompressOptions opt;
        opt.level = 19;
        opt.profile = profile;
        opt.block_steps = 1u << 15;
        auto z = compress(input, opt);
        ASSERT_TRUE(z.ok()) << z.error().message;
        auto back = decompress(*z);
        ASSERT_TRUE(back.ok()) << back.error().message;
        EXPECT_EQ(*back, input);
    }
}

}  // namespace
}  // namespace stepzip::stz

namespace stepzip::stz {
namespace {

bool thread_tables_clear() {
    const mixdetail::HashedTables& t = mixdetail::thread_tables();
    if (t.busy) return false;
    for (std::size_t i = 0; i < mixdetail::HashedTables::kEntries; ++i)
        if (t.entries[i].px != 0 || t.entries[i].n != 0) return false;
    for (std::uint8_t d : t.dirty)
        if (d != 0) return false;
    return true;
}

TEST(MixTables, ThreadTablesComeBackClearAndANestedPredictorCodesTheSame) {
    const Block a = fixed_block(contours(21, 80)), b = fixed_block(contours(22, 80));
    // A new thread starts from new tables: the reference coding of `a`.
    std::string fresh;
    std::thread([&] { fresh = write_mixed_step_model(a, 1); }).join();
    ASSERT_FALSE(fresh.empty());
    std::thread([&] {
        EXPECT_TRUE(thread_tables_clear());
        EXPECT_FALSE(write_mixed_step_model(b, 1).empty());
        EXPECT_TRUE(thread_tables_clear());  // given back cleared where written
        EXPECT_EQ(write_mixed_step_model(a, 1), fresh);
        {
            // While a predictor holds the thread's tables, the next one makes its own.
            Prob base[16]{};
            MixPredictor holder(base, kMixBaseModels);
            EXPECT_TRUE(mixdetail::thread_tables().busy);
            EXPECT_EQ(write_mixed_step_model(a, 1), fresh);
        }
        EXPECT_TRUE(thread_tables_clear());
    }).join();
}

TEST(MixedModels, FirstBlockTrialGivesTheBytesOfTheBlocksOwnChoice) {
    // One block (under the trial's size): with --profile auto the ranking's
    // cuts and model of the winner are reused; named, the block makes them.
    const std::string input = contours(23, 300);
    CompressOptions opt;
    opt.level = 19;
    auto z = compress(input, opt);
    ASSERT_TRUE(z.ok()) << z.error().message;
    auto info = inspect_stream(memory_reader(*z));
    ASSERT_TRUE(info.ok()) << info.error().message;
    opt.profile = info->profile;
    auto named = compress(input, opt);
    ASSERT_TRUE(named.ok()) << named.error().message;
    EXPECT_EQ(*z, *named);
    auto back = decompress(*z);
    ASSERT_TRUE(back.ok()) << back.error().message;
    EXPECT_EQ(*back, input);
}

}  // namespace
}  // namespace stepzip::stz
