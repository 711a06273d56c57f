// The adaptive binary range coder of the modeled blocks (docs/FORMAT.md
// "Range coder"): the coder writes the bytes that docs/FORMAT.md section 1.4
// prescribes (a hand-worked example, and a plain reference coder written
// here from the document, with no code shared with src/container); random
// bits under random, adapting probabilities decode back exactly and consume
// exactly the coded bytes; Exp-Golomb values round trip over their whole
// range and decode bit by bit as the document says; a truncated or garbage
// stream never reads past its buffer and is always told apart from the
// original.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "../src/container/range_coder.hpp"

namespace stepzip::stz {
namespace {

struct Coded {
    std::vector<int> ctx;   // context index of each bit
    std::vector<int> bits;  // the bits
    std::string bytes;
};

// Bits drawn with per-context biases (some near 0 or 1, some near 1/2).
Coded make_stream(std::uint64_t seed, std::size_t n, int contexts) {
    std::mt19937_64 rng(seed);
    std::vector<double> bias(static_cast<std::size_t>(contexts));
    for (double& b : bias) {
        const int kind = static_cast<int>(rng() % 3);
        b = kind == 0 ? 0.002 * static_cast<double>(rng() % 10)
            : kind == 1 ? 1.0 - 0.002 * static_cast<double>(rng() % 10)
                        : static_cast<double>(rng() % 1000) / 1000.0;
    }
    Coded c;
    std::vector<Prob> probs(static_cast<std::size_t>(contexts));
    RangeEncoder enc;
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (std::size_t i = 0; i < n; ++i) {
        const int k = static_cast<int>(rng() % static_cast<std::uint64_t>(contexts));
        const int bit = u(rng) < bias[static_cast<std::size_t>(k)] ? 1 : 0;
        c.ctx.push_back(k);
        c.bits.push_back(bit);
        enc.encode(probs[static_cast<std::size_t>(k)], bit);
    }
    c.bytes = enc.finish();
    return c;
}

// Decodes c.bits.size() bits of `bytes` with c's contexts; true when every
// bit equals the original.
bool decode_same(const Coded& c, std::string_view bytes, RangeDecoder& dec) {
    std::vector<Prob> probs(1024);
    bool same = true;
    for (std::size_t i = 0; i < c.bits.size(); ++i)
        same &= dec.decode(probs[static_cast<std::size_t>(c.ctx[i])]) == c.bits[i];
    (void)bytes;
    return same;
}

// ---- A reference coder written from docs/FORMAT.md section 1.4 alone ----
// Deliberately plain (branches, no tables), so that a changed constant in
// src/container/range_coder.hpp (in the encoder and decoder alike) shows up
// as a difference from what the document prescribes.
struct RefProb {
    std::uint32_t p = 32768;
    std::uint32_t n = 0;
};

void ref_update(RefProb& c, int bit) {
    int shift = 0;  // floor(log2(n + 2)), at most 5
    for (std::uint32_t v = c.n + 2; v >= 2; v /= 2) ++shift;
    if (shift > 5) shift = 5;
    if (bit == 0) c.p = c.p + ((65536 - c.p) >> shift);
    else c.p = c.p - (c.p >> shift);
    if (c.n < 255) c.n = c.n + 1;
}

struct RefEncoder {
    std::uint64_t low = 0;
    std::uint32_t range = 0xFFFFFFFFu;
    std::uint32_t cache = 0;
    std::uint64_t cache_size = 1;
    std::vector<unsigned> out;

