// The context-mixing step model (block type 6, model byte 4; docs/FORMAT.md
// 1.11.2) and its light version (model byte 5, 1.11.3): they round-trip
// with and without a window, 8- and 4-connected, and on the decoder's
// running history of a frame; their payload bytes of a small fixed input
// are pinned; the decoder's errors name the payload byte; every flipped bit
// of their stream decodes or is corrupt; the strong levels write the full
// model on glyph contours (also on blocks large enough to be chosen for it on
// a sample before their segments are cut), levels 2-9 the light one, level 1
// neither, and plots keep the segment model; a block of other than two axes
// gets none; a random walk's plain steps are coded by the step model or
// zstd from level 2 on.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../src/container/block_codec.hpp"
#include "../src/container/encoder.hpp"
#include "../src/container/modeled_block.hpp"
#include "../src/container/window.hpp"
#include "stepzip/container.hpp"
#include "stepzip/document.hpp"
#include "support/block_records.hpp"
#include "support/pinned_bytes.hpp"
#include "support/proved.hpp"

namespace stepzip::stz {
namespace {

using test::corpus_block;
using test::fixed_block;
using test::hex;

// The model bytes of a frame's type 6 blocks, in order.
std::vector<unsigned> mixed_model_bytes(const std::string& frame) {
    std::vector<unsigned> out;
    std::size_t pos = kFrameHeaderSize;
    while (pos < frame.size() && frame[pos] != 0) {
        const unsigned t = static_cast<unsigned char>(frame[pos++]) & 7u;
        std::uint64_t size = 0;
        for (int shift = 0;; shift += 7) {
            const unsigned char b = static_cast<unsigned char>(frame[pos++]);
            size |= static_cast<std::uint64_t>(b & 0x7Fu) << shift;
            if (!(b & 0x80u)) break;
        }
        if (t == kChains || t == kRaw)  // decoded size
            while (static_cast<unsigned char>(frame[pos++]) & 0x80u) {
            }
        if (t == kMixedModel) out.push_back(static_cast<unsigned char>(frame[pos]));
        pos += static_cast<std::size_t>(size) + kBlockChecksumSize;
    }
    return out;
}

Block decode(const std::string& payload, const WindowView* view) {
    Block out;
    BlockCounts counts;
    auto r = read_step_model(payload, 2, true, out, counts, "t", view, kFormatVersion, nullptr, true);
    EXPECT_TRUE(r.ok()) << r.error().message;
    return out;
}

// The first `lines` lines of corpora/`rel`.
std::string corpus_text(const char* rel, std::size_t lines) {
    std::ifstream f(std::filesystem::path(STEPZIP_SOURCE_DIR) / "corpora" / rel, std::ios::binary);
    std::string out, line;
    for (std::size_t i = 0; i < lines && std::getline(f, line); ++i) out += line + '\n';
    EXPECT_FALSE(out.empty()) << rel;
    return out;
}

using Writer = std::string (*)(const Block&, const WindowView*);
struct Model {
    Writer write;
    unsigned byte;
};
std::string write_dss(const Block& b, const WindowView* w) { return write_cm_step_model(b, w); }
std::string write_v4(const Block& b, const WindowView* w) { return write_cm_step_model(b, w, kMixedStepCm); }
std::string write_light(const Block& b, const WindowView* w) { return write_light_cm_step_model(b, w, kMixedStepCmLight); }
std::string write_light_small(const Block& b, const WindowView* w) { return write_light_cm_step_model(b, w); }
const Model kModelsUnderTest[] = {{write_dss, kMixedStepCmDss},
                                  {write_v4, kMixedStepCm},
                                  {write_light, kMixedStepCmLight},
                                  {write_light_small, kMixedStepCmLightSmall}};

TEST(CmStepModel, RoundTripsWithAndWithoutWindowOnEightAndFourConnectedContours) {
    for (const Model& model : kModelsUnderTest)
    for (const char* file : {"glyphs/liberation-8.fc", "glyphs/dejavu-4.fc", "traced/icons-4.fc"}) {
        SCOPED_TRACE(std::string(file) + " model " + std::to_string(model.byte));
        const Block all = corpus_block(file, 40000);
        Block first, second;
        first.axes = second.axes = 2;
        for (std::size_t i = 0; i < all.chains.size(); ++i)
            (i < all.chains.size() / 2 ? first : second).chains.push_back(all.chains[i]);
        auto w = std::make_shared<WindowBlock>();
        add_steps(*w, first);
        const WindowView window{w};
        const std::string alone = model.write(second, nullptr);
        const std::string primed = model.write(second, &window);
        ASSERT_FALSE(alone.empty());
        EXPECT_EQ(static_cast<unsigned char>(alone[0]), model.byte);
        EXPECT_EQ(decode(alone, nullptr).chains, second.chains);
        EXPECT_EQ(decode(primed, &window).chains, second.chains);
        // The window's steps are worth something to the match model.
        EXPECT_LT(primed.size(), alone.size());
        // The full models: smaller than the mixed step model of the same block.
        if (model.byte != kMixedStepCmLight && model.byte != kMixedStepCmLightSmall)
            EXPECT_LT(alone.size(), write_mixed_step_model(second, 1).size());
    }
}

// Model byte 7 is model byte 5 with its row table capped at 2^16 rows
// (docs/FORMAT.md 1.11.3): below 2^15 steps (2^16 rows or fewer either way)
// the two codings are the same bits after the model byte; above, the rows
// differ, and each decodes to its block.
TEST(CmStepModel, LightModelSmallRowsBindOnlyAboveTwoToTheFifteenSteps) {
    const Block all = corpus_block("glyphs/dejavu-4.fc", 40000);
    Block small, large;
    small.axes = large.axes = 2;
    std::uint64_t steps = 0;
    for (const Chain& c : all.chains) {
        if (steps + c.steps.size() < (1u << 15)) small.chains.push_back(c);
        large.chains.push_back(c);
        steps += c.steps.size();
    }
    ASSERT_GE(steps, std::uint64_t{1} << 15);  // 2^17 rows or more for model byte 5
    for (const Block* b : {&small, &large}) {
        const std::string five = write_light_cm_step_model(*b, nullptr, kMixedStepCmLight);
        const std::string seven = write_light_cm_step_model(*b, nullptr, kMixedStepCmLightSmall);
        ASSERT_FALSE(five.empty());
        ASSERT_FALSE(seven.empty());
        EXPECT_EQ(static_cast<unsigned char>(seven[0]), kMixedStepCmLightSmall);
        if (b == &small) EXPECT_EQ(five.substr(1), seven.substr(1));
        else EXPECT_NE(five.substr(1), seven.substr(1));
        EXPECT_EQ(decode(five, nullptr).chains, b->chains);
        EXPECT_EQ(decode(seven, nullptr).chains, b->chains);
    }
    // Neither names another model.
    EXPECT_TRUE(write_light_cm_step_model(small, nullptr, kMixedStepCmDss).empty());
}

// Pinned: a change of these bytes is a format change (docs/FORMAT.md 1.11.2).
TEST(CmStepModel, PayloadBytesArePinned) {
    const Block b = fixed_block("0 0 0000100001000010000\n5 -3 22223222232222\n");
    EXPECT_EQ(hex(write_cm_step_model(b, nullptr, kMixedStepCm)), "04 02 21 00 00 03 df 66 59 43 97 61 76 97 35 56 a7");
    EXPECT_EQ(hex(write_cm_step_model(b)), "06 02 21 00 00 03 6c 25 ec 76 77 cf 54 bc c3 49 52");
    EXPECT_EQ(hex(write_light_cm_step_model(b, nullptr, kMixedStepCmLight)),
              "05 02 21 00 00 01 24 ab 26 3b 1e 7e 43 2d 75 57 35 a2 00");
    // (a block this small: 2^12 rows either way, the same bits after the model byte)
    EXPECT_EQ(hex(write_light_cm_step_model(b)), "07 02 21 00 00 01 24 ab 26 3b 1e 7e 43 2d 75 57 35 a2 00");
}

// The DSS context (model byte 6) is worth a few per cent on glyph contours
// of either connectivity, at small sizes as at large.
TEST(CmStepModel, TheDssContextMakesContoursSmaller) {
    for (const char* file : {"glyphs/dejavu-4.fc", "glyphs/liberation-8.fc", "traced/icons-4.fc"}) {
        const Block b = corpus_block(file, 40000);
        const std::size_t dss = write_cm_step_model(b).size(), v4 = write_cm_step_model(b, nullptr, kMixedStepCm).size();
        EXPECT_LT(dss, v4 - v4 / 100) << file << ": " << dss << " against " << v4;
    }
}

// Model byte 6 codes chain starts by mixed contexts of the chains before
// them: what the starts of traced glyph contours cost (the block's size less
// that of the same chains each starting where the one before ended) is at
// least 8 % below model byte 4's, which codes each coordinate alone (10-13 %
// on the first 100 000 steps of these files; the same without the mixing).
TEST(CmStepModel, StartsAfterTheChainsBeforeThemCostLess) {
    for (const char* file : {"glyphs/dejavu-4.fc", "glyphs/dejavu-8.fc"}) {
        const Block b = corpus_block(file, 100000);
        Block joined = b;
        Point at{};
        for (Chain& c : joined.chains) {
            c.start = at;
            at = c.end();
        }
        auto starts_cost = [&](unsigned model) {
            return static_cast<double>(write_cm_step_model(b, nullptr, model).size()) -
                   static_cast<double>(write_cm_step_model(joined, nullptr, model).size());
        };
        const double dss = starts_cost(kMixedStepCmDss), v4 = starts_cost(kMixedStepCm);
        EXPECT_GT(v4, 0.0) << file;
        EXPECT_LT(dss, 0.92 * v4) << file << ": " << dss << " against " << v4;
    }
}

// The light model is smaller than the segment model on glyph contours and a
// few per cent larger than the full model it keeps a part of (model byte 4;
// model byte 6, with more, is smaller still).
TEST(CmStepModel, LightModelSitsBetweenTheSegmentModelAndTheFullModel) {
    const Block b = corpus_block("glyphs/dejavu-8.fc", 60000);
    const std::size_t light = write_light_cm_step_model(b).size(),
                      full = write_cm_step_model(b, nullptr, kMixedStepCm).size();
    EXPECT_GT(light, full);
    EXPECT_GT(full, write_cm_step_model(b).size());
    EXPECT_LT(light, full + full / 5);
    EXPECT_LT(light, write_step_model(b, 2).size());
}

class CmModelErrors : public ::testing::TestWithParam<Model> {};
INSTANTIATE_TEST_SUITE_P(EveryModel, CmModelErrors, ::testing::ValuesIn(kModelsUnderTest));

TEST_P(CmModelErrors, DecoderErrorsNameThePayloadByte) {
    const Block b = corpus_block("glyphs/c059-8.fc", 4000);
    const std::string payload = GetParam().write(b, nullptr);
    Block out;
    BlockCounts counts;
    // Cut short: the error is at or before the payload's end.
    const std::string cut = payload.substr(0, payload.size() - 1);
    auto r = read_step_model(cut, 2, true, out, counts, "blk", nullptr, kFormatVersion, nullptr, true);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, Errc::corrupt);
    EXPECT_EQ(r.error().message.rfind("blk byte ", 0), 0u) << r.error().message;
    // A byte too many: the stream does not end at the payload's end.
    r = read_step_model(payload + '\0', 2, true, out, counts, "blk", nullptr, kFormatVersion, nullptr, true);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, Errc::corrupt);
    // On three axes: corrupt at byte 0.
    r = read_step_model(payload, 3, true, out, counts, "blk", nullptr, kFormatVersion, nullptr, true);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message.rfind("blk byte 0: ", 0), 0u) << r.error().message;
    // More steps declared than the limit.
    std::string big = payload.substr(0, 1);
    put_varint(big, 1);
    put_varint(big, kMaxBlockSteps + 1);
    big += payload.substr(big.size());
    r = read_step_model(big, 2, true, out, counts, "blk", nullptr, kFormatVersion, nullptr, true);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, Errc::limit);
    // Not two axes: the encoder writes none.
    Block three;
    three.axes = 3;
    EXPECT_TRUE(GetParam().write(three, nullptr).empty());
}

