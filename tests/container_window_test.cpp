// Format version 2 (docs/FORMAT.md): the window across blocks finds repeats
// farther than a block but not farther than the declared window, the bytes
// do not depend on the thread count, a block that uses a window the frame
// does not declare is refused; a step-model block decodes on the steps
// of earlier blocks of other types; frames back to back decode as one stream;
// the fixed overhead of a frame is small.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "../src/container/block_codec.hpp"
#include "../src/common/bytes.hpp"
#include "../src/container/memory_io.hpp"
#include "../src/container/window.hpp"
#include "stepzip/container.hpp"
#include "stepzip/document.hpp"

namespace stepzip {
namespace {

// Plotter-like chains: runs of one direction with occasional turns; or,
// `noisy`, a random Freeman code at every step (the step model codes them).
std::string chains_text(std::uint64_t seed, int count, bool noisy = false) {
    std::mt19937_64 rng(seed);
    std::vector<Chain> chains;
    for (int i = 0; i < count; ++i) {
        Chain c;
        c.axes = 2;
        c.start = {static_cast<std::int64_t>(rng() % 2000), static_cast<std::int64_t>(rng() % 2000)};
        const int n = 20 + static_cast<int>(rng() % 80);
        int code = static_cast<int>(rng() % 8);
        for (int k = 0; k < n; ++k) {
            if (noisy || rng() % 6 == 0) code = (code + 1 + static_cast<int>(rng() % 7)) % 8;
            c.steps.push_back(freeman_to_step(code));
        }
        chains.push_back(std::move(c));
    }
    auto t = write_chains(InputFormat::freeman, chains);
    EXPECT_TRUE(t.ok());
    return t.ok() ? *t : std::string();
}

std::string must_compress(const std::string& input, const CompressOptions& opt) {
    auto z = compress(input, opt);
    EXPECT_TRUE(z.ok()) << z.error().message;
    if (!z.ok()) return {};
    auto back = decompress(*z);
    EXPECT_TRUE(back.ok()) << back.error().message;
    if (back.ok()) {
        EXPECT_EQ(*back, input);
    }
    return *z;
}

// A + B + A: the second A starts about 18000 steps after the first, more
// than four blocks of 4096 steps.
std::string far_repeat() {
    const std::string a = chains_text(1, 200), b = chains_text(2, 100);
    return a + b + a;
}

CompressOptions window_options(int window_log) {
    CompressOptions opt;
    opt.block_steps = 4096;
    opt.window_log = window_log;
    return opt;
}

TEST(ContainerWindow, RepeatsFartherThanABlockAreFoundInsideTheWindow) {
    const std::string input = far_repeat();
    const std::string none = must_compress(input, window_options(0));
    const std::string wide = must_compress(input, window_options(15));  // 32768 > 18000
    ASSERT_FALSE(none.empty());
    // The repeated third costs almost nothing with the window.
    EXPECT_LT(wide.size() * 10, none.size() * 8) << wide.size() << " vs " << none.size();
    auto info = inspect_stream(stz::memory_reader(wide));
    ASSERT_TRUE(info.ok()) << info.error().message;
    EXPECT_EQ(info->window, 1u << 15);
    EXPECT_EQ(info->format_version, 2);
}

// A window takes earlier blocks whole (docs/FORMAT.md 1.8), so the window a
// level declares must hold several blocks of the default size for a repeat
// farther than one block to be found: at least three, each with a chain per
// 8 steps, from level 1 on (2^21 at levels 1-2 held one).
TEST(ContainerWindow, EveryLevelsWindowHoldsThreeDefaultBlocks) {
    const std::string input = chains_text(3, 20);
    const std::uint64_t block_weight = kDefaultBlockSteps + kDefaultBlockSteps / 8;
    for (int level : {1, 2, 3, 9, 10, 19}) {
        CompressOptions opt;
        opt.level = level;
        const std::string z = must_compress(input, opt);
        auto info = inspect_stream(stz::memory_reader(z));
        ASSERT_TRUE(info.ok()) << info.error().message;
        EXPECT_GE(info->window, 3 * block_weight) << "level " << level;
        EXPECT_LE(info->window, std::uint64_t{1} << kMaxWindowLog) << "level " << level;
    }
}

TEST(ContainerWindow, NothingIsFoundPastTheDeclaredWindow) {
    const std::string input = far_repeat();
    const std::string none = must_compress(input, window_options(0));
    const std::string narrow = must_compress(input, window_options(13));  // 8192 < 18000
    ASSERT_FALSE(none.empty());
    EXPECT_GT(narrow.size() * 10, none.size() * 9) << narrow.size() << " vs " << none.size();
}

TEST(ContainerWindow, ALongStreamOfRepeatsDecodesAsTheWindowSays) {
    // Twenty pieces of about 2400 steps of noisy chains, each a copy of the one two places
    // before it or a new one: repeats lie within the window (2^13), and the
    // stream is many windows long, so the decoder's history drops what
    // left the window many times over.
    std::vector<std::string> fresh;
    for (int i = 0; i < 8; ++i) fresh.push_back(chains_text(100 + static_cast<std::uint64_t>(i), 40, true));
    std::string input;
    for (int i = 0; i < 20; ++i) input += fresh[static_cast<std::size_t>(i % 2 == 0 ? (i / 4) % 8 : i % 8)];
    CompressOptions opt;
    opt.block_steps = 2048;
    opt.window_log = 0;
    const std::string none = must_compress(input, opt);
    opt.window_log = 13;
    const std::string windowed = must_compress(input, opt);
    ASSERT_FALSE(none.empty());
    EXPECT_LT(windowed.size() * 10, none.size() * 9) << windowed.size() << " vs " << none.size();
    auto info = inspect_stream(stz::memory_reader(windowed));
    ASSERT_TRUE(info.ok()) << info.error().message;
    EXPECT_GT(info->step_model_blocks, 10u);
}

TEST(ContainerWindow, AStepModelBlockAfterBlocksOfOtherTypesFindsTheirSteps) {
    // Plotter-like chains (segment items) around noisy chains that come
    // again later: the decoder holds the earlier blocks until the first
    // step-model block flagged window needs their symbols.
    const std::string noisy = chains_text(7, 40, true);
    std::vector<Chain> lines(10);
    for (std::size_t i = 0; i < lines.size(); ++i) {
        lines[i].start = {static_cast<std::int64_t>(i) * 7, 0};
        for (int run = 0; run < 4; ++run)  // long straight runs: few segments
            lines[i].steps.insert(lines[i].steps.end(), 150 + 40 * static_cast<std::size_t>(run),
                                  freeman_to_step(static_cast<int>(i) + run * 2));
    }
    auto plot = write_chains(InputFormat::freeman, lines);
    ASSERT_TRUE(plot.ok());
    const std::string input = *plot + noisy + *plot + noisy;
    CompressOptions opt;
    opt.block_steps = 2048;
    opt.level = 3;
    opt.window_log = 0;
    const std::string none = must_compress(input, opt);
    opt.window_log = 15;
    const std::string windowed = must_compress(input, opt);
    ASSERT_FALSE(none.empty());
    EXPECT_LT(windowed.size() * 10, none.size() * 9) << windowed.size() << " vs " << none.size();
    auto info = inspect_stream(stz::memory_reader(windowed));
    ASSERT_TRUE(info.ok()) << info.error().message;
    EXPECT_GT(info->step_model_blocks, 0u);
    EXPECT_GT(info->table_blocks + info->segment_model_blocks, 0u);
}

// The encoder keeps a table block's chains with its window contribution, as
// the decoder does: the proof of a later table block copies whole chains
// from them. A + B + A in blocks large enough to be table blocks at level 1,
// the second A a block after the first.
TEST(ContainerWindow, TableBlocksProvedOnTheChainsOfTheWindowsTableBlocks) {
    const std::string a = chains_text(11, 1200), b = chains_text(12, 300);
    CompressOptions opt = window_options(18);
    opt.level = 1;
    opt.block_steps = 1 << 16;
    const std::string z = must_compress(a + b + a, opt);
    auto info = inspect_stream(stz::memory_reader(z));
    ASSERT_TRUE(info.ok()) << info.error().message;
    EXPECT_GE(info->table_blocks, 2u);
}

// A table block's chains kept with its contribution are lent to the
// step model when a later block wants the window's symbols: the symbols and
// starts are the block's own, and the chains stay with the contribution.
TEST(ContainerWindow, ChainsKeptWithAContributionAreLentForItsSymbols) {
    Block b;
    for (int i = 0; i < 3; ++i) {
        Chain c;
        c.axes = 2;
        c.start = {10 * i, -i};
        for (int k = 0; k < 5 + i; ++k) c.steps.push_back(freeman_to_step((i + k * k) % 8));
        b.chains.push_back(std::move(c));
    }
    stz::WindowBlock direct, kept, own;
    stz::add_steps(direct, b);
    ASSERT_FALSE(direct.symbols.empty());
    kept.chains = b.chains;
    Block none;  // the block once its chains went with the contribution
    stz::add_steps_lent(kept, none);
    EXPECT_EQ(kept.symbols, direct.symbols);
    EXPECT_EQ(kept.starts, direct.starts);
    EXPECT_EQ(kept.chains, b.chains);
    EXPECT_TRUE(none.chains.empty());
    Block mine = b;  // a block that has its chains
    stz::add_steps_lent(own, mine);
    EXPECT_EQ(own.symbols, direct.symbols);
    EXPECT_EQ(mine.chains, b.chains);
}

TEST(ContainerWindow, ThreadCountDoesNotChangeTheBytes) {
    const std::string input = far_repeat();
    CompressOptions opt = window_options(15);
    opt.block_steps = 1500;
    for (int level : {3, 12}) {
        opt.level = level;
        opt.threads = 1;
        const std::string one = must_compress(input, opt);
        for (unsigned t : {2u, 3u, 8u}) {
            opt.threads = t;
            EXPECT_EQ(must_compress(input, opt), one) << "level " << level << ", threads " << t;
        }
    }
}

TEST(ContainerWindow, ABlockUsingAnUndeclaredWindowIsCorrupt) {
    std::string frame = must_compress(far_repeat(), window_options(15));
    ASSERT_GT(frame.size(), stz::kFrameHeaderSize);
    // Header byte 6: axes in bits 0-2, window log in bits 3-7; the header
    // check made valid again.
    frame[6] = static_cast<char>(frame[6] & 7);
    frame[7] = static_cast<char>((stz::hash64(std::string_view(frame).substr(0, 7)) >> 8) & 0xFF);
    auto r = decompress(frame);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, Errc::corrupt) << r.error().message;
}

TEST(ContainerFrames, FramesBackToBackDecodeAsOneStream) {
    const std::string x = chains_text(3, 20), y = chains_text(4, 30);
    const std::string a = must_compress(x, {}), b = must_compress(y, {});
    auto both = decompress(a + b);
    ASSERT_TRUE(both.ok()) << both.error().message;
    EXPECT_EQ(*both, x + y);
    auto info = inspect_stream(stz::memory_reader(a + b + a));
    ASSERT_TRUE(info.ok()) << info.error().message;
    EXPECT_EQ(info->frames, 3u);
    EXPECT_EQ(info->decoded_bytes, 2 * x.size() + y.size());
    EXPECT_EQ(info->compressed_bytes, 2 * a.size() + b.size());
    // A second frame cut short is truncated; bytes that are no frame are not.
    auto cut = decompress(a + b.substr(0, b.size() - 1));
    ASSERT_FALSE(cut.ok());
    EXPECT_EQ(cut.error().code, Errc::truncated);
    auto junk = decompress(a + "junk");
    ASSERT_FALSE(junk.ok());
    EXPECT_EQ(junk.error().code, Errc::corrupt);
    // A version-1 frame may be followed by a version-2 frame.
    const std::filesystem::path v1 = std::filesystem::path(STEPZIP_SOURCE_DIR) / "tests" / "golden" / "plotter.fc.stz";
    std::ifstream f(v1, std::ios::binary);
    const std::string old((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    ASSERT_EQ(old[4], 1);
    auto mixed = decompress(old + a);
    ASSERT_TRUE(mixed.ok()) << mixed.error().message;
    auto alone = decompress(old);
    ASSERT_TRUE(alone.ok());
    EXPECT_EQ(*mixed, *alone + x);
}

TEST(ContainerFrames, FixedOverheadIsSmall) {
    const std::string empty = must_compress("", {});
    EXPECT_LE(empty.size(), 20u);
    const std::string thirty = "105 60 66666666666666666666666";
    ASSERT_EQ(thirty.size(), 30u);
    EXPECT_LE(must_compress(thirty, {}).size(), 50u);
}

}  // namespace
}  // namespace stepzip