    void shift_low() {
        if (low < 0xFF000000u || low >= (std::uint64_t{1} << 32)) {
            const std::uint32_t carry = static_cast<std::uint32_t>(low >> 32);
            out.push_back((cache + carry) % 256);
            for (std::uint64_t i = 1; i < cache_size; ++i) out.push_back((0xFF + carry) % 256);
            cache = static_cast<std::uint32_t>((low >> 24) & 0xFF);
            cache_size = 0;
        }
        cache_size += 1;
        low = (low & 0x00FFFFFF) << 8;
    }
    void encode(RefProb& c, int bit) {
        const std::uint32_t bound = (range >> 16) * c.p;
        if (bit == 0) {
            range = bound;
        } else {
            low += bound;
            range -= bound;
        }
        ref_update(c, bit);
        while (range < (1u << 24)) {
            range <<= 8;
            shift_low();
        }
    }
    std::string finish() {
        for (int i = 0; i < 5; ++i) shift_low();
        EXPECT_EQ(out.at(0), 0u) << "the first byte emitted is always 0";
        std::string bytes;
        for (std::size_t i = 1; i < out.size(); ++i) bytes.push_back(static_cast<char>(out[i]));
        return bytes;
    }
};

struct RefDecoder {
    std::string_view in;
    std::size_t pos = 0;
    std::uint32_t range = 0xFFFFFFFFu;
    std::uint32_t code = 0;
    explicit RefDecoder(std::string_view bytes) : in(bytes) {
        for (int i = 0; i < 4; ++i) code = (code << 8) | next();
    }
    std::uint32_t next() { return pos < in.size() ? static_cast<unsigned char>(in[pos++]) : 0u; }
    int decode(RefProb& c) {
        const std::uint32_t bound = (range >> 16) * c.p;
        int bit;
        if (code < bound) {
            range = bound;
            bit = 0;
        } else {
            code -= bound;
            range -= bound;
            bit = 1;
        }
        ref_update(c, bit);
        while (range < (1u << 24)) {
            range <<= 8;
            code = (code << 8) | next();
        }
        return bit;
    }
    // uint(M) of section 1.4: k ones then a zero, then the k bits of v + 1
    // below its top bit (values below 2^63 only, enough for the test).
    std::uint64_t decode_uint(RefProb (&unary)[24], RefProb (&mant)[24][8]) {
        int k = 0;
        while (decode(unary[std::min(k, 23)]) == 1) ++k;
        std::uint64_t w = 1;
        for (int j = 0; j < k; ++j) w = (w << 1) | static_cast<unsigned>(decode(mant[std::min(k, 23)][std::min(j, 7)]));
        return w - 1;
    }
};

std::string hex(std::string_view b) {
    static const char* digits = "0123456789abcdef";
    std::string s;
    for (unsigned char c : b) {
        s += digits[c >> 4];
        s += digits[c & 15];
        s += ' ';
    }
    return s;
}

std::string encode_with_library(const std::vector<int>& ctx, const std::vector<int>& bits, int contexts) {
    std::vector<Prob> probs(static_cast<std::size_t>(contexts));
    RangeEncoder enc;
    for (std::size_t i = 0; i < bits.size(); ++i) enc.encode(probs[static_cast<std::size_t>(ctx[i])], bits[i]);
    return enc.finish();
}

std::string encode_with_reference(const std::vector<int>& ctx, const std::vector<int>& bits, int contexts) {
    std::vector<RefProb> probs(static_cast<std::size_t>(contexts));
    RefEncoder enc;
    for (std::size_t i = 0; i < bits.size(); ++i) enc.encode(probs[static_cast<std::size_t>(ctx[i])], bits[i]);
    return enc.finish();
}

// Worked by hand from section 1.4. One 0 bit at p = 32768: bound =
// 0xFFFF * 0x8000 = 0x7FFF8000 becomes the range, low stays 0, and the five
// final shift_lows emit 00 00 00 00 00; the first is dropped. One 1 bit: low
// = 0x7FFF8000; shift_low 1 emits the cache 00 (dropped) and caches 7F, low
// = 0xFF800000; shift_low 2 holds it back (0xFF000000 <= low < 2^32), so
// cache_size = 2, low = 0x80000000; shift_low 3 emits 7F FF and caches 80;
// shift_lows 4 and 5 emit 80 and 00.
TEST(RangeCoderBytes, OneBitWorkedByHand) {
    for (int bit : {0, 1}) {
        RangeEncoder enc;
        Prob p;
        enc.encode(p, bit);
        const std::string got = enc.finish();
        const std::string want = bit == 0 ? std::string("\x00\x00\x00\x00", 4) : std::string("\x7F\xFF\x80\x00", 4);
        EXPECT_EQ(hex(got), hex(want)) << "bit " << bit;
        // and the probability after it, by section 1.4: shift 1 at n = 0
        EXPECT_EQ(p.p, bit == 0 ? 49152 : 16384);
        EXPECT_EQ(p.n, 1);
    }
}

TEST(RangeCoderBytes, AdaptationFollowsTheDocumentedSchedule) {
    // shift = min(5, floor(log2(n + 2))): 1, 1, 2, 2, 2, 2, 3, ... 5
    RefProb r;
    Prob p;
    std::mt19937_64 rng(3);
    for (int i = 0; i < 600; ++i) {
        const int bit = static_cast<int>(rng() % 7 == 0);
        update(p, bit);
        ref_update(r, bit);
        ASSERT_EQ(p.p, r.p) << "after bit " << i;
        ASSERT_EQ(p.n, r.n) << "after bit " << i;
    }
    // A run of zeros from the start, worked by hand: 32768 -> 49152 (shift 1)
    // -> 57344 (shift 1) -> 59392 (shift 2).
    Prob z;
    update(z, 0);
    EXPECT_EQ(z.p, 49152);
    update(z, 0);
    EXPECT_EQ(z.p, 57344);
    update(z, 0);
    EXPECT_EQ(z.p, 59392);
}

TEST(RangeCoderBytes, ShortSequenceHasFixedBytes) {
    // Eight bits in one context and four more alternating between two:
    // the bytes below were worked out with the reference coder above and
    // are pinned so that both it and the library must keep producing them.
    const std::vector<int> ctx = {0, 0, 0, 0, 0, 0, 0, 0, 1, 2, 1, 2};
    const std::vector<int> bits = {1, 0, 1, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    const std::string want("\x9a\x38\xbb\xbb\xe4\x00", 6);
    EXPECT_EQ(hex(encode_with_reference(ctx, bits, 3)), hex(want));
    EXPECT_EQ(hex(encode_with_library(ctx, bits, 3)), hex(want));
}

TEST(RangeCoderBytes, LibraryEncoderWritesWhatTheDocumentPrescribes) {
    // Long random streams (carries, runs of FF, skewed and flat contexts):
    // byte for byte the reference coder's output, and the reference
    // decoder reads the library's bytes back.
    for (std::uint64_t seed = 1; seed <= 12; ++seed) {
        const Coded c = make_stream(seed * 31, 1000 + seed * 1500, 1 + static_cast<int>(seed % 9));
        const int contexts = 1 + static_cast<int>(seed % 9);
        const std::string ref = encode_with_reference(c.ctx, c.bits, contexts);
        ASSERT_EQ(c.bytes.size(), ref.size()) << "seed " << seed;
        EXPECT_TRUE(c.bytes == ref) << "seed " << seed << ": first difference at byte "
                                    << std::distance(c.bytes.begin(), std::mismatch(c.bytes.begin(), c.bytes.end(), ref.begin()).first);
        RefDecoder dec(c.bytes);
        std::vector<RefProb> probs(static_cast<std::size_t>(contexts));
        std::size_t wrong = 0;
        for (std::size_t i = 0; i < c.bits.size(); ++i)
            wrong += dec.decode(probs[static_cast<std::size_t>(c.ctx[i])]) != c.bits[i];
        EXPECT_EQ(wrong, 0u) << "seed " << seed;
    }
}

TEST(RangeCoderBytes, ExpGolombIsTheDocumentedBinarization) {
    // Values coded by the library's code_uint, read back bit by bit by the
    // reference decoder with the contexts section 1.4 names.
    std::mt19937_64 rng(17);
    std::vector<std::uint64_t> values = {0, 1, 2, 3, 6, 7, 8, 255, 256, 1000000};
    for (int i = 0; i < 400; ++i) values.push_back(rng() >> (2 + rng() % 62));
    EncIo enc;
    UIntModel m;
    for (std::uint64_t v : values) code_uint(enc, m, v);
    const std::string bytes = enc.rc.finish();
    RefDecoder dec(bytes);
    RefProb unary[24];
    RefProb mant[24][8];
    for (std::size_t i = 0; i < values.size(); ++i) ASSERT_EQ(dec.decode_uint(unary, mant), values[i]) << i;
}

TEST(RangeCoder, RandomBitsWithRandomProbabilitiesRoundTrip) {
    for (std::uint64_t seed = 1; seed <= 40; ++seed) {
        const std::size_t n = seed * 997 % 20000;
        const Coded c = make_stream(seed, n, 1 + static_cast<int>(seed % 64));
        RangeDecoder dec(c.bytes);
        EXPECT_TRUE(decode_same(c, c.bytes, dec)) << "seed " << seed;
        EXPECT_TRUE(dec.finished()) << "seed " << seed << ": consumed " << dec.pos() << " of "
                                    << c.bytes.size();
    }
}

TEST(RangeCoder, SkewedStreamsCostFarLessThanABitPerBit) {
    RangeEncoder enc;
    Prob p;
    for (int i = 0; i < 100000; ++i) enc.encode(p, i % 1000 == 0);
    EXPECT_LT(enc.finish().size(), 100000u / 8 / 10);
}

TEST(RangeCoder, ProbabilitiesStayInsideTheirRange) {
    Prob p;
    for (int i = 0; i < 10000; ++i) {
        update(p, 0);
        ASSERT_GE(p.p, 1);
    }
    for (int i = 0; i < 10000; ++i) {
        update(p, 1);
        ASSERT_GE(p.p, 1);
    }
    // Ten thousand zeros push p towards 65536; it must stop below it (a
    // 16-bit p that reached 65536 would wrap to 0 and leave bit 0 no room).
    for (int i = 0; i < 10000; ++i) {
        update(p, 0);
        ASSERT_GE(p.p, 1);
    }
    EXPECT_GE(p.p, 65536 - 32);  // it did climb (one step of shift 5 below the top)
}

TEST(RangeCoder, ExpGolombValuesRoundTrip) {
    std::mt19937_64 rng(5);
    // the whole 64-bit range, both ends included
    constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();
    constexpr std::int64_t kMin = std::numeric_limits<std::int64_t>::min();
    std::vector<std::uint64_t> u = {0, 1, 2, 3, 7, 8, (std::uint64_t{1} << 40) - 2,
                                    std::uint64_t{1} << 63, kMax - 1, kMax};
    std::vector<std::int64_t> s = {0, 1, -1, 63, -64, (std::int64_t{1} << 39) - 1, -(std::int64_t{1} << 39),
                                   kMin, kMin + 1, std::numeric_limits<std::int64_t>::max()};
    for (int i = 0; i < 3000; ++i) {
        u.push_back(rng() >> (rng() % 64));
        s.push_back(static_cast<std::int64_t>(rng() >> (1 + rng() % 63)) * (rng() % 2 ? 1 : -1));
    }
    EncIo enc;
    UIntModel mu[3], ms[3];
    for (std::size_t i = 0; i < u.size(); ++i) {
        code_uint(enc, mu[i % 3], u[i]);
        code_sint(enc, ms[i % 3], s[i]);
    }
    const std::string bytes = enc.rc.finish();
    DecIo dec(bytes);
    UIntModel du[3], ds[3];
    for (std::size_t i = 0; i < u.size(); ++i) {
        ASSERT_EQ(code_uint(dec, du[i % 3], 0), u[i]) << i;
        ASSERT_EQ(code_sint(dec, ds[i % 3], 0), s[i]) << i;
    }
    EXPECT_FALSE(dec.failed);
    EXPECT_TRUE(dec.rc.finished());
}

TEST(RangeCoder, OverlongExpGolombPrefixFails) {
    // Bits of all ones decode as an endless unary prefix: the decoder stops
    // after 64 ones (the longest prefix a 64-bit value has).
    const std::string ones(64, '\xFF');
    DecIo dec(ones);
    UIntModel m;
    code_uint(dec, m, 0);
    EXPECT_TRUE(dec.failed);
}

TEST(RangeCoder, TreeSymbolsRoundTrip) {
    std::mt19937_64 rng(9);
    std::vector<unsigned> v;
    for (int i = 0; i < 5000; ++i) v.push_back(static_cast<unsigned>(rng() % 512) >> (rng() % 6));
    EncIo enc;
    Prob tree[512];
    for (unsigned x : v) code_tree(enc, tree, 9, x);
    const std::string bytes = enc.rc.finish();
    DecIo dec(bytes);
    Prob dtree[512];
    for (unsigned x : v) ASSERT_EQ(code_tree(dec, dtree, 9, 0), x);
    EXPECT_TRUE(dec.rc.finished());
}

TEST(RangeCoder, TruncatedStreamsAreNeverTakenForTheOriginal) {
    const Coded c = make_stream(77, 3000, 16);
    ASSERT_GT(c.bytes.size(), 20u);
    for (std::size_t n = 0; n < c.bytes.size(); ++n) {
        const std::string_view cut = std::string_view(c.bytes).substr(0, n);
        RangeDecoder dec(cut);
        const bool same = decode_same(c, cut, dec);
        EXPECT_LE(dec.pos(), n);
        EXPECT_TRUE(!same || !dec.finished()) << "length " << n;
        EXPECT_TRUE(dec.overrun() || !same) << "length " << n;
    }
}

TEST(RangeCoder, GarbageNeverReadsPastItsBuffer) {
    std::mt19937_64 rng(11);
    for (int t = 0; t < 200; ++t) {
        std::string junk(rng() % 64, '\0');
        for (char& ch : junk) ch = static_cast<char>(rng());
        DecIo dec(junk);
        UIntModel m[4];
        Prob tree[8];
        for (int i = 0; i < 500 && !dec.failed; ++i) {
            code_uint(dec, m[i % 4], 0);
            code_tree(dec, tree, 3, 0);
        }
        EXPECT_LE(dec.rc.pos(), junk.size());
        if (junk.size() < 16) EXPECT_TRUE(dec.rc.overrun() || dec.failed);
    }
}

}  // namespace
}  // namespace stepzip::stz
