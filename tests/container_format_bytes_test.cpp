// Format bytes, pinned: the exact payload bytes the encoders (format
// version 2; payloads without a window) write for small fixed inputs (record block before zstd, segment model,
// step model). Round-trip tests pass when the encoder and the decoder
// change together; these do not, so a change of the bytes on disk is
// always deliberate. This file is the one place to update when the format
// version changes (with docs/FORMAT.md and tests/golden/). The record
// payload of a one-segment chain is also worked out by hand from
// docs/FORMAT.md section 1.2. The range coder's own pinned bytes are in
// container_range_coder_test.cpp (they follow from section 1.4 alone).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../src/container/block_codec.hpp"
#include "../src/container/modeled_block.hpp"
#include "stepzip/document.hpp"
#include "stepzip/segmenter.hpp"
#include "support/pinned_bytes.hpp"

namespace stepzip::stz {
namespace {

using test::corpus_block;
using test::hex;
using test::unhex;
using test::fixed_block;
using test::greedy_cut;

// Two chains (plotter-like lines and a repeated pattern), eval8, greedy cut.
constexpr const char* kTwoChains = "0 0 0000100001000010000\n5 -3 22223222232222\n";

TEST(FormatBytes, RecordPayloadOfOneSegmentWorkedByHand) {
    // One chain at the origin, four steps along +x, eval8. Section 1.2:
    // nchains 1, nsegments 1, nsteps 4, layout size 0; chain header
    // svarint 0, svarint 0 (start - origin), varint 1 (segments); the
    // segment: octant 0 - previous octant 0 = 0, L - 1 = 3, minor total 0;
    // no phase (the y total is 0, so the only function is degenerate).
    const Block b = fixed_block("0 0 0000\n");
    const std::string payload = write_chain_payload(b, Profile::eval8, greedy_cut(b, Profile::eval8));
    EXPECT_EQ(hex(payload), "01 01 04 00 00 00 01 00 03 00");
}

// The bytes below were printed by the encoder of format version 1 and
// checked to decode back to kTwoChains (the round-trip tests); the first
// fields are the plain counts of section 1.2 / 1.3 (2 chains, 4 segments,
// 33 steps; 2 chains, 33 steps, order).
TEST(FormatBytes, RecordPayload) {
    const Block b = fixed_block(kTwoChains);
    EXPECT_EQ(hex(write_chain_payload(b, Profile::eval8, greedy_cut(b, Profile::eval8))), "02 04 21 00 00 00 02 00 0f 03 12 00 02 00 1b 0b 02 02 0a 02 0c 07 02 00");
}

TEST(FormatBytes, SegmentModelPayload) {
    const Block b = fixed_block(kTwoChains);
    EXPECT_EQ(hex(write_segment_model(b, Profile::eval8, greedy_cut(b, Profile::eval8))), "02 04 21 02 00 00 01 e0 5f 8c 21 bc 8e 5b 80 07 3f a0 80 00");
    EXPECT_EQ(hex(write_segment_model(b, Profile::grbl, greedy_cut(b, Profile::grbl))), "02 04 21 02 00 00 01 e0 5f 10 86 f2 39 6d ff 2f fa 60 00 00");
}

TEST(FormatBytes, StepModelPayload) {
    const Block b = fixed_block(kTwoChains);
    EXPECT_EQ(hex(write_step_model(b, 1)), "02 21 01 00 00 00 36 72 c7 bd 8f 53 07 38 43 6a a0 74");
    EXPECT_EQ(hex(write_step_model(b, 3)), "02 21 03 00 00 00 36 6e 36 6a e5 a6 5f d2 95 8a 4a f9 80");
}

TEST(FormatBytes, PinnedPayloadsDecodeToTheirChains) {
    // The decoder reads the pinned bytes as these chains: a decoder change
    // that moves the bytes' meaning fails here even if the encoder moved too.
    const Block b = fixed_block(kTwoChains);
    Block out;
    BlockCounts counts;
    ASSERT_TRUE(read_chain_payload(unhex("02 04 21 00 00 00 02 00 0f 03 12 00 02 00 1b 0b 02 02 0a 02 0c 07 02 00"),
                                   Profile::eval8, 2, true, out, counts, "pinned").ok());
    EXPECT_EQ(out.chains, b.chains);
    out = Block{};
    ASSERT_TRUE(read_segment_model(unhex("02 04 21 02 00 00 01 e0 5f 8c 21 bc 8e 5b 80 07 3f a0 80 00"),
                                   Profile::eval8, 2, true, out, counts, "pinned").ok());
    EXPECT_EQ(out.chains, b.chains);
    out = Block{};
    ASSERT_TRUE(read_step_model(unhex("02 21 03 00 00 00 36 6e 36 6a e5 a6 5f d2 95 8a 4a f9 80"), 2, true, out,
                                counts, "pinned").ok());
    EXPECT_EQ(out.chains, b.chains);
}

// Larger blocks reach the contexts and lists a small input never fills (the
// successor and recent-shape lists, match lengths, every turn context): the
// payloads of the first 20000 steps of two corpus files are pinned by size
// and XXH64. (They change if those corpus files are regenerated.)
TEST(FormatBytes, SegmentModelPayloadOfACorpusBlock) {
    const Block b = corpus_block("plotter/hershey-grbl.fc", 20000);
    const std::string payload = write_segment_model(b, Profile::grbl, greedy_cut(b, Profile::grbl));
    EXPECT_EQ(payload.size(), 1323u);
    EXPECT_EQ(hash64(payload), 12282891294102104036u);
}

// Version 2: the step model also predicts chain starts from its match, so
// these differ from the version-1 payloads (3498 and 3447 bytes).
TEST(FormatBytes, StepModelPayloadOfACorpusBlock) {
    const Block b = corpus_block("glyphs/dejavu-8.fc", 20000);
    for (int order : {1, 4}) {
        const std::string payload = write_step_model(b, order);
        EXPECT_EQ(payload.size(), order == 1 ? 3454u : 3403u) << order;
        EXPECT_EQ(hash64(payload), order == 1 ? 16409367610628402649u : 1179356124551759055u) << order;
    }
}

}  // namespace
}  // namespace stepzip::stz
