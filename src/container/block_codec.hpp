// The .stz frame constants and the block codec shared by the compressor and
// the decompressor (docs/FORMAT.md). Internal to src/container.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "stepzip/container.hpp"
#include "stepzip/document.hpp"
#include "stepzip/error.hpp"
#include "stepzip/profile.hpp"
#include "stepzip/segment.hpp"

namespace stepzip::stz {

inline constexpr unsigned char kMagic[4] = {0xB7, 0x53, 0x54, 0x5A};  // "\xB7STZ"
/// Frame header sizes: version 1 (10 bytes) and version 2 (8 bytes).
inline constexpr std::size_t kFrameHeaderSizeV1 = 10;
inline constexpr std::size_t kFrameHeaderSize = 8;
/// Version 1 block header (type, flags, u32 sizes); version 2 packs type and
/// flags in one byte and writes the sizes as varints.
inline constexpr std::size_t kBlockHeaderSizeV1 = 10;
inline constexpr std::size_t kBlockChecksumSize = 4;
/// Version 1, after the end mark: decoded size, three statistics, trailer
/// check, content XXH64.
inline constexpr std::size_t kTrailerSizeV1 = 8 + 3 * 8 + 4 + 8;
/// Version 2 trailer metadata: at most this many bytes (docs/FORMAT.md 1.7).
inline constexpr std::uint64_t kMaxMetadata = 4096;
/// Metadata record tags.
inline constexpr std::uint64_t kMetaPatentStats = 1;

enum BlockType : unsigned { kEnd = 0, kChains = 1, kRaw = 2, kSegmentModel = 3, kStepModel = 4, kTable = 5, kMixedModel = 6,
                        kExtended = 7 };
/// Block type 7 (the extended block): the payload's first byte is a subtype.
/// Block type 6 (mixed predictions): the payload's first byte, the model
/// (bit 0) and the flag kMixedCurvature (bit 1: two more hashed models,
/// docs/FORMAT.md 1.11.1); or kMixedStepCm, the context-mixing step model
/// (docs/FORMAT.md 1.11.2); or kMixedStepCmLight, its light version
/// (docs/FORMAT.md 1.11.3); or kMixedStepCmDss, it with the longest digital
/// straight segment as context (docs/FORMAT.md 1.11.4); or
/// kMixedStepCmLightSmall, the light version with at most 2^16 rows
/// (docs/FORMAT.md 1.11.3).
inline constexpr unsigned kMixedSegment = 0, kMixedStep = 1, kMixedCurvature = 2, kMixedStepCm = 4,
                          kMixedStepCmLight = 5, kMixedStepCmDss = 6, kMixedStepCmLightSmall = 7;
/// A type 6 payload's first byte names a context-mixing step model.
inline constexpr bool is_cm_step_model(unsigned byte) {
    return byte == kMixedStepCm || byte == kMixedStepCmLight || byte == kMixedStepCmDss ||
           byte == kMixedStepCmLightSmall;
}
/// The model (kSegmentModel or kStepModel) a type 6 payload's first byte
/// names, or kEnd for a byte that names none.
inline constexpr unsigned mixed_model_of(unsigned byte) {
    if (is_cm_step_model(byte)) return kStepModel;
    return byte > (kMixedStep | kMixedCurvature) ? kEnd : (byte & kMixedStep) ? kStepModel : kSegmentModel;
}
/// Block flags (version 1: the flags byte; version 2: bits 3.. of the block byte).
/// kFlagWindow (version 2 only): the block's models start from the window.
inline constexpr unsigned kFlagContinues = 1u, kFlagOpen = 2u, kFlagWindow = 4u;

/// Low 32 bits of XXH64(data, seed 0).
std::uint32_t check32(std::string_view data);
std::uint64_t hash64(std::string_view data);

/// Frame header fields.
struct FrameHeader {
    int version = kFormatVersion;
    Profile profile = Profile::eval8;
    InputFormat format = InputFormat::freeman;
    int axes = 2;
    SegmenterKind segmenter = SegmenterKind::greedy;
    int window_log = 0;  ///< version 2: window of 2^window_log steps + chains; 0: none
    std::size_t size() const { return version == 1 ? kFrameHeaderSizeV1 : kFrameHeaderSize; }
    std::uint64_t window() const { return window_log == 0 ? 0 : std::uint64_t{1} << window_log; }
};
/// A version-2 frame header.
std::string write_frame_header(const FrameHeader& h);
/// Parses a frame header of either version; `bytes` holds what could be read
/// (at most 10 bytes; fewer than the version's size: truncated).
Result<FrameHeader> parse_frame_header(std::string_view bytes, std::string_view source);

/// A version-2 block header: the block byte and the varint sizes.
std::string block_header(unsigned type, unsigned flags, std::uint64_t csize, std::uint64_t dsize);

/// Where a block record's payload lies (`rec` is one record this library
/// made: version 2).
struct RecordView {
    unsigned type = 0, flags = 0;
    std::string_view payload;
    std::uint64_t dsize = 0;
};
RecordView view_record(std::string_view rec);

/// Per-block counts gathered while decoding a chain payload.
struct BlockCounts {
    std::uint64_t chains = 0, segments = 0, steps = 0;
};

/// Serializes the segments of a block's chains into an uncompressed chain
/// payload (docs/FORMAT.md "Record block payload"). `segs[i]` are chain i's
/// segments. (Other layouts, for the measurements of docs/FORMAT.md: the
/// bench hook, bench_hooks.hpp.)
std::string write_chain_payload(const Block& block, Profile p,
                                const std::vector<std::vector<Segment>>& segs);

/// Parses an uncompressed chain payload into `out` (chains, layout); when
/// `expand` is false only counts are gathered. `where` is prefixed to error
/// messages ("SOURCE: block K payload"). Errors: Errc::corrupt, truncated,
/// limit, each naming the payload byte offset.
Result<void> read_chain_payload(std::string_view payload, Profile p, int axes, bool expand,
                                Block& out, BlockCounts& counts, const std::string& where);

/// One whole version-2 block record: header, zstd payload, checksum.
std::string make_block_record(unsigned type, unsigned flags, std::string_view uncompressed,
                              int level);

/// One whole version-2 block record whose payload is stored as is (modeled blocks:
/// decoded size = compressed size).
std::string make_stored_record(unsigned type, unsigned flags, std::string_view payload);

/// Decompresses a zstd payload whose decoded size is declared as `dsize`
/// (already checked against the limits). Errors: Errc::corrupt.
Result<std::string> unzstd(std::string_view compressed, std::uint32_t dsize,
                           const std::string& where);

}  // namespace stepzip::stz
