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
inline constexpr std::size_t kFrameHeaderSize = 10;
inline constexpr std::size_t kBlockHeaderSize = 10;
inline constexpr std::size_t kBlockChecksumSize = 4;
/// After the end mark: decoded size, three statistics, trailer check, content XXH64.
inline constexpr std::size_t kTrailerSize = 8 + 3 * 8 + 4 + 8;

enum BlockType : unsigned { kEnd = 0, kChains = 1, kRaw = 2, kSegmentModel = 3, kStepModel = 4 };
inline constexpr unsigned kFlagContinues = 1u, kFlagOpen = 2u;

/// Low 32 bits of XXH64(data, seed 0).
std::uint32_t check32(std::string_view data);
std::uint64_t hash64(std::string_view data);

/// Frame header fields.
struct FrameHeader {
    Profile profile = Profile::eval8;
    InputFormat format = InputFormat::freeman;
    int axes = 2;
    SegmenterKind segmenter = SegmenterKind::greedy;
};
std::string write_frame_header(const FrameHeader& h);
/// Parses the 10 header bytes (fewer: truncated).
Result<FrameHeader> parse_frame_header(std::string_view bytes, std::string_view source);

/// Per-block counts gathered while decoding a chain payload.
struct BlockCounts {
    std::uint64_t chains = 0, segments = 0, steps = 0;
};

/// Serializes the segments of a block's chains into an uncompressed chain
/// payload (docs/FORMAT.md "Chain payload"). `segs[i]` are chain i's
/// segments, `ends[i]` their counts.
/// Serialization variants measured for docs/FORMAT.md ("Rationale"). Only
/// the default is the format: the decoder reads nothing else.
struct PayloadVariant {
    bool interleaved = true;      ///< one record per segment (else one stream per field)
    bool start_from_end = true;   ///< chain start relative to the previous chain's end (else start)
    bool octant_delta = true;     ///< 2D direction as the octant turn from the previous segment
};
std::string write_chain_payload(const Block& block, Profile p,
                                const std::vector<std::vector<Segment>>& segs,
                                const PayloadVariant& variant = {});

/// Parses an uncompressed chain payload into `out` (chains, layout); when
/// `expand` is false only counts are gathered. `where` is prefixed to error
/// messages ("SOURCE: block K payload"). Errors: Errc::corrupt, truncated,
/// limit, each naming the payload byte offset.
Result<void> read_chain_payload(std::string_view payload, Profile p, int axes, bool expand,
                                Block& out, BlockCounts& counts, const std::string& where);

/// One whole block record: header, zstd payload, checksum.
std::string make_block_record(unsigned type, unsigned flags, std::string_view uncompressed,
                              int level);

/// One whole block record whose payload is stored as is (modeled blocks:
/// decoded size = compressed size).
std::string make_stored_record(unsigned type, unsigned flags, std::string_view payload);

/// Decompresses a zstd payload whose decoded size is declared as `dsize`
/// (already checked against the limits). Errors: Errc::corrupt.
Result<std::string> unzstd(std::string_view compressed, std::uint32_t dsize,
                           const std::string& where);

}  // namespace stepzip::stz
