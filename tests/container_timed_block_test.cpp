// The timed block (docs/FORMAT.md 1.12, block type 7 subtype 0): round trips
// of controller-like timed streams at every tier, its rate prediction, and
// its corrupt cases named by payload byte.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "../src/container/block_codec.hpp"
#include "../src/container/timed_block.hpp"
#include "../src/container/timed_phase.hpp"
#include "stepzip/container.hpp"
#include "stepzip/interpolate/segment.hpp"

namespace stepzip {
namespace {

// A controller's step log: per move a trapezoid speed profile cut into
// constant-rate segments of `seg_ticks`; the leading axis steps when a phase
// accumulator crosses 1 (carried across segments), the others by Bresenham
// on its steps; DIR levels set in an idle tick before the move. Settings
// (acceleration, top rate, segment length) vary with the seed.
std::string controller_stream(std::uint32_t seed, int axes, int moves) {
    std::mt19937 rng(seed);
    const double accel = 2e-6 * (1 + rng() % 8);     // steps/tick^2
    const double top = 0.05 + 0.02 * (rng() % 8);    // steps/tick
    const int seg_ticks = 100 + static_cast<int>(rng() % 200);
    std::string log;
    unsigned level = 0;
    for (int m = 0; m < moves; ++m) {
        std::vector<long> d(static_cast<std::size_t>(axes));
        for (auto& v : d) v = static_cast<long>(rng() % 800) - 400;
        d[0] = 200 + static_cast<long>(rng() % 1500);
        if (rng() % 2) d[0] = -d[0];
        std::shuffle(d.begin(), d.end(), rng);
        long major = 0;
        for (long v : d) major = std::max(major, std::labs(v));
        unsigned dirs = 0;
        for (int a = 0; a < axes; ++a)
            if (d[static_cast<std::size_t>(a)] < 0) dirs |= 2u << (2 * a);
        log.append(3, static_cast<char>(level));
        level = dirs;
        log.push_back(static_cast<char>(level));
        std::vector<long> err(static_cast<std::size_t>(axes), major / 2);
        double acc = 0, rate = 0;
        long done = 0;
        while (done < major) {
            // Segment rate: accelerate, cruise, or brake to stop at the end.
            const double brake = std::sqrt(2 * accel * static_cast<double>(major - done));
            rate = std::min({top, rate + accel * seg_ticks, std::max(brake, 0.004)});
            for (int t = 0; t < seg_ticks && done < major; ++t) {
                acc += rate;
                unsigned tick = level;
                if (acc >= 1) {
                    acc -= 1;
                    ++done;
                    for (int a = 0; a < axes; ++a) {
                        auto& e = err[static_cast<std::size_t>(a)];
                        e -= std::labs(d[static_cast<std::size_t>(a)]);
                        if (e < 0) {
                            e += major;
                            tick |= 1u << (2 * a);
                        }
                    }
                }
                log.push_back(static_cast<char>(tick));
            }
        }
    }
    // The log runs from the first step to the last (docs/formats.md).
    const auto first = log.find_first_of(std::string("\x01\x03\x04\x06\x07\x09\x0b\x0c\x0d\x0e\x0f", 11));
    std::size_t last = log.size();
    while (last > 0 && (log[last - 1] & 0x15) == 0) --last;
    return log.substr(first, last - first);
}

FrameInfo info_of(const std::string& frame) {
    std::size_t pos = 0;
    auto r = inspect_stream([&](char* buf, std::size_t n) -> Result<std::size_t> {
        const std::size_t k = std::min(n, frame.size() - pos);
        std::copy_n(frame.data() + pos, k, buf);
        pos += k;
        return k;
    });
    EXPECT_TRUE(r.ok()) << r.error().message;
    return r.ok() ? *r : FrameInfo{};
}

std::string slurp(const std::filesystem::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::ostringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

std::string compress_timed(const std::string& log, int level, std::size_t block_steps = kDefaultBlockSteps) {
    CompressOptions opt;
    opt.format = InputFormat::timed;
    opt.level = level;
    opt.allow_raw = false;
    opt.block_steps = block_steps;
    auto z = compress(log, opt);
    EXPECT_TRUE(z.ok()) << z.error().message;
    return z.ok() ? *z : std::string();
}

TEST(TimedBlock, GeneratedStreamsRoundTripAtEveryTier) {
    std::uint64_t timed_blocks = 0;
    for (std::uint32_t seed : {1u, 2u, 3u})
        for (int axes : {2, 3}) {
            const std::string log = controller_stream(seed, axes, 5);
            ASSERT_GT(log.size(), 10000u);
            for (int level : {1, 3, 10, 19}) {
                const std::string frame = compress_timed(log, level, 1u << 15);
                auto back = decompress(frame);
                ASSERT_TRUE(back.ok()) << back.error().message;
                EXPECT_EQ(*back, log) << "seed " << seed << " axes " << axes << " level " << level;
                timed_blocks += info_of(frame).timed_blocks;
            }
        }
    // The constant-rate segments of these streams are what the block predicts.
    EXPECT_GT(timed_blocks, 12u);
}

TEST(TimedBlock, CorporaRoundTripThroughTimedBlocks) {
    const auto dir = std::filesystem::path(STEPZIP_SOURCE_DIR) / "corpora" / "timed";
    for (const char* name : {"trapezoid-2axis.steps", "trapezoid-3axis.steps"}) {
        const std::string log = slurp(dir / name);
        ASSERT_GT(log.size(), 100000u) << name;
        const std::string frame = compress_timed(log, 3);
        auto back = decompress(frame);
        ASSERT_TRUE(back.ok()) << name << ": " << back.error().message;
        EXPECT_EQ(*back, log) << name;
        EXPECT_GE(info_of(frame).timed_blocks, 1u) << name;
    }
}

// An axis at a constant rate, cut into two segments: the rate prediction of
// the second phase is the phase that continues the first line exactly.
TEST(TimedBlock, RatePredictionContinuesAConstantRateExactly) {
    for (Profile p : {Profile::eval8, Profile::grbl, Profile::marlin})
        for (std::int64_t l : {7, 40, 250})
            for (std::int64_t s : {1, 3, 6})
                for (std::int64_t f = -s; f < l - s; f += 1 + l / 9) {
                    Segment a;
                    a.delta[0] = l;
                    a.delta[1] = s;
                    a.delta[2] = -(s / 2);
                    a.phase[0] = f;
                    a.phase[1] = phase_range(p, l, s / 2).lo;
                    stz::TimedRates rates;
                    rates.reset();
                    EXPECT_EQ(rates.predict(p, a, 3, 0), default_phase(p, l, s)) << "unknown: default";
                    rates.advance(p, a, 3);
                    EXPECT_EQ(rates.predict(p, a, 3, 0), f) << "l " << l << " s " << s << " f " << f;
                    // The continuation draws the same steps again.
                    std::vector<Step> one, two;
                    expand_segment(p, a, 3, one);
                    Segment b = a;
                    b.phase[0] = rates.predict(p, a, 3, 0);
                    expand_segment(p, b, 3, two);
                    EXPECT_EQ(one, two);
                }
}

TEST(TimedBlock, ASegmentTimeDoesNotLeadMakesEveryAxisUnknown) {
    Segment timed;
    timed.delta[0] = 10;
    timed.delta[1] = 3;
    timed.phase[0] = 2;
    Segment other;
    other.delta[0] = 2;
    other.delta[1] = 5;  // axis 1 leads: not a timed segment
    stz::TimedRates rates;
    rates.reset();
    rates.advance(Profile::eval8, timed, 2);
    EXPECT_EQ(rates.predict(Profile::eval8, timed, 2, 0), 2);
    rates.advance(Profile::eval8, other, 2);
    EXPECT_EQ(rates.predict(Profile::eval8, timed, 2, 0), default_phase(Profile::eval8, 10, 3));
    EXPECT_FALSE(stz::time_leads(other, 2));
}

// Where the first block of type 7 starts in `frame`: its payload offset.
std::size_t first_timed_payload(const std::string& frame, std::size_t& block_at, std::size_t& csize) {
    std::size_t i = 8;  // after the frame header
    while (i < frame.size() && frame[i] != 0) {
        const unsigned type = static_cast<unsigned char>(frame[i]) & 7u;
        std::size_t j = i + 1, c = 0, shift = 0;
        for (;; shift += 7) {
            const auto b = static_cast<unsigned char>(frame[j++]);
            c |= static_cast<std::size_t>(b & 0x7F) << shift;
            if (b < 0x80) break;
        }
        if (type == stz::kExtended) {
            block_at = i;
            csize = c;
            return j;
        }
        i = j + c + 4;
    }
    return 0;
}

// `frame` with payload byte `k` of its first timed block set to `v`, the
// block checksum made valid again.
std::string with_payload_byte(std::string frame, std::size_t k, unsigned v) {
    std::size_t at = 0, csize = 0;
    const std::size_t p = first_timed_payload(frame, at, csize);
    EXPECT_NE(p, 0u);
    frame[p + k] = static_cast<char>(v);
    const std::uint32_t sum = stz::check32(std::string_view(frame).substr(at, p + csize - at));
    for (int b = 0; b < 4; ++b) frame[p + csize + static_cast<std::size_t>(b)] = static_cast<char>((sum >> (8 * b)) & 0xFF);
    return frame;
}

// tests/golden/v2/timed.steps.stz: three blocks, a timed block with mixed
// predictions first (docs/FORMAT.md 1.12, coding 1).
std::string small_timed_frame() {
    const std::string frame =
        slurp(std::filesystem::path(STEPZIP_SOURCE_DIR) / "tests" / "golden" / "v2" / "timed.steps.stz");
    std::size_t at = 0, csize = 0;
    EXPECT_NE(first_timed_payload(frame, at, csize), 0u) << "the golden frame holds a timed block";
    return frame;
}

TEST(TimedBlock, UnknownSubtypeCodingOrFrameIsCorruptAtItsByte) {
    const std::string frame = small_timed_frame();
    ASSERT_TRUE(decompress(frame).ok());
    auto sub = decompress(with_payload_byte(frame, 0, 9));  // 0, 1, 2 and 4 name blocks
    ASSERT_FALSE(sub.ok());
    EXPECT_EQ(sub.error().code, Errc::corrupt);
    EXPECT_NE(sub.error().message.find("payload byte 0: unknown subtype"), std::string::npos) << sub.error().message;
    auto coding = decompress(with_payload_byte(frame, 1, 2));
    ASSERT_FALSE(coding.ok());
    EXPECT_EQ(coding.error().code, Errc::corrupt);
    EXPECT_NE(coding.error().message.find("payload byte 1: unknown coding"), std::string::npos)
        << coding.error().message;
    // The frame says steps instead of timed (descriptor bits 3-4), header check redone.
    std::string steps = frame;
    steps[5] = static_cast<char>((static_cast<unsigned char>(steps[5]) & ~0x18u) | (2u << 3));
    steps[7] = static_cast<char>((stz::hash64(std::string_view(steps).substr(0, 7)) >> 8) & 0xFF);
    auto fmt = decompress(steps);
    ASSERT_FALSE(fmt.ok());
    EXPECT_EQ(fmt.error().code, Errc::corrupt);
    EXPECT_NE(fmt.error().message.find("payload byte 0: a timed block in a frame that is not timed"),
              std::string::npos)
        << fmt.error().message;
    // A 4-connected profile (descriptor bits 0-2: eval4).
    std::string eval4 = frame;
    eval4[5] = static_cast<char>(static_cast<unsigned char>(eval4[5]) & ~0x07u);
    eval4[7] = static_cast<char>((stz::hash64(std::string_view(eval4).substr(0, 7)) >> 8) & 0xFF);
    auto prof = decompress(eval4);
    ASSERT_FALSE(prof.ok());
    EXPECT_TRUE(is_frame_error(prof.error().code)) << prof.error().message;
}

TEST(TimedBlock, EveryTruncationIsRejectedAsTruncated) {
    const std::string frame = small_timed_frame();
    for (std::size_t n = 0; n < frame.size(); ++n) {
        auto r = decompress(std::string_view(frame).substr(0, n));
        ASSERT_FALSE(r.ok()) << "length " << n;
        EXPECT_EQ(r.error().code, Errc::truncated) << "length " << n << ": " << r.error().message;
    }
}

TEST(TimedBlock, EveryPayloadByteFlipDecodesExactlyOrIsRejected) {
    // Flips inside the payload with the block checksum made valid again, so
    // that the timed block's own checks are what reject them.
    const std::string frame = small_timed_frame();
    auto original = decompress(frame);
    ASSERT_TRUE(original.ok());
    std::size_t at = 0, csize = 0;
    ASSERT_NE(first_timed_payload(frame, at, csize), 0u);
    int rejected = 0;
    for (std::size_t k = 0; k < csize; ++k)
        for (int bit = 0; bit < 8; ++bit) {
            std::size_t a = 0, c = 0;
            const std::size_t p = first_timed_payload(frame, a, c);
            const std::string bad =
                with_payload_byte(frame, k, static_cast<unsigned char>(frame[p + k]) ^ (1u << bit));
            auto r = decompress(bad);
            if (r.ok()) {
                // The content checksum of the frame stands behind every accepted decode.
                EXPECT_EQ(*r, *original) << "payload byte " << k << " bit " << bit;
            } else {
                EXPECT_TRUE(is_frame_error(r.error().code)) << r.error().message;
                ++rejected;
            }
        }
    EXPECT_GT(rejected, 0);
}

}  // namespace
}  // namespace stepzip
