// Chain files: writer(reader(input)) is the identical bytes, for hand-written
// tricky inputs and random ones (fixed seeds); the blocks do not depend on how
// the input is cut into feed() pieces; small blocks split chains correctly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "stepzip/document.hpp"

namespace stepzip {
namespace {

using namespace std::string_literals;

std::vector<Block> read_blocks(InputFormat f, std::string_view in, std::size_t block_steps,
                               std::size_t chunk, std::uint32_t seed = 0) {
    BlockReader r(f, "t", block_steps);
    std::vector<Block> out;
    std::mt19937 rng(seed);
    std::size_t pos = 0;
    Block b;
    while (pos < in.size()) {
        std::size_t n = chunk;
        if (chunk == 0) n = 1 + rng() % 97;  // random piece sizes
        n = std::min(n, in.size() - pos);
        const bool last = pos + n == in.size();
        auto res = r.feed(in.substr(pos, n), last);
        EXPECT_TRUE(res.ok()) << res.error().message;
        if (!res.ok()) return out;
        pos += n;
        while (r.next(b)) out.push_back(std::move(b));
    }
    if (in.empty()) {
        auto res = r.feed({}, true);
        EXPECT_TRUE(res.ok()) << res.error().message;
    }
    while (r.next(b)) out.push_back(std::move(b));
    return out;
}

std::string render(InputFormat f, const std::vector<Block>& blocks) {
    BlockWriter w(f);
    std::string out;
    for (const Block& b : blocks) {
        auto res = w.write(b, out);
        EXPECT_TRUE(res.ok()) << res.error().message;
    }
    return out;
}

bool same_blocks(const std::vector<Block>& a, const std::vector<Block>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (a[i].axes != b[i].axes || a[i].chains != b[i].chains || a[i].continues != b[i].continues ||
            a[i].open != b[i].open || a[i].layout != b[i].layout)
            return false;
    }
    return true;
}

// Structural promises of the reader about its blocks.
void check_blocks(InputFormat f, const std::vector<Block>& blocks, std::size_t block_steps) {
    ASSERT_FALSE(blocks.empty());
    for (std::size_t i = 0; i < blocks.size(); ++i) {
        const Block& b = blocks[i];
        std::size_t steps = 0;
        for (const Chain& c : b.chains) {
            EXPECT_EQ(c.axes, b.axes);
            steps += c.steps.size();
            for (Step s : c.steps) EXPECT_TRUE(step_valid(s, c.axes));
        }
        EXPECT_LE(steps, block_steps) << "block " << i;
        EXPECT_FALSE(b.layout.empty() && steps != 0) << "reader layouts are explicit";
        if (i == 0) EXPECT_FALSE(b.continues);
        if (i + 1 < blocks.size()) EXPECT_EQ(b.open, blocks[i + 1].continues) << "block " << i;
        if (i + 1 == blocks.size()) EXPECT_FALSE(b.open);
        if (b.open) EXPECT_FALSE(b.chains.empty());
        if (b.continues) {
            ASSERT_FALSE(b.chains.empty());
            ASSERT_FALSE(blocks[i - 1].chains.empty());
            EXPECT_EQ(b.chains[0].start, blocks[i - 1].chains.back().end()) << "block " << i;
        }
        if (f == InputFormat::freeman) EXPECT_EQ(b.axes, 2);
    }
}

// The full round-trip property for one input.
void round_trip(InputFormat f, const std::string& in, const std::vector<std::size_t>& sizes = {1, 2, 3, 5, 17, kDefaultBlockSteps}) {
    for (std::size_t bs : sizes) {
        SCOPED_TRACE("block_steps " + std::to_string(bs));
        const auto whole = read_blocks(f, in, bs, in.size() + 1);
        check_blocks(f, whole, bs);
        ASSERT_EQ(render(f, whole), in);
        EXPECT_TRUE(same_blocks(whole, read_blocks(f, in, bs, 1))) << "1-byte feeding differs";
        EXPECT_TRUE(same_blocks(whole, read_blocks(f, in, bs, 0, 7))) << "random feeding differs";
    }
}

Chain chain2(std::int64_t x, std::int64_t y, const char* codes) { return *from_freeman(x, y, codes); }

// ---- freeman --------------------------------------------------------------------

TEST(FreemanRoundTrip, HandWrittenInputs) {
    const std::vector<std::string> inputs = {
        "",
        "\n",
        "\n\n\n",
        "0 0 0123\n",
        "0 0 0123",
        "0 0 0123\r\n",
        "0 0 0123\r\n5 5 7\n",
        "# a comment\n0 0 01\n",
        "   # indented comment\n1 1 2\n",
        "#\r\n#\n#",
        "+5 -007 0123  \n",
        "-0 00 7\n",
        "5 7\n",
        "5 7",
        "5 7 \n",
        "5 7\t \r\n",
        "5\t7\t012\t\n",
        "\t1 2 3\n",
        "1  2  345\r\n1 2 3\n",
        "   \n\t\n",
        "# caf\xc3\xa9 \xff\xfe latin-1 and utf-8 bytes\n0 0 0\n",
        "1 2 3\n\n# x\r\n4 5 6",
        "-4611686018427387904 4611686018427387904 0246\n",
        "+0 -0 1357\n",
        "0 0 01234567012345670123456701234567\n0 0\n",
        "# only a comment without newline",
        "  ",
    };
    for (const auto& in : inputs) {
        SCOPED_TRACE("input: " + in);
        round_trip(InputFormat::freeman, in);
    }
}

TEST(FreemanRoundTrip, ChainsAreRead) {
    auto chains = read_chains(InputFormat::freeman, "# c\n+5 -007 0123  \r\n\n1 2\n-0 00 7");
    ASSERT_TRUE(chains.ok()) << chains.error().message;
    ASSERT_EQ(chains->size(), 3u);
    EXPECT_EQ((*chains)[0], chain2(5, -7, "0123"));
    EXPECT_EQ((*chains)[1], chain2(1, 2, ""));
    EXPECT_EQ((*chains)[2], chain2(0, 0, "7"));
}

// Runs of codes of every length up to past four 16-byte pieces, ended by
// every kind of byte: each code read as its step, and a byte that is no code
// (the ones next to '0'..'7' too) named at its column.
TEST(FreemanRoundTrip, CodeRunsOfEveryLengthAndEnd) {
    std::mt19937 rng(5);
    for (std::size_t n = 1; n <= 70; ++n) {
        std::string codes;
        for (std::size_t i = 0; i < n; ++i) codes.push_back(static_cast<char>('0' + rng() % 8));
        for (const std::string end : {"\n", " \n", "\r\n", ""}) {
            auto chains = read_chains(InputFormat::freeman, "3 -2 " + codes + end);
            ASSERT_TRUE(chains.ok()) << chains.error().message;
            ASSERT_EQ(chains->size(), 1u);
            EXPECT_EQ((*chains)[0], chain2(3, -2, codes.c_str())) << n;
        }
        for (const char bad : {'8', '9', '/', ':', 'a', '\x80', '\xff'}) {
            auto chains = read_chains(InputFormat::freeman, "0 0 " + codes + bad + "0\n", "t.txt");
            ASSERT_FALSE(chains.ok()) << n;
            EXPECT_EQ(chains.error().message.rfind("t.txt:1:" + std::to_string(5 + n) + ": ", 0), 0u)
                << chains.error().message;
        }
    }
}

TEST(FreemanRoundTrip, CanonicalLinesCostAFewLayoutBytes) {
    std::string in;
    for (int i = 0; i < 1000; ++i) in += std::to_string(i) + " " + std::to_string(-i) + " 0011223344556677\n";
    auto blocks = read_blocks(InputFormat::freeman, in, kDefaultBlockSteps, in.size());
    ASSERT_EQ(blocks.size(), 1u);
    EXPECT_LE(blocks[0].layout.size(), 3u);
    EXPECT_EQ(render(InputFormat::freeman, blocks), in);
    std::string crlf;
    for (char c : in) {
        if (c == '\n') crlf += '\r';
        crlf += c;
    }
    blocks = read_blocks(InputFormat::freeman, crlf, kDefaultBlockSteps, crlf.size());
    EXPECT_LE(blocks[0].layout.size(), 3u);
}

TEST(FreemanRoundTrip, LongLineSplitsAcrossBlocks) {
    std::mt19937 rng(11);
    std::string codes;
    for (int i = 0; i < 200000; ++i) codes += static_cast<char>('0' + rng() % 8);
    const std::string in = "  -3 +4\t" + codes + " \r\n# after\n7 7 0\n";
    const std::size_t bs = 1000;
    auto blocks = read_blocks(InputFormat::freeman, in, bs, 4096);
    check_blocks(InputFormat::freeman, blocks, bs);
    EXPECT_EQ(blocks.size(), 201u);
    EXPECT_EQ(render(InputFormat::freeman, blocks), in);
    auto chains = read_chains(InputFormat::freeman, in);
    ASSERT_TRUE(chains.ok());
    ASSERT_EQ(chains->size(), 2u);
    EXPECT_EQ((*chains)[0], chain2(-3, 4, codes.c_str()));
    round_trip(InputFormat::freeman, in, {7, 4096, 50000});
}

TEST(FreemanRoundTrip, HugeCommentIsCutByLayoutSize) {
    std::string in = "0 0 01\n#";
    in.append(5000, 'x');
    in += "\n1 1 2\n";
    auto blocks = read_blocks(InputFormat::freeman, in, 4, in.size());
    check_blocks(InputFormat::freeman, blocks, 4);
    EXPECT_GE(blocks.size(), 5000u / 256);
    for (const Block& b : blocks) EXPECT_LE(b.layout.size(), 256u + 16u);
    round_trip(InputFormat::freeman, in, {4, 300});
}

std::string random_spaces(std::mt19937& rng) {
    std::string s;
    const int n = 1 + static_cast<int>(rng() % 3);
    for (int i = 0; i < n; ++i) s += rng() % 4 == 0 ? '\t' : ' ';
    return s;
}

std::string random_number(std::mt19937& rng, long long v, bool odd) {
    std::string s;
    if (odd && rng() % 3 == 0) s += v < 0 ? "-" : (rng() % 2 ? "+" : "");
    else if (v < 0) s += "-";
    if (odd && rng() % 3 == 0) s.append(rng() % 4, '0');
    s += std::to_string(v < 0 ? -v : v);
    return s;
}

std::string random_freeman(std::mt19937& rng) {
    std::string out;
    const int lines = static_cast<int>(rng() % 40);
    const bool crlf_file = rng() % 4 == 0;
    for (int i = 0; i < lines; ++i) {
        const unsigned kind = rng() % 10;
        if (kind == 0) {
            out += "#";
            const int n = static_cast<int>(rng() % 20);
            for (int k = 0; k < n; ++k) {
                unsigned char c = static_cast<unsigned char>(0x20 + rng() % 0xE0);
                if (c == 0x7F) c = '\t';
                out += static_cast<char>(c);
            }
        } else if (kind == 1) {
            if (rng() % 2) out += random_spaces(rng);
        } else {
            const bool odd = kind == 2 || kind == 3;
            if (odd && rng() % 3 == 0) out += random_spaces(rng);
            out += random_number(rng, static_cast<long long>(rng() % 2001) - 1000, odd);
            out += odd ? random_spaces(rng) : " ";
            out += random_number(rng, static_cast<long long>(rng() % 2001) - 1000, odd);
            const int n = rng() % 8 == 0 ? 0 : static_cast<int>(rng() % 60);
            if (n > 0) {
                out += odd ? random_spaces(rng) : " ";
                for (int k = 0; k < n; ++k) out += static_cast<char>('0' + rng() % 8);
            }
            if (odd && rng() % 3 == 0) out += random_spaces(rng);
        }
        if (i + 1 == lines && rng() % 3 == 0) break;  // no final newline
        out += (crlf_file != (rng() % 10 == 0)) ? "\r\n" : "\n";
    }
    return out;
}

TEST(FreemanRoundTrip, RandomFiles) {
    std::mt19937 rng(20240501);
    for (int t = 0; t < 300; ++t) {
        const std::string in = random_freeman(rng);
        SCOPED_TRACE("case " + std::to_string(t) + ": " + in);
        round_trip(InputFormat::freeman, in, {1, 3, 16, 1000});
        if (HasFatalFailure()) return;
    }
}

// ---- points ---------------------------------------------------------------------

TEST(PointsRoundTrip, HandWrittenInputs) {
    const std::vector<std::string> inputs = {
        "",
        "\n",
        "0 0\n1 0\n1 1\n",
        "0 0\n1 0\n1 1",
        "0,0\n1,0\n",
        "0, 0\n1, 1\n",
        "0\t0\n-1\t-1\n",
        "0 0\r\n1 0\r\n\r\n5 5\r\n",
        "\n0 0\n1 1\n\n\n5 5\n5 6",
        "+1 007\n2 +8\n",
        "  1 2  \n2 3",
        "1 2 3\n2 3 4\n2 3 5\n\n0 0 0\n",
        "1 2 3 4 5 6\n2 3 4 5 6 7\n",
        "0 0\n# comment inside a chain\n1 0\n",
        "# header\n0 ,1\n1, 2\n1 ,3\n",
        "0 0\n1 1\n  \n2 2\n",
        "0 0\n1 1\n\t\r\n2 2\n",
        "0 0\n1 1\n2,2\n3,3\n4 4\r\n5 5\r\n",
        "-0 -0\n1 1\n",
        "0 0\n1 1\n\n",
        "  # indented comment\n0 0\n",
        "0   0\n1   1\n",
        // Lines next to the in-place reading of canonical lines: mixed
        // separators, "-0", leading zeros, 18 and 19 digits, CR LF.
        "10,-10\n11,-9\n11, -8\n12\t-8\n",
        "0 -1\n1 -0\n2 1\n",
        "0 0\n1 01\n2 2\n",
        "100000000000000000 0\n100000000000000001 -1\n",
        "1000000000000000000 0\n1000000000000000001 -1\n",
        "5 5\r\n6 6\n7 7\r\n",
        "1,2,3\n2,2,3\n2, 3,3\n",
    };
    for (const auto& in : inputs) {
        SCOPED_TRACE("input: " + in);
        round_trip(InputFormat::points, in);
    }
}

TEST(PointsRoundTrip, ChainsAreRead) {
    auto chains = read_chains(InputFormat::points, "0,0\n1,1\n1,2\n\n# c\n5 5\n4 5\n");
    ASSERT_TRUE(chains.ok()) << chains.error().message;
    ASSERT_EQ(chains->size(), 2u);
    EXPECT_EQ((*chains)[0], chain2(0, 0, "12"));
    EXPECT_EQ((*chains)[1], chain2(5, 5, "4"));
    auto three = read_chains(InputFormat::points, "0 0 0\n1 0 -1\n");
    ASSERT_TRUE(three.ok());
    ASSERT_EQ(three->size(), 1u);
    EXPECT_EQ((*three)[0].axes, 3);
    const int d[3] = {1, 0, -1};
    EXPECT_EQ((*three)[0].steps, std::vector<Step>{make_step(d, 3)});
}

TEST(PointsRoundTrip, CanonicalChainsCostAFewLayoutBytes) {
    std::vector<Chain> chains;
    std::mt19937 rng(5);
    for (int i = 0; i < 300; ++i) {
        Chain c;
        c.start[0] = static_cast<int>(rng() % 100);
        c.start[1] = -static_cast<int>(rng() % 100);
        for (int k = 0; k < 20; ++k) c.steps.push_back(freeman_to_step(static_cast<int>(rng() % 8)));
        chains.push_back(c);
    }
    auto text = write_chains(InputFormat::points, chains);
    ASSERT_TRUE(text.ok());
    auto blocks = read_blocks(InputFormat::points, *text, kDefaultBlockSteps, text->size());
    ASSERT_EQ(blocks.size(), 1u);
    EXPECT_LE(blocks[0].layout.size(), 6u);
    EXPECT_EQ(blocks[0].chains, chains);
    EXPECT_EQ(render(InputFormat::points, blocks), *text);
}

std::string random_points(std::mt19937& rng) {
    const int axes = 2 + static_cast<int>(rng() % 5);
    const char* seps[] = {" ", ",", ", ", "\t", " , ", "  "};
    const char* sep = seps[rng() % 6];
    const bool crlf = rng() % 4 == 0;
    std::string out;
    const int chains = static_cast<int>(rng() % 6);
    for (int c = 0; c < chains; ++c) {
        long long p[6];
        for (int a = 0; a < axes; ++a) p[a] = static_cast<long long>(rng() % 41) - 20;
        const int n = 1 + static_cast<int>(rng() % 30);
        for (int i = 0; i < n; ++i) {
            if (i > 0) {
                bool moved = false;
                while (!moved)  // a pass of all-zero moves leaves p as it was
                    for (int a = 0; a < axes; ++a) {
                        const int d = static_cast<int>(rng() % 3) - 1;
                        p[a] += d;
                        moved = moved || d != 0;
                    }
            }
            const bool odd = rng() % 8 == 0;
            if (odd && rng() % 2) out += " ";
            for (int a = 0; a < axes; ++a) {
                if (a) out += (odd && rng() % 3 == 0) ? seps[rng() % 6] : sep;
                out += random_number(rng, p[a], odd);
            }
            if (odd && rng() % 2) out += "\t";
            if (c + 1 == chains && i + 1 == n && rng() % 3 == 0) return out;
            out += (crlf != (rng() % 12 == 0)) ? "\r\n" : "\n";
            if (rng() % 15 == 0) out += crlf ? "# note\r\n" : "#\xa0note\n";
        }
        if (c + 1 < chains || rng() % 2) {
            out += rng() % 6 == 0 ? " \n" : crlf ? "\r\n" : "\n";
            if (rng() % 5 == 0) out += "\n";
        }
    }
    return out;
}

TEST(PointsRoundTrip, RandomFiles) {
    std::mt19937 rng(777);
    for (int t = 0; t < 300; ++t) {
        const std::string in = random_points(rng);
        SCOPED_TRACE("case " + std::to_string(t) + ": " + in);
        round_trip(InputFormat::points, in, {1, 2, 7, 1000});
        if (HasFatalFailure()) return;
    }
}

// ---- steps ----------------------------------------------------------------------

TEST(StepsRoundTrip, HandWrittenInputs) {
    const std::vector<std::string> inputs = {
        ""s,
        "\x01"s,
        "\x00"s,
        "\x00\x00\x00\x00"s,
        "\x01\x05\x04\x07\x03\x0f\x0c\x0d"s,
        "\x02\x01\x02\x03"s,             // DIR on a resting axis, then a step
        "\xff\xaa\x55\x00\x80\x40"s,     // all axes, DIR without steps, axis 3
        "\x10\x30\x20\x00\x01"s,
    };
    for (const auto& in : inputs) {
        SCOPED_TRACE("input size " + std::to_string(in.size()));
        round_trip(InputFormat::steps, in);
    }
}

TEST(StepsRoundTrip, AllByteValuesAndRandomLogs) {
    std::string all;
    for (int b = 0; b < 256; ++b) all += static_cast<char>(b);
    round_trip(InputFormat::steps, all);
    std::mt19937 rng(99);
    for (int t = 0; t < 100; ++t) {
        std::string in;
        const int n = static_cast<int>(rng() % 400);
        for (int i = 0; i < n; ++i) in += static_cast<char>(rng() % 256);
        round_trip(InputFormat::steps, in, {1, 5, 64, 100000});
        if (HasFatalFailure()) return;
    }
}

TEST(StepsRoundTrip, ChainIsReadFromTheOrigin) {
    auto chains = read_chains(InputFormat::steps, "\x01\x00\x05\x0f\x02\x10"s);
    ASSERT_TRUE(chains.ok());
    ASSERT_EQ(chains->size(), 1u);
    const Chain& c = (*chains)[0];
    EXPECT_EQ(c.axes, 3);
    EXPECT_EQ(c.start, Point{});
    ASSERT_EQ(c.steps.size(), 4u);
    EXPECT_EQ(c.steps[0], 0x01);
    EXPECT_EQ(c.steps[2], 0x0f);
    EXPECT_EQ(c.end()[0], 1);
    EXPECT_EQ(c.end()[1], 0);
    EXPECT_EQ(c.end()[2], 1);
}

// A synthetic STEP/DIR log: moves between random points with Bresenham
// ticks, DIR set `setup` ticks before the first step of a move and held,
// `idle` idle ticks after every step.
std::string synthetic_log(std::mt19937& rng, int moves, int setup, int idle) {
    std::string log;
    std::uint8_t dir = 0;
    for (int m = 0; m < moves; ++m) {
        const int dx = static_cast<int>(rng() % 201) - 100, dy = static_cast<int>(rng() % 201) - 100;
        std::uint8_t want = static_cast<std::uint8_t>((dx < 0 ? 0x02 : 0) | (dy < 0 ? 0x08 : 0));
        for (int k = 0; k < setup && want != dir; ++k) log += static_cast<char>(want);
        dir = want;
        const int L = std::max(std::abs(dx), std::abs(dy)), S = std::min(std::abs(dx), std::abs(dy));
        int e = L / 2;
        for (int k = 0; k < L; ++k) {
            std::uint8_t b = dir;
            const bool xl = std::abs(dx) >= std::abs(dy);
            b |= xl ? 0x01 : 0x04;
            e -= S;
            if (e < 0) {
                e += L;
                b |= xl ? 0x04 : 0x01;
            }
            // no STEP on an axis with zero travel
            if (dx == 0) b &= static_cast<std::uint8_t>(~0x01);
            if (dy == 0) b &= static_cast<std::uint8_t>(~0x04);
            if ((b & 0x55) == 0) continue;
            log += static_cast<char>(b);
            log.append(static_cast<std::size_t>(idle), static_cast<char>(dir));
        }
    }
    return log;
}

TEST(StepsRoundTrip, StickyDirKeepsSyntheticLogLayoutsSmall) {
    std::mt19937 rng(3);
    for (int setup : {0, 1, 3}) {
        for (int idle : {0, 2}) {
            const std::string log = synthetic_log(rng, 200, setup, idle);
            auto blocks = read_blocks(InputFormat::steps, log, kDefaultBlockSteps, log.size());
            ASSERT_EQ(blocks.size(), 1u);
            ASSERT_EQ(render(InputFormat::steps, blocks), log);
            const std::size_t steps = blocks[0].chains[0].steps.size();
            // Under a "DIR 0 on resting axes" convention every tick with a
            // DIR bit on a resting axis would be an exception.
            std::size_t zero_exceptions = 0;
            for (char ch : log) {
                const auto b = static_cast<std::uint8_t>(ch);
                if ((b & 0xAA & ~((b & 0x55) << 1)) != 0) ++zero_exceptions;
            }
            // Sticky DIR: a flip only where a resting axis changes its DIR
            // level, at most two per move, each with the runs it splits.
            // Idle ticks at a fixed pace fold into paced runs.
            EXPECT_LE(blocks[0].layout.size(), 8u + 8u * 200u);
            std::cout << "[ measure  ] setup " << setup << " idle " << idle << ": " << log.size()
                      << " ticks, " << steps << " steps, layout " << blocks[0].layout.size()
                      << " bytes (sticky DIR); " << zero_exceptions
                      << " exceptions under DIR-0-at-rest\n";
            round_trip(InputFormat::steps, log, {1, 1000});
        }
    }
}

// A log written one step at a time: each tick's byte holds the DIR bits of
// its stepping axes only (resting axes at DIR 0), `idle` idle ticks of 0
// after every step.
std::string zero_dir_log(std::mt19937& rng, int moves, int idle) {
    std::string log;
    for (int m = 0; m < moves; ++m) {
        const int dx = static_cast<int>(rng() % 201) - 100, dy = static_cast<int>(rng() % 201) - 100;
        const int L = std::max(std::abs(dx), std::abs(dy)), S = std::min(std::abs(dx), std::abs(dy));
        const bool xl = std::abs(dx) >= std::abs(dy);
        int e = L / 2;
        for (int k = 0; k < L; ++k) {
            bool minor = false;
            e -= S;
            if (e < 0) {
                e += L;
                minor = true;
            }
            const bool x = xl || minor, y = !xl || minor;
            std::uint8_t b = 0;
            if (x && dx != 0) b |= dx < 0 ? 0x03 : 0x01;
            if (y && dy != 0) b |= dy < 0 ? 0x0C : 0x04;
            if (b == 0) continue;
            log += static_cast<char>(b);
            log.append(static_cast<std::size_t>(idle), '\0');
        }
    }
    return log;
}

TEST(StepsRoundTrip, DirZeroAtRestIsChosenWhereItHasFewerExceptions) {
    std::mt19937 rng(5);
    for (int idle : {0, 2}) {
        const std::string log = zero_dir_log(rng, 200, idle);
        auto blocks = read_blocks(InputFormat::steps, log, kDefaultBlockSteps, log.size());
        ASSERT_EQ(blocks.size(), 1u);
        ASSERT_EQ(render(InputFormat::steps, blocks), log);
        // Sticky DIR would flip a resting axis after about every negative
        // minor step; DIR 0 at rest has no exception at all.
        std::size_t sticky_flips = 0;
        std::uint8_t level = 0;
        for (char ch : log) {
            const auto b = static_cast<std::uint8_t>(ch);
            if (((b ^ level) & 0xAA & ~((b & 0x55) << 1)) != 0) ++sticky_flips;
            level = b & 0xAA;
        }
        EXPECT_GT(sticky_flips, 1000u);
        ASSERT_FALSE(blocks[0].layout.empty());
        EXPECT_EQ(static_cast<std::uint8_t>(blocks[0].layout[0]), 0xD1);
        EXPECT_LE(blocks[0].layout.size(), 8u + 4u * 200u);
        // Every block (small ones continue a move mid-way) chooses alone,
        // whatever the feeding.
        round_trip(InputFormat::steps, log, {1, 7, 1000, 4096, 5000, kDefaultBlockSteps});
    }
    // A sticky log keeps the sticky layout.
    const std::string sticky = synthetic_log(rng, 200, 1, 0);
    auto blocks = read_blocks(InputFormat::steps, sticky, kDefaultBlockSteps, sticky.size());
    ASSERT_EQ(blocks.size(), 1u);
    ASSERT_FALSE(blocks[0].layout.empty());
    EXPECT_NE(static_cast<std::uint8_t>(blocks[0].layout[0]), 0xD1);
    // A block picks its convention on its first 4096 steps and keeps it.
    const std::string zero = zero_dir_log(rng, 200, 0);
    ASSERT_GT(sticky.size(), 4096u);
    ASSERT_GT(zero.size(), 4096u);
    for (const auto& [log, zero_first] : {std::pair{sticky + zero, false}, std::pair{zero + sticky, true}}) {
        blocks = read_blocks(InputFormat::steps, log, kDefaultBlockSteps, log.size());
        ASSERT_EQ(blocks.size(), 1u);
        ASSERT_FALSE(blocks[0].layout.empty());
        EXPECT_EQ(static_cast<std::uint8_t>(blocks[0].layout[0]) == 0xD1, zero_first);
        round_trip(InputFormat::steps, log, {kDefaultBlockSteps});
    }
}

TEST(StepsRoundTrip, DirZeroAtRestOnlyAsTheFirstOperation) {
    Block b;
    b.axes = 2;
    Chain c;
    c.axes = 2;
    c.steps = {make_step2(-1, 0), make_step2(0, 1)};
    b.chains.push_back(c);
    b.layout = "\xD1\x01"s;  // DIR 0 at rest, two steps
    std::string out;
    ASSERT_TRUE(BlockWriter(InputFormat::steps).write(b, out).ok());
    EXPECT_EQ(out, "\x03\x04"s);  // the sticky convention would give 03 06
    b.layout = "\x00\xD1\x00"s;
    out.clear();
    auto res = BlockWriter(InputFormat::steps).write(b, out);
    ASSERT_FALSE(res.ok());
    EXPECT_EQ(res.error().code, Errc::corrupt);
}

TEST(StepsRoundTrip, VaryingGapsAfterSingleStepsFormGapLists) {
    // One step, then 1..5 idle ticks (a rate that changes every step), then
    // a long constant pace, then varying gaps again.
    std::mt19937 rng(8);
    std::string log;
    auto pair = [&](int g) {
        log += '\x01';
        log.append(static_cast<std::size_t>(g), '\0');
    };
    for (int i = 0; i < 100; ++i) pair(1 + static_cast<int>(rng() % 5));
    for (int i = 0; i < 100; ++i) pair(3);
    for (int i = 0; i < 100; ++i) pair(1 + static_cast<int>(rng() % 5));
    auto blocks = read_blocks(InputFormat::steps, log, kDefaultBlockSteps, log.size());
    ASSERT_EQ(blocks.size(), 1u);
    ASSERT_EQ(render(InputFormat::steps, blocks), log);
    const std::string& layout = blocks[0].layout;
    // gap list, pace, gap list: a byte per pair in a list, a few for the pace.
    ASSERT_GE(layout.size(), 2u);
    EXPECT_EQ(static_cast<std::uint8_t>(layout[0]), 0xD2);
    EXPECT_EQ(std::count(layout.begin(), layout.end(), '\xD0'), 1);
    EXPECT_LE(layout.size(), 220u);
    round_trip(InputFormat::steps, log, {1, 7, 150, kDefaultBlockSteps});
    // A lone pace of a few pairs keeps its paced op.
    const std::string paced = "\x01\x00\x00\x01\x00\x00\x01\x00\x00\x05"s;
    blocks = read_blocks(InputFormat::steps, paced, kDefaultBlockSteps, paced.size());
    ASSERT_EQ(blocks.size(), 1u);
    EXPECT_EQ(blocks[0].layout, "\xD0\x02\x03\x00"s);
}

TEST(StepsRoundTrip, GapListsAreChecked) {
    Block b;
    b.axes = 2;
    Chain c;
    c.axes = 2;
    c.steps = {make_step2(1, 0), make_step2(1, 0)};
    b.chains.push_back(c);
    b.layout = "\xD2\x02\x00\x02"s;  // two pairs: gaps 1 and 3
    std::string out;
    ASSERT_TRUE(BlockWriter(InputFormat::steps).write(b, out).ok());
    EXPECT_EQ(out, "\x01\x00\x01\x00\x00\x00"s);
    for (const std::string bad : {"\xD2\x01\x00\x00\x00"s, "\xD2\x03\x00\x00\x00"s, "\xD2\x02\x00"s}) {
        b.layout = bad;
        out.clear();
        auto res = BlockWriter(InputFormat::steps).write(b, out);
        ASSERT_FALSE(res.ok());
        EXPECT_EQ(res.error().code, Errc::corrupt);
    }
}

TEST(StepsRoundTrip, WriteChainsUsesStickyDir) {
    Chain c;
    c.axes = 2;
    c.steps = {make_step2(-1, 0), make_step2(0, 1), make_step2(1, 1)};
    auto bytes = write_chains(InputFormat::steps, {c});
    ASSERT_TRUE(bytes.ok());
    // -x sets DIR x; the +y step keeps it; the +x+y step clears it.
    EXPECT_EQ(*bytes, "\x03\x06\x05"s);
    auto back = read_chains(InputFormat::steps, *bytes);
    ASSERT_TRUE(back.ok());
    EXPECT_EQ((*back)[0], c);
}

// ---- whole-file conveniences ----------------------------------------------------

TEST(WriteChains, CanonicalTextRoundTrips) {
    const std::vector<Chain> chains = {chain2(0, 0, "0020020020"), chain2(-5, 3, ""),
                                       chain2(7, -7, "1357")};
    auto fc = write_chains(InputFormat::freeman, chains);
    ASSERT_TRUE(fc.ok());
    EXPECT_EQ(*fc, "0 0 0020020020\n-5 3\n7 -7 1357\n");
    auto back = read_chains(InputFormat::freeman, *fc);
    ASSERT_TRUE(back.ok());
    EXPECT_EQ(*back, chains);

    auto pts = write_chains(InputFormat::points, {chain2(0, 0, "01"), chain2(5, 5, "")});
    ASSERT_TRUE(pts.ok());
    EXPECT_EQ(*pts, "0 0\n1 0\n2 1\n\n5 5\n");
    auto pback = read_chains(InputFormat::points, *pts);
    ASSERT_TRUE(pback.ok());
    EXPECT_EQ(*pback, (std::vector<Chain>{chain2(0, 0, "01"), chain2(5, 5, "")}));
}

TEST(WriteChains, RefusesChainsThatDoNotFit) {
    Chain three;
    three.axes = 3;
    three.steps = {0x10};
    EXPECT_EQ(write_chains(InputFormat::freeman, {three}).error().code, Errc::invalid_argument);
    Chain off = chain2(1, 0, "0");
    EXPECT_EQ(write_chains(InputFormat::steps, {off}).error().code, Errc::invalid_argument);
    Chain five;
    five.axes = 5;
    five.steps = {0x100};
    EXPECT_EQ(write_chains(InputFormat::steps, {five}).error().code, Errc::invalid_argument);
    Chain bad = chain2(0, 0, "");
    bad.steps = {0x02};
    EXPECT_EQ(write_chains(InputFormat::points, {bad}).error().code, Errc::invalid_argument);
    // points: one axis count per file
    EXPECT_EQ(write_chains(InputFormat::points, {chain2(0, 0, "0"), three}).error().code,
              Errc::invalid_argument);
}

TEST(BlockWriter, RefusesLayoutsThatDoNotFit) {
    auto blocks = read_blocks(InputFormat::freeman, "0 0 01\n1 1 2\n", 100, 100);
    ASSERT_EQ(blocks.size(), 1u);
    Block b = blocks[0];
    b.chains.pop_back();
    std::string out;
    BlockWriter w(InputFormat::freeman);
    EXPECT_EQ(w.write(b, out).error().code, Errc::corrupt);
    EXPECT_TRUE(out.empty());
    b = blocks[0];
    b.layout = "\x09";
    EXPECT_EQ(w.write(b, out).error().code, Errc::corrupt);
    b.layout = "\x03\x10xy";  // verbatim longer than the layout
    EXPECT_EQ(w.write(b, out).error().code, Errc::corrupt);

    auto sb = read_blocks(InputFormat::steps, "\x01\x01\x00"s, 100, 100);
    ASSERT_EQ(sb.size(), 1u);
    BlockWriter ws(InputFormat::steps);
    Block s = sb[0];
    s.chains[0].steps.push_back(0x01);
    EXPECT_EQ(ws.write(s, out).error().code, Errc::corrupt);

    auto pb = read_blocks(InputFormat::points, "0 0\n1 1\n", 100, 100);
    BlockWriter wp(InputFormat::points);
    Block p = pb[0];
    p.chains[0].steps.push_back(make_step2(1, 0));
    EXPECT_EQ(wp.write(p, out).error().code, Errc::corrupt);
}

TEST(BlockWriter, FreemanRefusesAStepWithoutACodeAnywhereInAChain) {
    // The renderer writes a chain in pieces of 1024 steps, sixteen steps a
    // round (with SSSE3), then four a round, and checks the codes after each
    // loop: a bad step at any place of either round, of the tail or of a
    // later piece is refused.
    std::mt19937 rng(17);
    BlockWriter w(InputFormat::freeman);
    std::vector<std::size_t> sizes;
    for (std::size_t n = 1; n <= 40; ++n) sizes.push_back(n);
    for (std::size_t n : {1023, 1024, 1025, 2100}) sizes.push_back(n);
    for (const std::size_t n : sizes) {
        std::string codes;
        for (std::size_t i = 0; i < n; ++i) codes.push_back(static_cast<char>('0' + rng() % 8));
        const std::string text = "4 -1 " + codes + "\n";
        const auto blocks = read_blocks(InputFormat::freeman, text, 100000, 100);
        ASSERT_EQ(blocks.size(), 1u);
        std::string out;
        ASSERT_TRUE(w.write(blocks[0], out).ok());
        EXPECT_EQ(out, text);
        // Every place of a short chain; a long one's ends and piece boundaries.
        std::vector<std::size_t> places;
        for (std::size_t k = 0; k < n; ++k)
            if (n <= 40 || k == 0 || k == 1022 || k == 1023 || k + 2 >= n) places.push_back(k);
        for (const std::size_t k : places)
            for (const Step bad : {Step{0}, Step{0x02}, Step{0x08}, Step{0x10}, Step{0x11}, Step{0xFF}, Step{0x0105},
                                   Step{0x8004}}) {
                Block b = blocks[0];
                b.chains[0].steps[k] = bad;
                std::string o;
                const auto r = w.write(b, o);
                ASSERT_FALSE(r.ok()) << n << " " << k << " " << bad;
                EXPECT_EQ(r.error().code, Errc::corrupt);
            }
    }
}

}  // namespace
}  // namespace stepzip
