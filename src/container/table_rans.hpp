// Static-table entropy coding for the table block (docs/FORMAT.md "Table
// block"): per-block frequency tables, two interleaved rANS states with
// 16-bit renormalization, and a raw bit stream for the extra bits of
// bucketed values. Decoding a symbol is one table look-up, a multiply and
// at most one 16-bit read. Internal to src/container.
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace stepzip::stz::table {

inline constexpr std::uint32_t kRansLow = 1u << 16;  // state lies in [kRansLow, 2^32)
inline constexpr int kMaxPrecision = 12;             // table sizes 2^1 .. 2^12

/// One table as the payload describes it: the symbols used, with their
/// frequencies summing to 2^precision.
struct FreqTable {
    int precision = 0;  ///< 0: table unused
    std::vector<std::uint16_t> symbol;
    std::vector<std::uint32_t> freq;
};

/// Decoder entry of one slot: the symbol, its frequency and the slot's
/// place among the symbol's slots (slot - start(s)), the state's next value
/// being one multiply and one add; padded to eight bytes (one scaled index).
struct Slot {
    std::uint16_t symbol, freq, offset, unused = 0;
};

/// The decoding table of a FreqTable (2^precision slots).
struct DecodeTable {
    int precision = -1;  ///< -1: no table (the payload left it unused)
    std::uint32_t mask = 0;  ///< 2^precision - 1
    std::vector<Slot> slots;
};

/// Encoder entry: per symbol, its frequency (0: absent) and first slot.
struct EncodeTable {
    int precision = 0;
    std::vector<std::uint32_t> freq, start;
};

/// The rANS stream of a sequence of symbols given forward, each a (table,
/// symbol) pair whose table indexes `tables`: encoded backward (symbol i by
/// state i & 1) into two u32 states (little-endian), then 16-bit words
/// (little-endian) in the order the decoder reads them. The words are
/// written from the end of a buffer of one word per symbol (at most one
/// each), which then reads forward in the decoder's order.
template <class Sym, std::size_t N>
std::string rans_encode(const std::vector<Sym>& syms, const std::array<EncodeTable, N>& tables) {
    // A state stays below 2^32: renormalized below ((2^16 >> P) << 16) f,
    // it becomes at most (x / f) 2^P + f - 1 < 2^32.
    std::uint32_t x[2] = {kRansLow, kRansLow};
    const auto words = std::make_unique_for_overwrite<std::uint16_t[]>(syms.size());
    std::uint16_t* const end = words.get() + syms.size();
    std::uint16_t* w = end;
    for (std::size_t i = syms.size(); i-- > 0;) {
        const EncodeTable& t = tables[syms[i].first];
        const unsigned sym = syms[i].second;
        const std::uint32_t f = t.freq.data()[sym];
        std::uint32_t& s = x[i & 1];
        if (std::uint64_t{s} >= ((std::uint64_t{kRansLow} >> t.precision) << 16) * f) {
            *--w = static_cast<std::uint16_t>(s & 0xFFFF);
            s >>= 16;
        }
        s = ((s / f) << t.precision) + s % f + t.start.data()[sym];
    }
    const auto nwords = static_cast<std::size_t>(end - w);
    std::string out(8 + 2 * nwords, '\0');
    // Little-endian hosts only (as the decoder).
    std::memcpy(out.data(), x, 8);
    if (nwords > 0) std::memcpy(out.data() + 8, w, 2 * nwords);
    return out;
}

/// rANS decoder. Reading past the stream sets `failed` (words read as 0).
class RansDecoder {
public:
    explicit RansDecoder(std::string_view s) : p_(reinterpret_cast<const unsigned char*>(s.data())),
                                               end_(p_ + s.size()), begin_(p_) {
        if (s.size() < 8) {
            failed = true;
            p_ = end_;
            return;
        }
        for (int k = 0; k < 2; ++k) {
            std::uint32_t v;
            std::memcpy(&v, p_, 4);
            x_[k] = v;  // little-endian hosts only (as the rest of the library)
            p_ += 4;
        }
        if (x_[0] < kRansLow || x_[1] < kRansLow) failed = true;
    }
    /// A symbol of `t` (a table, precision >= 0).
    unsigned get(const DecodeTable& t) {
        // The state of this symbol is x_[0]; it moves to x_[1], the other
        // state to x_[0] for the next symbol.
        std::uint32_t x = x_[0];
        const Slot e = t.slots.data()[x & t.mask];
        x = e.freq * (x >> t.precision) + e.offset;
        x_[0] = x_[1];
        if (x < kRansLow) {
            if (end_ - p_ >= 2) {
                x = (x << 16) | p_[0] | (std::uint32_t{p_[1]} << 8);
                p_ += 2;
            } else {
                failed = true;
                x = kRansLow;
            }
        }
        x_[1] = x;
        return e.symbol;
    }
    /// Stream offset of the next word.
    std::size_t pos() const { return static_cast<std::size_t>(p_ - begin_); }
    /// Every word read and both states back at their initial value.
    bool finished() const { return !failed && p_ == end_ && x_[0] == kRansLow && x_[1] == kRansLow; }
    bool failed = false;

private:
    const unsigned char* p_;
    const unsigned char* end_;
    const unsigned char* begin_;
    std::uint32_t x_[2] = {kRansLow, kRansLow};  // x_[0]: the next symbol's
};

/// Raw bits, low bit first within each byte, written forward.
class BitWriter {
public:
    void put(std::uint64_t v, int n) {
        if (n > 32) {
            put(v & 0xFFFFFFFFu, 32);
            put(v >> 32, n - 32);
            return;
        }
        acc_ |= (v & ((std::uint64_t{1} << n) - 1)) << fill_;
        fill_ += n;
        while (fill_ >= 8) {
            out_.push_back(static_cast<char>(acc_ & 0xFF));
            acc_ >>= 8;
            fill_ -= 8;
        }
    }
    std::string finish() {
        if (fill_ > 0) out_.push_back(static_cast<char>(acc_ & 0xFF));
        acc_ = 0;
        fill_ = 0;
        return std::move(out_);
    }

private:
    std::string out_;
    std::uint64_t acc_ = 0;
    int fill_ = 0;
};

/// Reads what BitWriter wrote; reading past the end sets `failed`.
class BitReader {
public:
    explicit BitReader(std::string_view s) : p_(reinterpret_cast<const unsigned char*>(s.data())),
                                             end_(p_ + s.size()), begin_(p_) {}
    std::uint64_t get(int n) {
        if (n > 32) {
            const std::uint64_t lo = get(32);
            return lo | (get(n - 32) << 32);
        }
        while (fill_ < n) {
            if (p_ == end_) {
                failed = true;
                return 0;
            }
            acc_ |= std::uint64_t{*p_++} << fill_;
            fill_ += 8;
        }
        const std::uint64_t v = acc_ & ((std::uint64_t{1} << n) - 1);
        acc_ >>= n;
        fill_ -= n;
        return v;
    }
    std::size_t pos() const { return static_cast<std::size_t>(p_ - begin_); }
    /// Every byte read and the unread bits of the last one zero.
    bool finished() const { return !failed && p_ == end_ && acc_ == 0; }
    bool failed = false;

private:
    const unsigned char* p_;
    const unsigned char* end_;
    const unsigned char* begin_;
    std::uint64_t acc_ = 0;
    int fill_ = 0;
};

/// Bucket of an unsigned value: v < 8 is its own symbol; above, the
/// symbol 8 + 2 (k - 3) + m names the bit length k + 1 and the bit m below
/// the top bit, and k - 1 extra bits follow.
inline unsigned bucket_of(std::uint64_t v, int& nbits, std::uint64_t& extra) {
    if (v < 8) {
        nbits = 0;
        extra = 0;
        return static_cast<unsigned>(v);
    }
    const int k = std::bit_width(v) - 1;
    nbits = k - 1;
    extra = v & ((std::uint64_t{1} << (k - 1)) - 1);
    return 8 + 2 * static_cast<unsigned>(k - 3) + static_cast<unsigned>((v >> (k - 1)) & 1);
}
/// Symbols of bucket_of for 64-bit values.
inline constexpr unsigned kBuckets = 8 + 2 * 61;

}  // namespace stepzip::stz::table