// Every bit of the range-coded stream flipped: the reader decodes some
// chains or reports a corrupt payload byte; never anything else.
TEST_P(CmModelErrors, EveryStreamBitFlipDecodesOrIsCorrupt) {
    const Block b = fixed_block(corpus_text("glyphs/c059-8.fc", 4));
    const std::string payload = GetParam().write(b, nullptr);
    ASSERT_FALSE(payload.empty());
    // model byte, then nchains, nsteps and the layout's two sizes (0: no layout)
    std::size_t header = 1;
    for (int field = 0; field < 4; ++field)
        while (static_cast<unsigned char>(payload[header++]) & 0x80u) {
        }
    int rejected = 0;
    for (std::size_t k = header; k < payload.size(); ++k)
        for (int bit = 0; bit < 8; ++bit) {
            std::string bad = payload;
            bad[k] = static_cast<char>(static_cast<unsigned char>(bad[k]) ^ (1u << bit));
            Block out;
            BlockCounts counts;
            auto r = read_step_model(bad, 2, true, out, counts, "blk", nullptr, kFormatVersion, nullptr, true);
            if (r.ok()) continue;
            ++rejected;
            EXPECT_EQ(r.error().code, Errc::corrupt) << r.error().message;
            EXPECT_EQ(r.error().message.rfind("blk byte ", 0), 0u) << r.error().message;
        }
    EXPECT_GT(rejected, 0);
}

