// The adaptive binary range coder of the modeled blocks (docs/FORMAT.md
// "Range coder"): random bits under random, adapting probabilities decode
// back exactly and consume exactly the coded bytes; Exp-Golomb values round
// trip over their whole range; a truncated or garbage stream never reads
// past its buffer and is always told apart from the original.
#include <gtest/gtest.h>

#include <limits>
#include <random>
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
    for (int i = 0; i < 10000; ++i) update(p, 0);
    EXPECT_LE(p.p, 65535);
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
