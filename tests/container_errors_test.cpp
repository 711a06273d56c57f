// Damaged .stz frames: every truncation and every single-bit flip of a small
// frame is either decoded exactly or rejected with a documented error; reserved
// bits, bad magic/version and sizes over the decoder limits are rejected
// before anything of the declared size is allocated; each file in
// tests/golden-errors/ fails with the code named in its .expect file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "../src/container/block_codec.hpp"
#include "../src/common/bytes.hpp"
#include "stepzip/container.hpp"
#include "support/files.hpp"

namespace stepzip {
namespace {

using stz::Cursor;

// A small frame with a chain block (plotter-like vectors, eval8).
std::string small_frame() {
    CompressOptions opt;
    opt.profile = Profile::eval8;
    opt.allow_raw = false;
    opt.block_steps = 60;
    auto z = compress("# two chains\n0 0 0000100001000010000\n5 -3 22223222232222\n", opt);
    EXPECT_TRUE(z.ok());
    return z.ok() ? *z : std::string();
}

TEST(ContainerErrors, EveryTruncationIsRejectedAsTruncated) {
    const std::string frame = small_frame();
    ASSERT_GT(frame.size(), 40u);
    for (std::size_t n = 0; n < frame.size(); ++n) {
        auto r = decompress(std::string_view(frame).substr(0, n));
        ASSERT_FALSE(r.ok()) << "length " << n;
        EXPECT_EQ(r.error().code, Errc::truncated) << "length " << n << ": " << r.error().message;
    }
    EXPECT_TRUE(decompress(frame).ok());
}

TEST(ContainerErrors, EverySingleBitFlipDecodesExactlyOrIsRejected) {
    const std::string frame = small_frame();
    auto original = decompress(frame);
    ASSERT_TRUE(original.ok());
    int accepted = 0;
    for (std::size_t i = 0; i < frame.size(); ++i)
        for (int bit = 0; bit < 8; ++bit) {
            std::string bad = frame;
            bad[i] = static_cast<char>(bad[i] ^ (1 << bit));
            auto r = decompress(bad);
            if (r.ok()) {
                EXPECT_EQ(*r, *original) << "byte " << i << " bit " << bit;
                ++accepted;
            } else {
                EXPECT_TRUE(is_frame_error(r.error().code))
                    << "byte " << i << " bit " << bit << ": " << r.error().message;
            }
        }
    // The header check covers the informational segmenter field too.
    EXPECT_EQ(accepted, 0);
}

// `frame` with header byte `i` set to `v` and the header check made valid
// again (docs/FORMAT.md 1.1), so that the field itself is what is checked.
std::string with_header_byte(std::string frame, std::size_t i, unsigned v) {
    frame[i] = static_cast<char>(v);
    frame[7] = static_cast<char>((stz::hash64(std::string_view(frame).substr(0, 7)) >> 8) & 0xFF);
    return frame;
}

TEST(ContainerErrors, HeaderFieldsAreChecked) {
    const std::string frame = small_frame();
    ASSERT_EQ(frame[4], 2);
    auto code = [](std::string f) {
        auto r = decompress(f);
        return r.ok() ? Errc::ok : r.error().code;
    };
    std::string f = frame;
    f[0] = 'S';
    EXPECT_EQ(code(f), Errc::bad_magic);
    f = frame;
    f[4] = 3;
    EXPECT_EQ(code(f), Errc::bad_version);
    f = frame;
    f[4] = 0;
    EXPECT_EQ(code(f), Errc::bad_version);
    // Any other header byte changed: the header check fails.
    for (std::size_t i = 5; i < stz::kFrameHeaderSize; ++i) {
        f = frame;
        f[i] = static_cast<char>(f[i] ^ 0x10);
        EXPECT_EQ(code(f), Errc::checksum) << "byte " << i;
    }
    const auto b5 = static_cast<unsigned char>(frame[5]), b6 = static_cast<unsigned char>(frame[6]);
    EXPECT_EQ(code(with_header_byte(frame, 5, b5 | 0x80)), Errc::reserved_bits);
    EXPECT_EQ(code(with_header_byte(frame, 5, (b5 & ~7u) | 6)), Errc::corrupt);          // profile 6
    EXPECT_EQ(code(with_header_byte(frame, 5, (b5 & ~0x18u) | 0x18)), Errc::corrupt);    // input format 3
    EXPECT_EQ(code(with_header_byte(frame, 5, b5 | 0x60)), Errc::corrupt);               // segmenter 3
    EXPECT_EQ(code(with_header_byte(frame, 6, (b6 & ~7u) | 1)), Errc::corrupt);          // 1 axis
    EXPECT_EQ(code(with_header_byte(frame, 6, (b6 & 7u) | ((kMaxWindowLog + 1) << 3))), Errc::limit);
    EXPECT_EQ(code(with_header_byte(frame, 6, (b6 & 7u) | (31u << 3))), Errc::limit);
    f = frame;
    f[stz::kFrameHeaderSize] = static_cast<char>(f[stz::kFrameHeaderSize] | 0x40);  // first block's flags
    EXPECT_EQ(code(f), Errc::reserved_bits);
    f = frame + "x";
    EXPECT_EQ(code(f), Errc::corrupt);
    f = frame + std::string(reinterpret_cast<const char*>(stz::kMagic), 3);
    EXPECT_EQ(code(f), Errc::corrupt);
}

TEST(ContainerErrors, TheTrailerIsChecked) {
    // The last 8 bytes are the content XXH64; before them the trailer flags
    // (no metadata here: 0) and the varint decoded size.
    const std::string frame = small_frame();
    auto code = [](std::string f) {
        auto r = decompress(f);
        return r.ok() ? Errc::ok : r.error().code;
    };
    const std::size_t flags = frame.size() - 9;
    ASSERT_EQ(frame[flags], 0);
    std::string f = frame;
    f[flags] = 2;
    EXPECT_EQ(code(f), Errc::reserved_bits);
    f = frame;
    f[flags - 1] = static_cast<char>(f[flags - 1] ^ 1);  // decoded size
    EXPECT_EQ(code(f), Errc::corrupt);
    f = frame;
    f.back() = static_cast<char>(f.back() ^ 1);
    EXPECT_EQ(code(f), Errc::checksum);
    // Metadata declared over the limit: refused before it is read.
    f = frame.substr(0, flags) + '\x01';
    stz::put_varint(f, stz::kMaxMetadata + 1);
    EXPECT_EQ(code(f + std::string(16, '\0')), Errc::limit);
}

// A frame around one hand-made chain payload, with valid checksums.
std::string frame_with_payload(const std::string& payload, unsigned type = stz::kChains) {
    stz::FrameHeader h;
    h.profile = Profile::eval8;
    std::string f = stz::write_frame_header(h);
    f += stz::make_block_record(type, 0, payload, 3);
    stz::put_u8(f, stz::kEnd);
    stz::put_varint(f, 0);  // decoded size
    stz::put_u8(f, 0);      // trailer flags
    stz::put_le(f, stz::hash64(""), 8);
    return f;
}

std::string payload(std::uint64_t chains, std::uint64_t segs, std::uint64_t steps,
                    std::initializer_list<std::int64_t> records) {
    std::string p;
    stz::put_varint(p, chains);
    stz::put_varint(p, segs);
    stz::put_varint(p, steps);
    stz::put_varint(p, 0);  // layout
    for (std::int64_t v : records) stz::put_varint(p, static_cast<std::uint64_t>(v));
    return p;
}

TEST(ContainerErrors, DeclaredSizesOverTheLimitsAreRejectedBeforeAllocating) {
    // Block header claiming a 4 GiB payload in a few bytes.
    const std::string frame = small_frame();
    Cursor cur(std::string_view(frame).substr(stz::kFrameHeaderSize + 1));
    std::uint64_t csize;
    ASSERT_TRUE(cur.varint(csize));
    std::string f = frame.substr(0, stz::kFrameHeaderSize + 1);
    stz::put_varint(f, std::uint64_t{1} << 32);
    f += frame.substr(stz::kFrameHeaderSize + 1 + cur.pos());
    auto r = decompress(f);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, Errc::limit) << r.error().message;
    // A payload declaring 2^40 steps.
    r = decompress(frame_with_payload(payload(1, 1, std::uint64_t{1} << 40, {0, 0, 0, 2, 0})));
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, Errc::limit) << r.error().message;
    // A segment of 2^29 steps in a payload declaring 3: corrupt, never expanded.
    r = decompress(frame_with_payload(payload(1, 1, 3, {0, 0, 1, 0, (1 << 29) - 1, 0})));
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, Errc::corrupt) << r.error().message;
    // A segment longer than 2^30 on an axis.
    r = decompress(frame_with_payload(payload(1, 1, 3, {0, 0, 1, 0, std::int64_t{1} << 31, 0})));
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, Errc::limit) << r.error().message;
}

