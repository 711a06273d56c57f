// Adaptive binary range coder of the modeled blocks (docs/FORMAT.md
// "Range coder"): LZMA-style carry-less-decoder arithmetic with 16-bit
// probabilities whose adaptation rate starts fast and settles at 1/2^kMaxShift.
// Internal to src/container.
//
// Encoder and decoder share the model code through the `Io` types below:
// `EncIo::bit(p, b)` codes `b` and returns it, `DecIo::bit(p, ignored)`
// returns the decoded bit, so one template describes both directions.
// Complexity: O(1) per bit. Not thread-safe (one object per block).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace stepzip::stz {

/// Probability that the next bit is 0, in 1/65536 units (1..65535), and the
/// number of bits seen in this context (saturates at 255).
struct Prob {
    std::uint16_t p = 32768;
    std::uint8_t n = 0;
};

inline constexpr int kMaxShift = 5;

/// Adaptation: shift = min(kMaxShift, floor(log2(n + 2))); then
/// bit 0: p += (65536 - p) >> shift, bit 1: p -= p >> shift; n += 1.
inline void update(Prob& pr, int bit) noexcept {
    unsigned v = pr.n + 2u;
    int shift = 0;
    while (v > 1) {
        v >>= 1;
        ++shift;
    }
    if (shift > kMaxShift) shift = kMaxShift;
    if (bit)
        pr.p = static_cast<std::uint16_t>(pr.p - (pr.p >> shift));
    else
        pr.p = static_cast<std::uint16_t>(pr.p + ((65536u - pr.p) >> shift));
    if (pr.n < 255) ++pr.n;
}

class RangeEncoder {
public:
    void encode(Prob& pr, int bit) {
        const std::uint32_t bound = (range_ >> 16) * pr.p;
        if (bit) {
            low_ += bound;
            range_ -= bound;
        } else {
            range_ = bound;
        }
        update(pr, bit);
        while (range_ < (1u << 24)) {
            range_ <<= 8;
            shift_low();
        }
    }
    /// Flushes and returns the coded bytes (the always-zero first byte of the
    /// LZMA arithmetic is not stored).
    std::string finish() {
        for (int i = 0; i < 5; ++i) shift_low();
        return out_.substr(1);
    }

private:
    void shift_low() {
        if (static_cast<std::uint32_t>(low_) < 0xFF000000u || (low_ >> 32) != 0) {
            const unsigned carry = static_cast<unsigned>(low_ >> 32);
            unsigned char temp = cache_;
            do {
                out_.push_back(static_cast<char>((temp + carry) & 0xFFu));
                temp = 0xFF;
            } while (--cache_size_ != 0);
            cache_ = static_cast<unsigned char>((low_ >> 24) & 0xFFu);
        }
        ++cache_size_;
        low_ = (low_ & 0x00FFFFFFu) << 8;
    }

    std::uint64_t low_ = 0;
    std::uint32_t range_ = 0xFFFFFFFFu;
    unsigned char cache_ = 0;
    std::uint64_t cache_size_ = 1;
    std::string out_;
};

/// Decoder over a byte range. Every read is bounds-checked: a read past the
/// end yields 0 and sets overrun(); a valid stream is consumed exactly
/// (finished() is true after its last bit).
class RangeDecoder {
public:
    explicit RangeDecoder(std::string_view in) : in_(in) {
        for (int i = 0; i < 4; ++i) code_ = (code_ << 8) | next();
    }
    int decode(Prob& pr) {
        const std::uint32_t bound = (range_ >> 16) * pr.p;
        int bit;
        if (code_ < bound) {
            range_ = bound;
            bit = 0;
        } else {
            code_ -= bound;
            range_ -= bound;
            bit = 1;
        }
        update(pr, bit);
        while (range_ < (1u << 24)) {
            range_ <<= 8;
            code_ = (code_ << 8) | next();
        }
        return bit;
    }
    bool overrun() const noexcept { return overrun_; }
    /// All input consumed, nothing read past it.
    bool finished() const noexcept { return !overrun_ && pos_ == in_.size(); }
    std::size_t pos() const noexcept { return pos_; }

private:
    std::uint32_t next() {
        if (pos_ < in_.size()) return static_cast<unsigned char>(in_[pos_++]);
        overrun_ = true;
        return 0;
    }
    std::string_view in_;
    std::size_t pos_ = 0;
    std::uint32_t code_ = 0;
    std::uint32_t range_ = 0xFFFFFFFFu;
    bool overrun_ = false;
};

