// The CM raw block (docs/FORMAT.md 1.15, block type 7 subtype 3): round
// trips of text-like and binary payloads, the encoder's choice of it where
// zstd's raw block was written (HP-GL text read as steps), its golden file,
// and its corrupt and truncated payloads named by payload byte.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "../src/common/bytes.hpp"
#include "../src/container/block_codec.hpp"
#include "../src/container/encoder.hpp"
#include "../src/container/raw_cm.hpp"
#include "stepzip/container.hpp"
#include "stepzip/document.hpp"
#include "support/block_records.hpp"
#include "support/files.hpp"
#include "support/proved.hpp"

namespace stepzip {
namespace {

using test::corpus;
using test::slurp;

// HP-GL as a plotter driver writes it: pen moves along curves, labels.
std::string hpgl_text(std::uint32_t seed, std::size_t lines) {
    std::mt19937 rng(seed);
    std::string t = "IN;\nSC0,10000,0,7500;\nSP1;\n";
    int x = 1000, y = 1000;
    for (std::size_t i = 0; i < lines; ++i) {
        switch (rng() % 6) {
            case 0: t += "PU;\n"; break;
            case 1: t += "LB" + std::to_string(rng() % 100) + "\x03\n"; break;
            default:
                x += static_cast<int>(rng() % 41) - 20;
                y += static_cast<int>(rng() % 21) - 10;
                t += (rng() % 3 ? "PD;PA" : "PU;PA") + std::to_string(x) + "," + std::to_string(y) + ";\n";
        }
    }
    return t;
}

// A raw block's payload: varint nchains, varint nsteps, the bytes.
std::string raw_payload(std::uint64_t chains, std::uint64_t steps, const std::string& bytes) {
    std::string r;
    wire::put_varint(r, chains);
    wire::put_varint(r, steps);
    return r + bytes;
}

std::string round_trip(const std::string& raw) {
    const std::string payload = stz::write_raw_cm_block(raw);
    EXPECT_GE(payload.size(), 3u);
    EXPECT_EQ(static_cast<unsigned char>(payload[0]), stz::kRawCmSubtype);
    EXPECT_EQ(static_cast<unsigned char>(payload[1]), stz::kRawCmCoding);
    auto back = stz::read_raw_cm_block(payload, "P");
    EXPECT_TRUE(back.ok()) << back.error().message;
    return back.ok() ? *back : std::string("<error>");
}

TEST(RawCmBlock, RoundTripsTextLikeInput) {
    for (std::uint32_t seed = 1; seed <= 3; ++seed) {
        const std::string raw = raw_payload(1, 5000 * seed, hpgl_text(seed, 3000 * seed));
        EXPECT_EQ(round_trip(raw), raw) << seed;
        // A context-mixing coder of text: well under a quarter of the bytes.
        EXPECT_LT(stz::write_raw_cm_block(raw).size() * 4, raw.size()) << seed;
    }
    const std::string gp = corpus("plotter/gnuplot.hpgl");
    const std::string raw = raw_payload(1, 96376, gp);
    EXPECT_EQ(round_trip(raw), raw);
}

TEST(RawCmBlock, RoundTripsBinaryStepsAndEdgeCases) {
    const std::string steps = corpus("stepper/engrave-4axis.steps").substr(0, 60000);
    EXPECT_EQ(round_trip(raw_payload(3, 60000, steps)), raw_payload(3, 60000, steps));
    std::string every;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 256; ++c) every.push_back(static_cast<char>(c ^ (r * 37)));
    EXPECT_EQ(round_trip(every), every);
    std::mt19937 rng(5);
    std::string noise;
    for (int i = 0; i < 20000; ++i) noise.push_back(static_cast<char>(rng()));
    EXPECT_EQ(round_trip(noise), noise);
    EXPECT_EQ(round_trip(std::string()), std::string());
    EXPECT_EQ(round_trip(std::string(1, '\n')), std::string(1, '\n'));
    EXPECT_EQ(round_trip(std::string(100000, 'A')), std::string(100000, 'A'));
    EXPECT_LT(stz::write_raw_cm_block(std::string(100000, 'A')).size(), 100u);
}

// The block records of a one-frame version-2 file as (block type, payload
// byte 0).
std::vector<std::pair<unsigned, unsigned>> block_kinds(const std::string& frame) {
    std::vector<std::pair<unsigned, unsigned>> kinds;
    for (const test::BlockRecord& r : test::block_records(frame))
        kinds.emplace_back(r.type, r.payload.empty() ? 256u : static_cast<unsigned char>(r.payload[0]));
    return kinds;
}

// Against a chain block the CM raw block is coded whole only where its
// model's stretches say it may win: on the HP-GL text (its stretches cost
// about 1.27 times the whole per byte) a chain block twice its size or
// 1/16 over it leaves it in, one of half or nine tenths of its size does
// not (the whole cannot win there either); small content
// and no chain block always leave it in.
TEST(RawCmBlock, CodedWholeAgainstAChainBlockOnlyWhereItMayWin) {
    const std::string gp = corpus("plotter/gnuplot.hpgl");
    const std::size_t cm = stz::write_raw_cm_block(gp).size();
    ASSERT_GT(cm, 0u);
    EXPECT_TRUE(stz::raw_cm_may_win(gp, 2 * cm));
    EXPECT_TRUE(stz::raw_cm_may_win(gp, cm + cm / 16));
    EXPECT_FALSE(stz::raw_cm_may_win(gp, cm / 2));
    EXPECT_FALSE(stz::raw_cm_may_win(gp, cm * 9 / 10));
    EXPECT_TRUE(stz::raw_cm_may_win(gp, 0));
    EXPECT_TRUE(stz::raw_cm_may_win(std::string_view(gp).substr(0, 60000), 1));
}

// Where the model does not learn (a random walk: its stretches cost what the
// whole does per byte), the whole is coded only when the stretches already
// come 1/32 under `best`: not against a block of the whole's own size (the
// 1.3 reach of text would code it, for nothing), but against one twice its
// size.
TEST(RawCmBlock, CodedWholeWhereItDoesNotLearnOnlyWhenItWinsOnTheSample) {
    const std::string walk = corpus("random/walk-8.fc");
    const std::size_t cm = stz::write_raw_cm_block(walk).size();
    ASSERT_GT(walk.size(), 65536u);
    EXPECT_FALSE(stz::raw_cm_may_win(walk, cm));
    EXPECT_FALSE(stz::raw_cm_may_win(walk, cm + cm / 64));
    EXPECT_TRUE(stz::raw_cm_may_win(walk, 2 * cm));
}

// The chains of `data` read as `format`, as one block.
Block block_of(InputFormat format, const std::string& data) {
    auto chains = read_chains(format, data);
    EXPECT_TRUE(static_cast<bool>(chains));
    Block b;
    if (!chains) return b;
    b.chains = std::move(*chains);
    b.axes = 2;
    for (const Chain& c : b.chains) b.axes = std::max(b.axes, c.axes);
    return b;
}

// `text` compressed as a steps log at `level` (raw blocks allowed or not),
// checked to decompress to itself (empty when not).
std::string steps_frame_proved(const std::string& text, int level, bool allow_raw) {
    CompressOptions opt;
    opt.level = level;
    opt.format = InputFormat::steps;
    opt.allow_raw = allow_raw;
    return test::compress_proved(text, opt);
}

// Text read as steps (its axes turn back every few moves) is told from a
// machine's step logs, whose axes seldom do, and from two-axis chains (a
// random walk turns back as often: its step model wins there); the few
// moves of a short text do not decide.
TEST(TextReadAsSteps, ToldFromStepLogsByTheirReversals) {
    EXPECT_TRUE(stz::reads_as_text(block_of(InputFormat::steps, corpus("plotter/gnuplot.hpgl"))));
    EXPECT_TRUE(stz::reads_as_text(block_of(InputFormat::steps, hpgl_text(7, 3000))));
    EXPECT_FALSE(stz::reads_as_text(block_of(InputFormat::steps, hpgl_text(7, 40))));
    EXPECT_FALSE(stz::reads_as_text(block_of(InputFormat::steps, corpus("stepper/engrave-4axis.steps"))));
    EXPECT_FALSE(stz::reads_as_text(block_of(InputFormat::steps, corpus("timed/trapezoid-3axis.steps"))));
    EXPECT_FALSE(stz::reads_as_text(block_of(InputFormat::steps, corpus("timed/heldout-fast-3axis.steps"))));
    EXPECT_FALSE(stz::reads_as_text(block_of(InputFormat::freeman, corpus("random/walk-4.fc"))));
}

// With raw blocks not allowed (--no-raw) text read as steps still takes a
// chain block, at every level: the text shortcut is for raw blocks only.
TEST(TextReadAsSteps, NoRawStillCodesItAsChains) {
    const std::string gp = corpus("plotter/gnuplot.hpgl");
    for (int level : {1, 3, 19}) {
        const std::string z = steps_frame_proved(gp, level, false);
        ASSERT_FALSE(z.empty()) << level;
        for (const auto& [type, first] : block_kinds(z)) {
            EXPECT_NE(type, stz::kRaw) << level;
            EXPECT_FALSE(type == stz::kExtended && first == stz::kRawCmSubtype) << level;
        }
    }
}

// HP-GL text read as steps is written raw; from -L 3 the CM raw block takes
// it (about half zstd's size), at -L 1 zstd's raw block (type 2) still does.
TEST(RawCmBlock, EncoderPicksItOnHpglText) {
    const std::string gp = corpus("plotter/gnuplot.hpgl");
    for (int level : {1, 3, 19}) {
        const std::string z = steps_frame_proved(gp, level, true);
        ASSERT_FALSE(z.empty()) << level;
        const auto kinds = block_kinds(z);
        ASSERT_EQ(kinds.size(), 1u) << level;
        if (level >= stz::kRawCmLevel) {
            EXPECT_EQ(kinds[0].first, stz::kExtended) << level;
            EXPECT_EQ(kinds[0].second, stz::kRawCmSubtype) << level;
            // below xz -9e (16560 bytes) at every such level
            EXPECT_LT(z.size(), 16560u) << level;
        } else {
            EXPECT_EQ(kinds[0].first, stz::kRaw) << level;
        }
    }
}

// tests/golden/v2/raw_cm.hpgl.stz holds a CM raw block (the golden test of
// container_roundtrip_test decodes it byte-exactly; here its block kind).
TEST(RawCmBlock, GoldenFileHoldsTheBlock) {
    const auto dir = std::filesystem::path(STEPZIP_SOURCE_DIR) / "tests" / "golden" / "v2";
    const std::string frame = slurp(dir / "raw_cm.hpgl.stz");
    const auto kinds = block_kinds(frame);
    ASSERT_FALSE(kinds.empty());
    EXPECT_EQ(kinds[0].first, stz::kExtended);
    EXPECT_EQ(kinds[0].second, stz::kRawCmSubtype);
    auto back = decompress(frame);
    ASSERT_TRUE(back.ok()) << back.error().message;
    EXPECT_EQ(*back, slurp(dir / "raw_cm.hpgl"));
}

bool names_byte(const Error& e) {
    return (e.code == Errc::corrupt || e.code == Errc::limit) && e.message.rfind("P byte ", 0) == 0;
}

TEST(RawCmBlock, BadHeadersAreRejectedWithTheirByte) {
    const std::string good = stz::write_raw_cm_block(raw_payload(1, 10, hpgl_text(7, 50)));
    std::string p = good;
    p[0] = 9;
    auto r = stz::read_raw_cm_block(p, "P");
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message.rfind("P byte 0:", 0), 0u) << r.error().message;
    p = good;
    p[1] = 1;  // an unknown coding
    r = stz::read_raw_cm_block(p, "P");
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, Errc::corrupt);
    EXPECT_EQ(r.error().message.rfind("P byte 1:", 0), 0u) << r.error().message;
    // A declared size over the raw block's limit: refused before any table is made.
    std::string big = {static_cast<char>(stz::kRawCmSubtype), 0};
    wire::put_varint(big, std::uint64_t{kMaxBlockBytes} + 21);
    r = stz::read_raw_cm_block(big + std::string(8, '\0'), "P");
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, Errc::limit);
    EXPECT_EQ(r.error().message.rfind("P byte 2:", 0), 0u) << r.error().message;
    // A size field that runs past the end.
    r = stz::read_raw_cm_block(std::string("\x03\x00\x80", 3), "P");
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message.rfind("P byte 2:", 0), 0u) << r.error().message;
}

