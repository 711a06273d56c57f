// The context-mixing raw block (docs/FORMAT.md "CM raw block"): block type 7,
// subtype 3. The payload of a raw block (varint nchains, varint nsteps, the
// block's input bytes) coded byte by byte, bit by bit, by a byte-oriented
// context-mixing model in the style of lpaq1: hashed contexts of the
// preceding bytes (orders 1-6), a word, column and field context of
// text lines, a match model, two mixers and adaptive probability maps.
// Where zstd's raw block is what a text-like input (HP-GL, G-code) falls
// back to, this one is about half its size. Internal to src/container.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "block_codec.hpp"

namespace stepzip::stz {

/// Subtype 3 of block type 7: the CM raw block.
inline constexpr unsigned kRawCmSubtype = 3;
/// The coding byte (payload byte 1) of the model below; others: corrupt.
inline constexpr unsigned kRawCmCoding = 0;
/// The lowest level whose encoder tries it where it tries a raw block.
inline constexpr int kRawCmLevel = 3;

/// Payload of a CM raw block (subtype and coding bytes first) coding `raw`,
/// a raw block's payload before zstd; empty when `raw` is over the raw
/// block's limit (kMaxBlockBytes + 20). `half`, when given, receives the
/// coded size after the first half of `raw` (for estimates: the rate of
/// the second half is the model's once it has learned the first).
std::string write_raw_cm_block(std::string_view raw, std::size_t* half = nullptr);

/// The raw block payload a CM raw block payload decodes to. Errors:
/// Errc::corrupt and Errc::limit naming the payload byte after `where`.
Result<std::string> read_raw_cm_block(std::string_view payload, const std::string& where);

}  // namespace stepzip::stz