// Frames of several blocks, each flagged `window` but the first: the
// decoder codes them on its running history of the frame.
TEST(CmStepModel, StrongLevelsWriteItOnContoursAndTheFramesDecode) {
    const std::string glyphs = corpus_text("glyphs/liberation-8.fc", 200) + corpus_text("glyphs/liberation-8.fc", 200);
    for (const int threads : {1, 2}) {
        CompressOptions opt;
        opt.level = 19;
        opt.block_steps = 6000;
        opt.threads = threads;
        auto z = compress(glyphs, opt);
        ASSERT_TRUE(z.ok()) << z.error().message;
        auto back = decompress(*z);
        ASSERT_TRUE(back.ok()) << back.error().message;
        EXPECT_EQ(*back, glyphs);
        const auto models = mixed_model_bytes(*z);
        EXPECT_GT(std::count(models.begin(), models.end(), kMixedStepCmDss), 1) << "threads " << threads;
        // Levels 2-9: the light model, on every block.
        for (const int level : {2, 3, 9}) {
            opt.level = level;
            auto fast = compress(glyphs, opt);
            ASSERT_TRUE(fast.ok());
            auto fast_back = decompress(*fast);
            ASSERT_TRUE(fast_back.ok()) << fast_back.error().message;
            EXPECT_EQ(*fast_back, glyphs);
            const auto light = mixed_model_bytes(*fast);
            EXPECT_GT(light.size(), 1u) << "level " << level;
            EXPECT_EQ(std::count(light.begin(), light.end(), kMixedStepCmLightSmall),
                      static_cast<std::ptrdiff_t>(light.size()));
        }
        // Level 1: neither.
        opt.level = 1;
        auto fastest = compress(glyphs, opt);
        ASSERT_TRUE(fastest.ok());
        EXPECT_TRUE(mixed_model_bytes(*fastest).empty());
    }
}