// Every truncation of a payload is refused (the stream ends early, or does
// not end where the payload does), naming a byte; so are trailing bytes.
TEST(RawCmBlock, TruncatedPayloadsAreRejectedWithTheirByte) {
    const std::string good = stz::write_raw_cm_block(raw_payload(1, 300, hpgl_text(8, 200)));
    for (std::size_t n = 0; n < good.size(); n += n < 40 ? 1 : 7) {
        auto r = stz::read_raw_cm_block(good.substr(0, n), "P");
        ASSERT_FALSE(r.ok()) << n;
        EXPECT_TRUE(names_byte(r.error())) << n << ": " << r.error().message;
    }
    auto r = stz::read_raw_cm_block(good + "x", "P");
    ASSERT_FALSE(r.ok());
    EXPECT_TRUE(names_byte(r.error())) << r.error().message;
}

// Random streams behind a valid header, and damaged good payloads: each is
// decoded or rejected naming a byte, never a crash.
TEST(RawCmBlock, RandomAndDamagedPayloadsAreDecodedOrRejected) {
    std::mt19937 rng(21);
    int rejected = 0;
    const std::string good = stz::write_raw_cm_block(raw_payload(1, 300, hpgl_text(9, 400)));
    for (int trial = 0; trial < 200; ++trial) {
        std::string p;
        if (trial % 2 == 0) {
            p = {static_cast<char>(stz::kRawCmSubtype), 0};
            wire::put_varint(p, rng() % 3000);
            const std::size_t n = rng() % 200;
            for (std::size_t i = 0; i < n; ++i) p.push_back(static_cast<char>(rng()));
        } else {
            p = good;
            p[3 + rng() % (p.size() - 3)] ^= static_cast<char>(1 + rng() % 255);
        }
        auto r = stz::read_raw_cm_block(p, "P");
        if (!r.ok()) {
            EXPECT_TRUE(names_byte(r.error())) << r.error().message;
            ++rejected;
        }
    }
    EXPECT_GT(rejected, 60);
}

}  // namespace
}  // namespace stepzip
