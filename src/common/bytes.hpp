// The one byte layer of stepzip (not installed): little-endian integers,
// LEB128 varints, zigzag, length-prefixed byte strings and a bounds-checked
// cursor, for the .stz container (src/container/) and the chain files'
// layouts (src/io/). Then the wrapping arithmetic of .stz chain starts.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace stepzip::wire {

inline void put_u8(std::string& out, unsigned v) { out.push_back(static_cast<char>(v & 0xFFu)); }

inline void put_le(std::string& out, std::uint64_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) out.push_back(static_cast<char>(i < 8 ? (v >> (8 * i)) & 0xFFu : 0));
}

inline std::uint64_t get_le(const char* p, int bytes) {
    std::uint64_t v = 0;
    for (int i = 0; i < bytes; ++i) v |= std::uint64_t{static_cast<unsigned char>(p[i])} << (8 * i);
    return v;
}

/// Unsigned LEB128: 7 bits per byte, low group first, high bit = more.
inline void put_varint(std::string& out, std::uint64_t v) {
    while (v >= 0x80) {
        out.push_back(static_cast<char>((v & 0x7F) | 0x80));
        v >>= 7;
    }
    out.push_back(static_cast<char>(v));
}

inline std::uint64_t zigzag(std::int64_t v) {
    return (static_cast<std::uint64_t>(v) << 1) ^ static_cast<std::uint64_t>(v >> 63);
}
inline std::int64_t unzigzag(std::uint64_t v) {
    return static_cast<std::int64_t>(v >> 1) ^ -static_cast<std::int64_t>(v & 1);
}

inline void put_svarint(std::string& out, std::int64_t v) { put_varint(out, zigzag(v)); }

/// A byte string preceded by its length as a varint (read by Cursor::sized).
inline void put_sized(std::string& out, std::string_view s) {
    put_varint(out, s.size());
    out.append(s);
}

/// Bounds-checked cursor over a byte range. Every read reports failure instead
/// of reading past the end; `pos()` is the offset of the next byte.
class Cursor {
public:
    Cursor() = default;
    explicit Cursor(std::string_view data) : data_(data) {}

    std::size_t pos() const noexcept { return pos_; }
    std::size_t left() const noexcept { return data_.size() - pos_; }
    bool done() const noexcept { return pos_ == data_.size(); }

    bool u8(unsigned& v) {
        if (pos_ >= data_.size()) return false;
        v = static_cast<unsigned char>(data_[pos_++]);
        return true;
    }
    bool u8(std::uint8_t& v) {
        unsigned u;
        if (!u8(u)) return false;
        v = static_cast<std::uint8_t>(u);
        return true;
    }
    /// A varint of at most 10 bytes whose value fits 64 bits; false when it
    /// runs past the end or is over-long (`overlong` set).
    bool varint(std::uint64_t& v, bool* overlong = nullptr) {
        v = 0;
        for (int shift = 0; shift < 64; shift += 7) {
            unsigned b;
            if (!u8(b)) return false;
            if (shift == 63 && b > 1) break;
            v |= std::uint64_t{b & 0x7Fu} << shift;
            if ((b & 0x80u) == 0) return true;
        }
        if (overlong) *overlong = true;
        return false;
    }
    bool svarint(std::int64_t& v, bool* overlong = nullptr) {
        std::uint64_t u;
        if (!varint(u, overlong)) return false;
        v = unzigzag(u);
        return true;
    }
    bool bytes(std::size_t n, std::string_view& v) {
        if (n > left()) return false;
        v = data_.substr(pos_, n);
        pos_ += n;
        return true;
    }
    /// A byte string written by put_sized().
    bool sized(std::string_view& v) {
        std::uint64_t n;
        return varint(n) && n <= left() && bytes(static_cast<std::size_t>(n), v);
    }

private:
    std::string_view data_;
    std::size_t pos_ = 0;
};

}  // namespace stepzip::wire

namespace stepzip::stz {

using namespace wire;

/// a - b and a + b modulo 2^64. Chain starts are coded as the wrapping
/// difference from a reference point, so any two coordinates have one and the
/// decoder's wrapping sum gives the start back exactly.
inline std::int64_t wrap_sub(std::int64_t a, std::int64_t b) {
    return static_cast<std::int64_t>(static_cast<std::uint64_t>(a) - static_cast<std::uint64_t>(b));
}
inline std::int64_t wrap_add(std::int64_t a, std::int64_t b) {
    return static_cast<std::int64_t>(static_cast<std::uint64_t>(a) + static_cast<std::uint64_t>(b));
}
/// |v| without overflow (|INT64_MIN| = 2^63).
inline std::uint64_t magnitude(std::int64_t v) {
    return v < 0 ? 0 - static_cast<std::uint64_t>(v) : static_cast<std::uint64_t>(v);
}
/// Largest |coordinate| of a decoded chain start: chain files hold
/// coordinates within +-2^62, and a chain piece that continues another starts
/// where that one ended, which is less than 2^61 steps further.
inline constexpr std::int64_t kMaxStartCoordinate = (std::int64_t{1} << 62) + (std::int64_t{1} << 61);
inline bool start_in_range(std::int64_t v) { return v >= -kMaxStartCoordinate && v <= kMaxStartCoordinate; }

}  // namespace stepzip::stz