TEST(CmStepModel, PlotsKeepTheSegmentModel) {
    const std::string plot = corpus_text("plotter/hershey-grbl.fc", 300);
    CompressOptions opt;
    opt.level = 19;
    auto z = compress(plot, opt);
    ASSERT_TRUE(z.ok()) << z.error().message;
    const auto models = mixed_model_bytes(*z);
    ASSERT_FALSE(models.empty());
    EXPECT_EQ(std::count(models.begin(), models.end(), kMixedStepCmDss), 0);
    auto back = decompress(*z);
    ASSERT_TRUE(back.ok()) << back.error().message;
    EXPECT_EQ(*back, plot);
    // The default level: no light model either.
    opt.level = 3;
    z = compress(plot, opt);
    ASSERT_TRUE(z.ok()) << z.error().message;
    EXPECT_TRUE(mixed_model_bytes(*z).empty());
}

// A block of more than 2^16 steps whose sample the model codes well below
// the segment model is left to it before its segments are cut (and a first
// block of more than 2^17 steps before the profiles' larger trial): glyph
// contours come out as one context-mixing block that decodes; a plot of the
// same size keeps the segment model.
TEST(CmStepModel, LargeBlocksAreChosenBeforeTheirSegmentsAreCut) {
    const std::string glyphs = corpus_text("glyphs/dejavu-8.fc", 1u << 20);
    const std::string plot = corpus_text("plotter/hershey-grbl.fc", 1u << 20);
    for (const std::string* input : {&glyphs, &plot}) {
        CompressOptions opt;
        opt.level = 19;
        auto z = compress(*input, opt);
        ASSERT_TRUE(z.ok()) << z.error().message;
        auto back = decompress(*z);
        ASSERT_TRUE(back.ok()) << back.error().message;
        EXPECT_EQ(*back, *input);
        const auto models = mixed_model_bytes(*z);
        ASSERT_EQ(models.size(), 1u);
        if (input == &glyphs) EXPECT_EQ(models[0], kMixedStepCmDss);
        else EXPECT_NE(models[0], kMixedStepCmDss);
    }
}