struct EncIo {
    static constexpr bool kDecode = false;
    RangeEncoder rc;
    bool failed = false;
    int field = 0;           // statistics: field being coded
    double cost[16] = {};    // statistics: bits spent per field (STEPZIP_MODEL_STATS builds)
    int bit(Prob& p, int b) {
#ifdef STEPZIP_MODEL_STATS
        const double q = p.p / 65536.0;
        cost[field] -= std::log2(b ? 1 - q : q);
#endif
        rc.encode(p, b);
        return b;
    }
};

struct DecIo {
    static constexpr bool kDecode = true;
    explicit DecIo(std::string_view in) : rc(in) {}
    RangeDecoder rc;
    bool failed = false;
    int bit(Prob& p, int) { return rc.decode(p); }
};

/// Bit length of v (0 for 0).
inline int bit_length(std::uint64_t v) noexcept {
    int n = 0;
    while (v) {
        v >>= 1;
        ++n;
    }
    return n;
}

/// Adaptive Exp-Golomb code of an unsigned value v < 2^kUIntMaxBits - 1:
/// k = bit_length(v + 1) - 1 in unary (k ones then a zero, the i-th unary bit
/// in context unary[min(i, 23)]), then the k bits of v + 1 below its top
/// bit, high to low, the j-th (j = 0 first) in context mant[min(k, 23)][min(j, 7)].
/// A decoder reading more than kUIntMaxBits unary ones fails.
inline constexpr int kUIntMaxBits = 40;
struct UIntModel {
    Prob unary[24];
    Prob mant[24][8];
};

template <class Io>
std::uint64_t code_uint(Io& io, UIntModel& m, std::uint64_t v) {
    const std::uint64_t w = v + 1;
    const int k = Io::kDecode ? 0 : bit_length(w) - 1;
    int got = 0;
    for (;;) {
        const int more = io.bit(m.unary[got < 23 ? got : 23], got < k);
        if (!more) break;
        if (++got > kUIntMaxBits) {
            io.failed = true;
            return 0;
        }
    }
    std::uint64_t r = 1;
    Prob* row = m.mant[got < 23 ? got : 23];
    for (int j = 0; j < got; ++j) {
        const int b = io.bit(row[j < 7 ? j : 7], static_cast<int>((w >> (got - 1 - j)) & 1u));
        r = (r << 1) | static_cast<unsigned>(b);
    }
    return r - 1;
}

/// Signed value as the Exp-Golomb code of its zigzag.
template <class Io>
std::int64_t code_sint(Io& io, UIntModel& m, std::int64_t v) {
    const std::uint64_t z = (static_cast<std::uint64_t>(v) << 1) ^ static_cast<std::uint64_t>(v >> 63);
    const std::uint64_t r = code_uint(io, m, z);
    return static_cast<std::int64_t>(r >> 1) ^ -static_cast<std::int64_t>(r & 1);
}

/// A value of `nbits` bits, high to low, through a binary tree of contexts
/// `tree[1 .. 2^nbits - 1]` (node 1 the root, node 2n + b the child).
template <class Io>
unsigned code_tree(Io& io, Prob* tree, int nbits, unsigned v) {
    unsigned node = 1;
    for (int i = nbits - 1; i >= 0; --i) node = (node << 1) | static_cast<unsigned>(io.bit(tree[node], (v >> i) & 1u));
    return node - (1u << nbits);
}

}  // namespace stepzip::stz