TEST(ContainerErrors, PhaseOutsideItsRangeIsCorrupt) {
    // One chain at (0,0), one segment: octant 0, L = 5, S = 2, phase diff +3
    // (phase 3, range [-2, 3)). Steps = 5.
    auto r = decompress(frame_with_payload(payload(1, 1, 5, {0, 0, 1, 0, 4, 2, 6})));
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, Errc::corrupt) << r.error().message;
    // The same with phase diff +2 is valid except for the content checksum of
    // the empty original: checksum or size error, never success.
    r = decompress(frame_with_payload(payload(1, 1, 5, {0, 0, 1, 0, 4, 2, 4})));
    ASSERT_FALSE(r.ok());
    EXPECT_TRUE(r.error().code == Errc::checksum || r.error().code == Errc::corrupt);
}

using test::slurp;

// Each NAME.expect holds the error code's name on its first line and, on the
// second, where the decoder must report it ("byte N", the frame offset, and
// for an error inside a modeled payload the payload offset after it): the
// message must be "<source>: <where>: ...".
TEST(ContainerErrors, GoldenErrorFilesFailWithTheirExpectedCodeAndOffset) {
    const std::filesystem::path dir =
        std::filesystem::path(STEPZIP_SOURCE_DIR) / "tests" / "golden-errors";
    int seen = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
        if (e.path().extension() != ".stz") continue;
        std::filesystem::path expect = e.path();
        expect.replace_extension(".expect");
        std::istringstream lines(slurp(expect));
        std::string want_code, want_where;
        std::getline(lines, want_code);
        std::getline(lines, want_where);
        ASSERT_FALSE(want_code.empty()) << expect;
        ASSERT_EQ(want_where.rfind("byte ", 0), 0u) << expect << ": second line must say where";
        const std::string source = e.path().filename().string();
        auto r = decompress(slurp(e.path()), source);
        ASSERT_FALSE(r.ok()) << e.path();
        EXPECT_EQ(std::string(errc_name(r.error().code)), want_code) << e.path() << ": " << r.error().message;
        EXPECT_EQ(r.error().message.rfind(source + ": " + want_where + ": ", 0), 0u)
            << e.path() << ": expected the error at " << want_where << ", got: " << r.error().message;
        ++seen;
    }
    EXPECT_GE(seen, 17);
}