// A random walk's steps are plain (order-2 entropy as high as order 0);
// traced contours and plots are not, nor are a few steps or more than two
// axes.
TEST(PlainSteps, ToldFromChainsByTheirOrderTwoEntropy) {
    EXPECT_TRUE(plain_steps(corpus_block("random/walk-4.fc", 150000)));
    EXPECT_TRUE(plain_steps(corpus_block("random/walk-8.fc", 150000)));
    for (const char* rel : {"glyphs/dejavu-8.fc", "glyphs/liberation-4.fc", "plotter/hershey-grbl.fc", "plotter/gnuplot-eval4.fc"})
        EXPECT_FALSE(plain_steps(corpus_block(rel, 200000))) << rel;
    EXPECT_FALSE(plain_steps(corpus_block("traced/icons-8.fc", 60000)));
    const std::string walk = corpus_text("random/walk-8.fc", 2);
    const std::size_t codes = walk.find("0 0 ") + 4;
    EXPECT_FALSE(plain_steps(test::block_of(InputFormat::freeman, walk.substr(0, codes + 10000) + "\n")));
    EXPECT_TRUE(plain_steps(test::block_of(InputFormat::freeman, walk.substr(0, codes + 20000) + "\n")));
    Block three = test::block_of(InputFormat::freeman, walk);
    three.axes = 3;
    EXPECT_FALSE(plain_steps(three));
}

// Levels 2-9 code a random walk by the step model or zstd's raw block (not
// the light model, the table block or the CM raw block), level 1 by zstd's
// raw block only, and it decodes; -L 3's bytes are those it wrote before
// the rule.
TEST(PlainSteps, FastLevelsCodeThemByTheStepModelOrZstd) {
    const std::string walk = corpus_text("random/walk-8.fc", 2);
    for (const int level : {1, 2, 3, 9}) {
        CompressOptions opt;
        opt.level = level;
        const std::string z = test::compress_proved(walk, opt);
        ASSERT_FALSE(z.empty()) << level;
        const auto records = test::block_records(z);
        ASSERT_FALSE(records.empty());
        for (const auto& r : records)
            EXPECT_TRUE(r.type == kRaw || (level > 1 && r.type == kStepModel)) << level << ": " << r.type;
    }
}

}  // namespace
}  // namespace stepzip::stz
