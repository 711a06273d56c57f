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

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>

namespace stepzip::stz {

/// Probability that the next bit is 0, in 1/65536 units (1..65535), and the
/// number of bits seen in this context (saturates at 255). `n` is 16 bits
/// wide (the struct is 4 bytes either way): a store through a char type
/// could alias the coder's state and keep it out of registers.
struct Prob {
    std::uint16_t p = 32768;
    std::uint16_t n = 0;
};

inline constexpr int kMaxShift = 5;

namespace detail {
// shift = min(Max, floor(log2(n + 2))) for every n (0..255).
template <int Max>
struct ShiftTable {
    std::uint8_t v[256];
    constexpr ShiftTable() : v() {
        for (int n = 0; n < 256; ++n) {
            int shift = 0;
            for (unsigned m = static_cast<unsigned>(n) + 2u; m > 1; m >>= 1) ++shift;
            v[n] = static_cast<std::uint8_t>(shift < Max ? shift : Max);
        }
    }
};
inline constexpr ShiftTable<kMaxShift> kShift{};
}  // namespace detail

/// Adaptation: shift = min(kMaxShift, floor(log2(n + 2))); then
/// bit 0: p += (65536 - p) >> shift, bit 1: p -= p >> shift; n += 1.
/// Branch-free: the shift comes from a table, both updates are computed and
/// one is selected.
[[gnu::always_inline]] inline void update(Prob& pr, int bit) noexcept {
    const unsigned shift = detail::kShift.v[pr.n];
    const unsigned p = pr.p;
    const unsigned down = p - (p >> shift);
    const unsigned up = p + ((65536u - p) >> shift);
    pr.p = static_cast<std::uint16_t>(bit ? down : up);
    pr.n = static_cast<std::uint16_t>(pr.n + (pr.n < 255));
}

class RangeEncoder {
public:
    [[gnu::always_inline]] void encode(Prob& pr, int bit) {
        encode_p(pr.p, bit);
        update(pr, bit);
    }
    /// Codes `bit` with probability p0 / 65536 of a 0 (1 <= p0 <= 65535),
    /// nothing adapted.
    [[gnu::always_inline]] void encode_p(std::uint32_t p0, int bit) {
        const std::uint32_t bound = (range_ >> 16) * p0;
        const std::uint32_t mask = 0u - static_cast<std::uint32_t>(bit != 0);
        low_ += bound & mask;
        range_ = (bound & ~mask) | ((range_ - bound) & mask);
        // range >= 2^8 after any bit (p >= 1, range >= 2^24 before it): at
        // most two shifts.
        if (range_ < (1u << 24)) [[unlikely]] {
            range_ <<= 8;
            shift_low();
            if (range_ < (1u << 24)) {
                range_ <<= 8;
                shift_low();
            }
        }
    }
    /// Bytes coded so far (those written and those held for a carry).
    std::size_t size() const noexcept { return out_.size() + static_cast<std::size_t>(cache_size_); }
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
    [[gnu::always_inline]] int decode(Prob& pr) {
        const int bit = decode_p(pr.p);
        update(pr, bit);
        return bit;
    }
    /// Decodes a bit coded with probability p0 / 65536 of a 0, nothing adapted.
    [[gnu::always_inline]] int decode_p(std::uint32_t p0) {
        const std::uint32_t bound = (range_ >> 16) * p0;
        const int bit = code_ >= bound;
        // Branch-free select: the bit is what the model could not predict.
        const std::uint32_t mask = 0u - static_cast<std::uint32_t>(bit);
        code_ -= bound & mask;
        range_ = (bound & ~mask) | ((range_ - bound) & mask);
        if (range_ < (1u << 24)) [[unlikely]] normalize();
        return bit;
    }
    bool overrun() const noexcept { return overrun_; }
    /// All input consumed, nothing read past it.
    bool finished() const noexcept { return !overrun_ && pos_ == in_.size(); }
    std::size_t pos() const noexcept { return pos_; }

private:
    // range >= 2^8 after any bit: at most two bytes are needed.
    [[gnu::always_inline]] void normalize() {
        if (pos_ + 2 <= in_.size()) [[likely]] {
            const auto* b = reinterpret_cast<const unsigned char*>(in_.data()) + pos_;
            range_ <<= 8;
            code_ = (code_ << 8) | b[0];
            ++pos_;
            if (range_ < (1u << 24)) {
                range_ <<= 8;
                code_ = (code_ << 8) | b[1];
                ++pos_;
            }
            return;
        }
        while (range_ < (1u << 24)) {
            range_ <<= 8;
            code_ = (code_ << 8) | next();
        }
    }
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

// `field(k)` names the field the next bits belong to: a no-op here, counted
// by the bench hook's encoder (bench_hooks.hpp).
struct EncIo {
    static constexpr bool kDecode = false;
    RangeEncoder rc;
    bool failed = false;
    void field(int) {}
    [[gnu::always_inline]] int bit(Prob& p, int b) {
        rc.encode(p, b);
        return b;
    }
};

struct DecIo {
    static constexpr bool kDecode = true;
    explicit DecIo(std::string_view in) : rc(in) {}
    RangeDecoder rc;
    bool failed = false;
    void field(int) {}
    [[gnu::always_inline]] int bit(Prob& p, int) { return rc.decode(p); }
};

/// Bit length of v (0 for 0).
inline int bit_length(std::uint64_t v) noexcept { return static_cast<int>(std::bit_width(v)); }

/// Adaptive Exp-Golomb code of any unsigned 64-bit value v:
/// k = bit_length(v + 1) - 1 in unary (k ones then a zero, the i-th unary bit
/// in context unary[min(i, 23)]), then the k bits of v + 1 below its top
/// bit, high to low, the j-th (j = 0 first) in context mant[min(k, 23)][min(j, 7)].
/// A decoder reading more than kUIntMaxBits unary ones fails.
inline constexpr int kUIntMaxBits = 64;
struct UIntModel {
    Prob unary[24];
    Prob mant[24][8];
};

template <class Io>
std::uint64_t code_uint(Io& io, UIntModel& m, std::uint64_t v) {
    // w = v + 1 is 2^64 for v = 2^64 - 1: then k = 64 and the bits below
    // w's top bit are all zero, as the wrapped w = 0 gives them.
    const std::uint64_t w = v + 1;
    const int k = Io::kDecode ? 0 : (w == 0 ? 64 : bit_length(w) - 1);
    int got = 0;
    for (;;) {
        const int more = io.bit(m.unary[got < 23 ? got : 23], got < k);
        if (!more) break;
        if (++got > kUIntMaxBits) {
            io.failed = true;
            return 0;
        }
    }
    std::uint64_t r = 1;  // with got == 64 the leading 1 shifts out: r keeps the low bits
    Prob* row = m.mant[got < 23 ? got : 23];
    for (int j = 0; j < got; ++j) {
        const int b = io.bit(row[j < 7 ? j : 7], static_cast<int>((w >> (got - 1 - j)) & 1u));
        r = (r << 1) | static_cast<unsigned>(b);
    }
    if (got == 64) {  // w = 2^64 + r: only r == 0 is a 64-bit value
        if (r != 0) io.failed = true;
        return std::numeric_limits<std::uint64_t>::max();
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
[[gnu::always_inline]] inline unsigned code_tree(Io& io, Prob* tree, int nbits, unsigned v) {
    unsigned node = 1;
    for (int i = nbits - 1; i >= 0; --i) node = (node << 1) | static_cast<unsigned>(io.bit(tree[node], (v >> i) & 1u));
    return node - (1u << nbits);
}

}  // namespace stepzip::stz
