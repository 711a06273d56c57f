// The timed format: a steps log read as one chain in (time, axes).
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "../src/container/memory_io.hpp"
#include "stepzip/container.hpp"
#include "stepzip/document.hpp"
#include "stepzip/segmenter.hpp"

namespace stepzip {
namespace {

using namespace std::string_literals;

std::vector<Block> read_blocks(std::string_view in, std::size_t block_steps, std::size_t piece) {
    BlockReader r(InputFormat::timed, "<test>", block_steps);
    for (std::size_t at = 0; at < in.size(); at += piece) {
        auto fed = r.feed(in.substr(at, piece), false);
        EXPECT_TRUE(fed.ok());
    }
    EXPECT_TRUE(r.feed({}, true).ok());
    std::vector<Block> out;
    Block b;
    while (r.next(b)) out.push_back(std::move(b));
    return out;
}

std::string render(const std::vector<Block>& blocks) {
    std::string out;
    for (const Block& b : blocks) {
        BlockWriter w(InputFormat::timed);  // each block renders on its own
        auto r = w.write(b, out);
        EXPECT_TRUE(r.ok()) << r.error().message;
    }
    return out;
}

// A controller-like log: moves at a constant rate per move, with idle ticks
// between steps, DIR set up in an idle tick before a move's first step, and
// now and then a DIR pin that flips and flips back with no step between.
std::string controller_log(std::uint32_t seed, int axes, std::size_t moves) {
    std::mt19937 rng(seed);
    std::string log;
    std::uint8_t level = 0;
    for (std::size_t m = 0; m < moves; ++m) {
        std::uint8_t dirs = 0;
        for (int a = 0; a < axes; ++a)
            if (rng() % 2) dirs = static_cast<std::uint8_t>(dirs | (2u << (2 * a)));
        log.append(rng() % 5, static_cast<char>(level));
        level = dirs;
        log.push_back(static_cast<char>(level));  // the DIR setup tick
        if (rng() % 7 == 0) {
            log.push_back(static_cast<char>(level ^ 0x02));
            log.push_back(static_cast<char>(level));
        }
        const unsigned gap = 1 + rng() % 9;
        const unsigned n = 1 + rng() % 40;
        for (unsigned k = 0; k < n; ++k) {
            std::uint8_t b = level;
            for (int a = 0; a < axes; ++a)
                if (a == 0 || rng() % 3 == 0) b = static_cast<std::uint8_t>(b | (1u << (2 * a)));
            log.push_back(static_cast<char>(b));
            log.append(gap, static_cast<char>(level));
        }
    }
    return log;
}

TEST(TimedFormat, NameAndChainShape) {
    EXPECT_EQ(format_name(InputFormat::timed), "timed");
    EXPECT_EQ(parse_format("timed"), InputFormat::timed);
    // Ticks: idle, X+ step, idle with X DIR set, X- step, Y+ step.
    auto chains = read_chains(InputFormat::timed, "\x00\x01\x02\x03\x04"s);
    ASSERT_TRUE(chains.ok()) << chains.error().message;
    ASSERT_EQ(chains->size(), 1u);
    const Chain& c = chains->front();
    EXPECT_EQ(c.axes, 3);
    ASSERT_EQ(c.steps.size(), 5u);  // one step per tick
    const int want[5][3] = {{1, 0, 0}, {1, 1, 0}, {1, 0, 0}, {1, -1, 0}, {1, 0, 1}};
    for (std::size_t k = 0; k < 5; ++k)
        for (int a = 0; a < 3; ++a) EXPECT_EQ(step_axis(c.steps[k], a), want[k][a]) << k << " " << a;
    EXPECT_EQ(c.end()[0], 5);
    EXPECT_EQ(c.end()[1], 0);
    EXPECT_EQ(c.end()[2], 1);
}

TEST(TimedFormat, RoundTripsByteExactlyAtEveryBlockSize) {
    for (std::uint32_t seed = 1; seed <= 6; ++seed) {
        const std::string log = controller_log(seed, 1 + seed % 4, 60);
        for (std::size_t bs : {std::size_t{1}, std::size_t{7}, std::size_t{100}, kDefaultBlockSteps}) {
            const auto whole = read_blocks(log, bs, log.size() + 1);
            EXPECT_EQ(render(whole), log) << "seed " << seed << " block " << bs;
            const auto pieces = read_blocks(log, bs, 3);
            ASSERT_EQ(pieces.size(), whole.size());
            for (std::size_t i = 0; i < whole.size(); ++i) {
                EXPECT_EQ(pieces[i].layout, whole[i].layout);
                ASSERT_EQ(pieces[i].chains.size(), 1u);
                EXPECT_EQ(pieces[i].chains[0].steps, whole[i].chains[0].steps);
            }
        }
    }
    // Every byte value, in every order of two.
    std::string all;
    for (int a = 0; a < 256; ++a)
        for (int b = 0; b < 256; b += 17) {
            all.push_back(static_cast<char>(a));
            all.push_back(static_cast<char>(b));
        }
    EXPECT_EQ(render(read_blocks(all, 1000, all.size())), all);
}

TEST(TimedFormat, LayoutHoldsOnlyDirChangesOfRestingAxes) {
    // Steps and idle ticks with no DIR change on a resting axis: empty layout.
    std::string plain = "\x01\x00\x00\x05\x00\x03\x02\x02\x03"s;
    auto blocks = read_blocks(plain, kDefaultBlockSteps, plain.size());
    ASSERT_EQ(blocks.size(), 1u);
    EXPECT_TRUE(blocks[0].layout.empty());
    // One DIR setup on a resting axis (tick 2): start level, gap 2, mask 1.
    std::string setup = "\x01\x00\x02\x03"s;
    blocks = read_blocks(setup, kDefaultBlockSteps, setup.size());
    EXPECT_EQ(blocks[0].layout, "\x00\x02\x01"s);
    // A block cut after the setup starts from the held level.
    blocks = read_blocks(setup, 3, setup.size());
    ASSERT_EQ(blocks.size(), 2u);
    EXPECT_EQ(blocks[1].layout, "\x01"s);
    EXPECT_EQ(render(blocks), setup);
}

TEST(TimedFormat, RejectsLayoutsThatDoNotFit) {
    auto blocks = read_blocks("\x01\x00\x02\x03"s, kDefaultBlockSteps, 4);
    ASSERT_EQ(blocks.size(), 1u);
    const std::string bad[] = {
        "\x10"s,             // level mask beyond four axes
        "\x00\x02\x00"s,     // empty flip mask
        "\x00\x03\x01"s,     // flip on the stepping tick of that axis
        "\x00\x09\x01"s,     // flip after the last tick
        "\x00\x02\x01\x00\x02"s,  // second flip on the same tick
        "\x00\x02"s,         // truncated
    };
    for (const std::string& layout : bad) {
        Block b = blocks[0];
        b.layout = layout;
        std::string out;
        BlockWriter w(InputFormat::timed);
        auto r = w.write(b, out);
        EXPECT_FALSE(r.ok()) << "layout size " << layout.size();
        if (!r.ok()) EXPECT_EQ(r.error().code, Errc::corrupt);
        EXPECT_TRUE(out.empty());
    }
    // A chain step that does not advance time is not a tick.
    Chain c;
    c.axes = 3;
    c.steps = {0x05, 0x04};
    EXPECT_EQ(write_chains(InputFormat::timed, {c}).error().code, Errc::invalid_argument);
    c.steps = {0x05, 0x01};
    auto ok = write_chains(InputFormat::timed, {c});
    ASSERT_TRUE(ok.ok());
    EXPECT_EQ(*ok, "\x01\x00"s);
}

TEST(TimedFormat, ConstantRateStretchIsOneSegment) {
    // 2000 ticks at 3 X steps per 7 ticks and 1 Y step per 7 ticks: straight
    // in (time, x, y), so the reverse interpolation needs one segment where
    // the steps format (time dropped) needs none of this.
    std::string log;
    for (int t = 0; t < 2100; ++t) {
        std::uint8_t b = 0;
        if ((3 * t) % 7 < 3) b |= 0x01;
        if (t % 7 == 3) b |= 0x04;
        log.push_back(static_cast<char>(b));
    }
    auto chains = read_chains(InputFormat::timed, log);
    ASSERT_TRUE(chains.ok());
    std::vector<Segment> segs;
    ASSERT_TRUE(segment_steps(chains->front().steps, 3, Profile::eval8, SegmenterKind::greedy, segs).ok());
    EXPECT_EQ(segs.size(), 1u);
}

std::string corpus(const char* name) {
    std::ifstream f(std::string(STEPZIP_SOURCE_DIR) + "/corpora/timed/" + name, std::ios::binary);
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}

TEST(TimedFormat, GeneratedStreamsCompressByteExactly) {
    for (const char* name : {"trapezoid-2axis.steps", "trapezoid-3axis.steps"}) {
        const std::string in = corpus(name);
        ASSERT_GT(in.size(), 100000u) << name;
        CompressOptions timed;
        timed.format = InputFormat::timed;
        auto z = compress(in, timed);
        ASSERT_TRUE(z.ok()) << z.error().message;
        auto back = decompress(*z);
        ASSERT_TRUE(back.ok()) << back.error().message;
        EXPECT_TRUE(*back == in) << name;
        // Smaller block size: chains continue across blocks.
        timed.block_steps = 50000;
        auto zb = compress(in, timed);
        ASSERT_TRUE(zb.ok());
        auto backb = decompress(*zb);
        ASSERT_TRUE(backb.ok());
        EXPECT_TRUE(*backb == in) << name;
    }
}

// A timed log's blocks hold kDefaultTimedBlockTicks ticks unless the caller
// names a block size: a log of more than 2^20 ticks is one block.
TEST(TimedFormat, DefaultBlocksOfATimedLogHoldFourTimesTheSteps) {
    const std::string in = controller_log(5, 2, 12000);
    ASSERT_GT(in.size(), kDefaultBlockSteps + 1000);
    ASSERT_LT(in.size(), kDefaultTimedBlockTicks);
    CompressOptions opt;
    opt.format = InputFormat::timed;
    opt.level = 1;
    auto z = compress(in, opt);
    ASSERT_TRUE(z.ok()) << z.error().message;
    opt.block_steps = kDefaultBlockSteps;
    auto zb = compress(in, opt);
    ASSERT_TRUE(zb.ok()) << zb.error().message;
    auto whole = inspect_stream(stz::memory_reader(*z)), named = inspect_stream(stz::memory_reader(*zb));
    ASSERT_TRUE(whole.ok() && named.ok());
    EXPECT_EQ(whole->blocks, 1u);
    EXPECT_EQ(named->blocks, 2u);
    for (const std::string* frame : {&*z, &*zb}) {
        auto back = decompress(*frame);
        ASSERT_TRUE(back.ok()) << back.error().message;
        EXPECT_TRUE(*back == in);
    }
}

}  // namespace
}  // namespace stepzip