// The block checksum alone: a frame whose stored block checksum is wrong
// but whose blocks decode to the original (so the content checksum holds)
// is rejected, at the checksum's offset; fixing the checksum field back
// makes it decode. Nothing else in the frame can catch this damage.
TEST(ContainerErrors, BlockChecksumIsCheckedOnItsOwn) {
    const std::string frame = small_frame();
    // Version 2 (docs/FORMAT.md 1.2): the block byte (type in bits 0-2),
    // varint compressed size C, a varint decoded size for chain and raw
    // blocks only, C payload bytes, then the checksum.
    std::size_t pos = stz::kFrameHeaderSize;
    const unsigned type = static_cast<unsigned char>(frame.at(pos++)) & 7u;
    auto varint = [&] {
        std::uint64_t v = 0;
        for (int shift = 0;; shift += 7) {
            const auto b = static_cast<unsigned char>(frame.at(pos++));
            v |= static_cast<std::uint64_t>(b & 0x7F) << shift;
            if (b < 0x80) return v;
        }
    };
    const std::uint64_t csize = varint();
    if (type == stz::kChains || type == stz::kRaw) varint();
    const std::size_t at = pos + csize;  // first block's checksum
    ASSERT_LT(at + 4, frame.size());
    for (int bit = 0; bit < 32; ++bit) {
        std::string bad = frame;
        bad[at + static_cast<std::size_t>(bit / 8)] ^= static_cast<char>(1 << (bit % 8));
        auto r = decompress(bad, "f");
        ASSERT_FALSE(r.ok()) << "bit " << bit;
        EXPECT_EQ(r.error().code, Errc::checksum) << r.error().message;
        EXPECT_EQ(r.error().message.rfind("f: byte " + std::to_string(at) + ": ", 0), 0u) << r.error().message;
    }
    EXPECT_TRUE(decompress(frame).ok());
}

}  // namespace
}  // namespace stepzip
