// stepzip — internals shared by the chain-file readers and writers
// (freeman_format.cpp, points_format.cpp, steps_format.cpp, document.cpp).
//
// Not installed; nothing here is part of the public API.
#pragma once

#include <algorithm>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <deque>
#include <memory>
#include <string>
#include <string_view>

#include "../../common/bytes.hpp"
#include "stepzip/document.hpp"

namespace stepzip::io {

/// Coordinates in text files must lie in [-kCoordLimit, kCoordLimit]; then no
/// sum or difference of two coordinates, and no chain of fewer than 2^62
/// steps, can overflow an int64.
inline constexpr std::int64_t kCoordLimit = std::int64_t{1} << 62;

/// Longest run of spaces/tabs, or of leading zeros, accepted inside a chain
/// line; longest buffered point line. Keeps a block's memory bounded.
inline constexpr std::size_t kMaxFieldBytes = 4096;
inline constexpr std::size_t kMaxLineBytes = 65536;

/// A block is also cut once its layout holds this many bytes.
inline std::size_t layout_cap(std::size_t block_steps) {
    return block_steps < 256 ? 256 : block_steps;
}

// ---- layout byte code: the common byte layer (src/common/bytes.hpp) ---------

using wire::put_varint;
/// Reads a layout; every getter returns false at a truncated or malformed field.
using LayoutCursor = wire::Cursor;

// ---- number spelling --------------------------------------------------------

/// How a decimal integer was written, relative to its canonical spelling
/// (no '+', no leading zeros, '-' only on negative values).
struct Spelling {
    std::uint8_t sign = 0;    ///< 0 canonical, 1 explicit '+', 2 '-' on zero
    std::uint64_t zeros = 0;  ///< leading zeros beyond the canonical digits
    bool canonical() const { return sign == 0 && zeros == 0; }
};

/// Appends `v` spelled as `sp`.
void append_number(std::string& out, std::int64_t v, Spelling sp);
/// Appends the canonical decimal spelling of `v`.
void append_int(std::string& out, std::int64_t v);
// Writes the canonical decimal spelling of v at w; returns its end. The
// digits are made right to left in a scratch array and moved with one
// fixed-size copy of 20 bytes: w must have room for 21.
inline char* put_int(char* w, std::int64_t v) {
    static constexpr char kPairs[] =
        "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
        "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
        "8081828384858687888990919293949596979899";
    std::uint64_t m = v < 0 ? 0 - static_cast<std::uint64_t>(v) : static_cast<std::uint64_t>(v);
    if (v < 0) *w++ = '-';
    char tmp[40] = {};
    char* const e = tmp + 20;
    char* d = e;
    while (m >= 100) {  // two digits per division
        const auto r = static_cast<std::size_t>(m % 100);
        m /= 100;
        *--d = kPairs[2 * r + 1];
        *--d = kPairs[2 * r];
    }
    if (m >= 10) {
        *--d = kPairs[2 * m + 1];
        *--d = kPairs[2 * m];
    } else {
        *--d = static_cast<char>('0' + m);
    }
    std::memcpy(w, d, 20);  // constant size: a few moves, no call; d + 20 <= tmp + 40
    return w + (e - d);
}

/// Layout field: sign byte then zero count.
inline void put_spelling(std::string& out, Spelling sp) {
    out.push_back(static_cast<char>(sp.sign));
    put_varint(out, sp.zeros);
}
/// Reads a spelling field and checks that it fits `v`.
bool get_spelling(LayoutCursor& c, std::int64_t v, Spelling& sp);

/// Incremental decimal integer: sign then digits. Tracks the spelling.
struct NumberAccum {
    bool negative = false;
    bool plus = false;
    std::uint64_t digits = 0;     // digits seen
    std::uint64_t magnitude = 0;  // value of the digits, saturated past the limit
    bool too_big = false;
    void reset() { *this = NumberAccum{}; }
    void digit(unsigned d) {
        ++digits;
        if (too_big) return;
        constexpr auto kLimit = static_cast<std::uint64_t>(kCoordLimit);
        if (magnitude > kLimit / 10) {  // checked before multiplying: 10 * magnitude could wrap
            too_big = true;
            return;
        }
        magnitude = magnitude * 10 + d;
        if (magnitude > kLimit) too_big = true;
    }
    std::int64_t value() const {
        const auto m = static_cast<std::int64_t>(magnitude);
        return negative ? -m : m;
    }
    Spelling spelling() const;
};

/// "SOURCE:LINE:COLUMN: what".
std::string at(const std::string& source, std::uint64_t line, std::uint64_t column,
               std::string_view what);

/// True for bytes a text format never accepts anywhere: NUL and the other C0
/// controls except TAB, LF and CR, and DEL.
inline bool is_binary_byte(unsigned char c) {
    return (c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7F;
}

/// True when some byte of `bytes` is_binary_byte (16 bytes at a time where
/// SSE2 is there; document.cpp).
bool has_binary_byte(std::string_view bytes) noexcept;

/// "byte 0x07" or "'x'" for messages.
std::string describe_byte(unsigned char c);

// ---- per-format parser and renderer -------------------------------------------

class FormatParser {
public:
    virtual ~FormatParser() = default;
    virtual Result<void> feed(std::string_view data, bool last) = 0;
    /// 1-based line number the parser has reached (for detect_format).
    virtual std::uint64_t line() const { return 0; }
    std::deque<Block> ready;
};

class FormatRenderer {
public:
    virtual ~FormatRenderer() = default;
    virtual Result<void> write(const Block& block, std::string& out) = 0;
};

std::unique_ptr<FormatParser> make_freeman_parser(std::string source, std::size_t block_steps);
std::unique_ptr<FormatParser> make_points_parser(std::string source, std::size_t block_steps);
std::unique_ptr<FormatParser> make_steps_parser(std::string source, std::size_t block_steps);
std::unique_ptr<FormatRenderer> make_freeman_renderer();
std::unique_ptr<FormatRenderer> make_points_renderer();
std::unique_ptr<FormatRenderer> make_steps_renderer();
std::unique_ptr<FormatParser> make_timed_parser(std::string source, std::size_t block_steps);
std::unique_ptr<FormatRenderer> make_timed_renderer();

// ---- STEP/DIR logs (steps_format.cpp, timed_steps.cpp) -------------------------

inline constexpr std::uint8_t kStepBits = 0x55;  // STEP bit of axis i: bit 2i
inline constexpr std::uint8_t kDirBits = 0xAA;   // DIR bit of axis i: bit 2i + 1

/// A tick byte read against the DIR level of the tick before it.
struct Tick {
    std::uint8_t stepping;     // STEP bits
    std::uint8_t moving_dirs;  // the DIR bits' places of the stepping axes
    std::uint8_t dirs;         // DIR bits
    std::uint8_t flip;         // DIR bits that changed on axes that do not step
};
inline Tick read_tick(std::uint8_t b, std::uint8_t level) {
    Tick t;
    t.stepping = b & kStepBits;
    t.moving_dirs = static_cast<std::uint8_t>(t.stepping << 1);
    t.dirs = b & kDirBits;
    t.flip = static_cast<std::uint8_t>((t.dirs ^ level) & ~t.moving_dirs & kDirBits);
    return t;
}

/// The tick byte of `s` (STEP bits and the DIR bits of the stepping axes)
/// after DIR level `level`, with the idle axes' DIR bits in `flip` changed.
inline std::uint8_t tick_byte(std::uint8_t s, std::uint8_t level, std::uint8_t flip) {
    const auto moving_dirs = static_cast<std::uint8_t>((s & kStepBits) << 1);
    return static_cast<std::uint8_t>(s | ((level ^ flip) & ~moving_dirs & kDirBits));
}

/// Axes of a log whose axes with a step so far have STEP bits `seen`: at
/// least two.
inline int log_axes(std::uint8_t seen) {
    int a = 2;
    for (int i = 0; i < 4; ++i)
        if (seen & (1u << (2 * i))) a = std::max(a, i + 1);
    return a;
}

/// DIR bits of a tick byte (1, 3, 5, 7) <-> a 4-bit axis mask.
inline std::uint8_t dir_to_mask(std::uint8_t d) {
    return static_cast<std::uint8_t>(((d >> 1) & 1) | ((d >> 2) & 2) | ((d >> 3) & 4) | ((d >> 4) & 8));
}
inline std::uint8_t mask_to_dir(std::uint8_t m) {
    return static_cast<std::uint8_t>(((m & 1) << 1) | ((m & 2) << 2) | ((m & 4) << 3) | ((m & 8) << 4));
}

/// Error for a layout that does not fit its block.
inline Error corrupt(std::string_view format, std::string_view what) {
    return make_error(Errc::corrupt, std::string(format) + " layout: " + std::string(what));
}

/// The steps of a log block (one chain, starting at the origin unless it
/// continues), or the `corrupt` error naming `format`.
inline Result<const std::vector<Step>*> log_block_steps(const Block& b, std::string_view format) {
    static const std::vector<Step> kNone;
    if (b.chains.size() > 1) return corrupt(format, "a log block holds one chain");
    if (!b.continues && !b.chains.empty() && b.chains[0].start != Point{})
        return corrupt(format, "the chain does not start at the origin");
    return b.chains.empty() ? &kNone : &b.chains[0].steps;
}

}  // namespace stepzip::io
