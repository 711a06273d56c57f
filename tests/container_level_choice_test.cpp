// Which codings the fast levels choose for a large block (docs/FORMAT.md
// section 4): from level 3 a block of 2^16 steps or more that a table block
// codes is coded by the segment model when that is at least 1/32 smaller;
// below level 3 it stays a table block; where the table block's matches win
// (the same glyphs again at the same coordinates) it stays one at level 3
// too. Every frame decodes to its input.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "../src/container/memory_io.hpp"
#include "stepzip/container.hpp"
#include "support/files.hpp"
#include "support/proved.hpp"

namespace stepzip {
namespace {

using test::corpus;

struct Coded {
    std::string frame;
    FrameInfo info;
};

// `block_steps`: nullopt for the default.
Coded code(const std::string& input, int level, std::optional<std::size_t> block_steps = {}) {
    CompressOptions opt;
    opt.level = level;
    opt.block_steps = block_steps;
    std::string z = test::compress_proved(input, opt);
    if (z.empty()) return {};
    auto info = inspect_stream(stz::memory_reader(z));
    EXPECT_TRUE(info.ok());
    return {z, info.ok() ? *info : FrameInfo{}};
}

TEST(LevelChoice, LargePlotBlockTakesTheSegmentModelFromLevel3) {
    // 215 960 steps, one block; the segment model is 13 % smaller there.
    const std::string input = corpus("plotter/hershey-grbl.fc");
    const Coded two = code(input, 2), three = code(input, 3);
    EXPECT_EQ(two.info.blocks, 1u);
    EXPECT_EQ(two.info.table_blocks, 1u);
    EXPECT_EQ(three.info.blocks, 1u);
    EXPECT_EQ(three.info.segment_model_blocks, 1u);
    EXPECT_EQ(three.info.table_blocks, 0u);
    // kept only by the margin: at least 1/32 smaller than level 2's table
    // block (the same table effort; the frames differ in the window only)
    EXPECT_LE(three.frame.size() * 32, two.frame.size() * 31);
}

TEST(LevelChoice, Level1KeepsLargeBlocksAsTableBlocksAndLevel2TakesTheLightStepModel) {
    const std::string input = corpus("glyphs/dejavu-4.fc");  // 301 042 steps
    const Coded one = code(input, 1), two = code(input, 2), three = code(input, 3);
    EXPECT_EQ(one.info.segment_model_blocks, 0u);
    EXPECT_EQ(one.info.table_blocks, one.info.blocks);
    // From level 2 the light step model (a step-model block) on contours,
    // at least 1/32 smaller than the table block.
    for (const Coded* c : {&two, &three}) {
        EXPECT_EQ(c->info.step_model_blocks, c->info.blocks);
        EXPECT_LE(c->frame.size() * 32, one.frame.size() * 31);
    }
}

TEST(LevelChoice, RepeatedGlyphsStayATableBlockAtLevel1) {
    // 84 134 steps: the same page in four Hershey fonts; the table block's
    // matches over the segment stream find the shared glyphs. From level 2
    // the light step model's match finds them too, and is smaller.
    const std::string input = corpus("plotter/hershey-pages-grbl.fc");
    const Coded c = code(input, 1), three = code(input, 3);
    EXPECT_EQ(c.info.blocks, 1u);
    EXPECT_EQ(c.info.table_blocks, 1u);
    EXPECT_EQ(three.info.step_model_blocks, 1u);
    EXPECT_LT(three.frame.size(), c.frame.size());
}

TEST(LevelChoice, ManyBlocksRoundTripAndDecodeTheSameAcrossThreads) {
    // several blocks of the same data: the window passes after the choice
    // (level 1: the table blocks coded once, late, from the window)
    const std::string one = corpus("plotter/gnuplot-grbl.fc");
    const std::string input = one + one + one;  // 1.3 M steps: two blocks
    for (int level : {1, 3}) {
        CompressOptions opt;
        opt.level = level;
        auto a = compress(input, opt);
        opt.threads = 2;
        auto b = compress(input, opt);
        ASSERT_TRUE(a.ok());
        ASSERT_TRUE(b.ok());
        EXPECT_EQ(*a, *b) << "level " << level;
        const Coded c = code(input, level);
        EXPECT_GE(c.info.blocks, 2u);
    }
}

TEST(LevelChoice, Level1TableBlocksFindTheWindowAndWeakBlocksStayZstds) {
    // Below level 3 a large block's table block is coded once, after the
    // blocks before it are known (block_strategy.cpp, table_late_pays()):
    // the second copy of a glyph file, in later blocks of 2^17 steps, is
    // found in the window.
    const std::string glyphs = corpus("glyphs/dejavu-4.fc");  // 301 042 steps
    const Coded once = code(glyphs, 1, 1u << 17), twice = code(glyphs + glyphs, 1, 1u << 17);
    EXPECT_EQ(twice.info.table_blocks, twice.info.blocks);
    EXPECT_GE(twice.info.blocks, 4u);
    EXPECT_LT(twice.frame.size(), once.frame.size() * 11 / 10);
    // A random walk's table block is weak (under 5:1): zstd of its bytes
    // is tried and kept, block by block, as before.
    const std::string walk = corpus("random/walk-8.fc");  // 100 000 steps
    const Coded w = code(walk + walk, 1, 100000);
    EXPECT_EQ(w.info.blocks, 2u);
    EXPECT_EQ(w.info.raw_blocks, w.info.blocks);
}

}  // namespace
}  // namespace stepzip
