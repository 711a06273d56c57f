// stepzip — the .stz container: chain files in, verified compressed frames out.
//
// The byte layout is specified in docs/FORMAT.md (format version
// kFormatVersion, independent of the library version). Compression parses the
// input into blocks (document.hpp), cuts each chain into exact segments
// (segmenter.hpp), codes each block by the models that win (a block may start
// from the window of earlier blocks the frame declares), and proves the
// round trip of every block before writing it. Decompression reverses the
// stages and checks the XXH64 of the decoded bytes; frames back to back
// decode as one stream.
//
// Memory is bounded by the block size times the number of threads plus the
// window (at most 2^kMaxWindowLog steps + chains), not by the input size:
// both directions stream one block at a time.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "stepzip/document.hpp"
#include "stepzip/error.hpp"
#include "stepzip/interpolate/arc.hpp"
#include "stepzip/profile.hpp"
#include "stepzip/segmenter.hpp"

namespace stepzip {

/// Version of the .stz byte format written by this library (docs/FORMAT.md).
inline constexpr int kFormatVersion = 2;
/// Oldest format version the decoder still reads.
inline constexpr int kOldestFormatVersion = 1;

/// Decoder limits (docs/FORMAT.md "Limits"). A frame exceeding any of them is
/// rejected with Errc::limit before anything of that size is allocated.
inline constexpr std::uint32_t kMaxBlockPayload = 64u << 20;     ///< compressed or decoded payload bytes
inline constexpr std::uint32_t kMaxBlockBytes = 256u << 20;      ///< decoded bytes of a raw block
inline constexpr std::uint64_t kMaxBlockSteps = std::uint64_t{1} << 24;  ///< steps (and segments) per block
inline constexpr std::uint64_t kMaxBlockChains = std::uint64_t{1} << 20; ///< chains per block
/// Largest window a frame may declare: 2^kMaxWindowLog steps + chains of
/// earlier blocks (docs/FORMAT.md "Window"); a larger one is Errc::limit.
inline constexpr int kMaxWindowLog = 23;
/// A window covers at most this many earlier blocks (docs/FORMAT.md
/// "Window"): rebuilding it costs a block at most this many blocks' work.
inline constexpr std::size_t kMaxWindowBlocks = 8;

/// Segmenter implied by a level when none is named: greedy below
/// kOptimalLevel, optimal from it on.
inline constexpr int kOptimalLevel = 19;

/// Options of compress_stream(). Defaults match `stepzip compress`.
struct CompressOptions {
    std::optional<Profile> profile;          ///< nullopt: auto (smallest first block)
    std::optional<SegmenterKind> segmenter;  ///< nullopt: implied by `level`
    int level = 3;                           ///< 1..19, also the zstd level
    unsigned threads = 1;                    ///< 0: all cores; output does not depend on it
    std::optional<InputFormat> format;       ///< nullopt: detect from the first bytes
    /// Steps per block (1..kMaxBlockSteps); nullopt: kDefaultBlockSteps,
    /// or kDefaultTimedBlockTicks ticks for a timed log.
    std::optional<std::size_t> block_steps;
    std::string source = "<input>";          ///< input name for error messages
    /// Carry a block as zstd of its bytes when that is smaller than its
    /// segments (docs/FORMAT.md "Raw blocks"); false forces chain blocks
    /// wherever the profile can represent the chains.
    bool allow_raw = true;
    /// Window across blocks: 2^window_log steps + chains of earlier blocks
    /// (0: blocks independent; at most kMaxWindowLog); nullopt: set by the
    /// level, and kMaxWindowLog for a timed input (docs/FORMAT.md "Encoder
    /// behaviour").
    std::optional<int> window_log;
    /// Two-axis chains: also cut each block into arcs drawn by this method
    /// and default-phase lines, and keep that table block where it is
    /// smaller (docs/FORMAT.md 1.10.1); nullopt: lines only.
    std::optional<ArcMethod> arc_method;
};

/// What a frame holds; filled by compress_stream(), decompress_stream() and
/// inspect_stream().
struct FrameInfo {
    int format_version = kFormatVersion; ///< of the first frame
    std::uint64_t frames = 1;           ///< frames read (concatenated frames decode as one stream)
    std::uint64_t window = 0;           ///< window of the first frame, in steps + chains (0: none)
    Profile profile = Profile::eval8;
    InputFormat format = InputFormat::freeman;
    SegmenterKind segmenter = SegmenterKind::greedy;
    int axes = 2;
    std::uint64_t blocks = 0;           ///< data blocks (both kinds)
    std::uint64_t raw_blocks = 0;       ///< blocks carried as zstd of their bytes
    std::uint64_t segment_model_blocks = 0;  ///< blocks coded by the segment model
    std::uint64_t step_model_blocks = 0;     ///< blocks coded by the step model
    std::uint64_t table_blocks = 0;          ///< table blocks (block type 5 and type 7 subtype 4, the fast levels)
    std::uint64_t timed_blocks = 0;          ///< timed and tick blocks (block type 7 subtypes 0 and 2, timed frames)
    std::uint64_t chains = 0;           ///< chains in chain blocks (a chain split across blocks counts once)
    std::uint64_t steps = 0;            ///< steps in chain blocks
    std::uint64_t segments = 0;         ///< segments in chain blocks (none in step-model blocks)
    std::uint64_t decoded_bytes = 0;    ///< size of the original input
    std::uint64_t compressed_bytes = 0; ///< size of the frame
    std::uint64_t checksum = 0;         ///< XXH64 (seed 0) of the decoded bytes
    SegmentStats stats;                 ///< patent segmenter statistics (zero otherwise)
};

/// Pulls up to `cap` bytes into `buf`; returns the count, 0 at the end of
/// the input. Errors: Errc::io with a message naming the source.
using ReadFn = std::function<Result<std::size_t>(char* buf, std::size_t cap)>;
/// Pushes bytes to the output. Errors: Errc::io with a message.
using WriteFn = std::function<Result<void>(std::string_view bytes)>;
/// Progress: input bytes consumed (compress) or frame bytes read (decompress).
using ProgressFn = std::function<void(std::uint64_t bytes)>;

/// Compresses a chain file into one .stz frame, written through `out` block
/// by block. Every block is decoded again (forward interpolation) and
/// compared with the input bytes before it is written.
/// Returns the frame's description.
/// Errors: the parser's Errc::syntax / not_a_step / limit ("SOURCE:LINE:COL:
/// ..." or "SOURCE: byte N: ..."), Errc::unsupported when the format cannot be
/// detected, Errc::connectivity / invalid_argument when an explicitly named
/// profile cannot represent the chains, Errc::invalid_argument for bad
/// options, Errc::io from `in`/`out`, Errc::mismatch when a round-trip proof
/// fails (an internal error; nothing more is written).
/// On error, bytes already passed to `out` are an incomplete frame: write to
/// a temporary file and discard it.
/// Thread-safety: independent calls may run concurrently; `in`, `out` and
/// `progress` are called from the calling thread only.
/// Does not promise: the same compressed bytes across library versions (only
/// the round trip is guaranteed), nor across block sizes; it does promise
/// identical bytes for any `threads` value.
Result<FrameInfo> compress_stream(const ReadFn& in, const WriteFn& out, const CompressOptions& opt,
                                  const ProgressFn& progress = {});

/// Decodes a .stz stream from `in`: one frame, or several frames back to
/// back (decoded as one stream, as zstd and gzip do), writing the original
/// bytes through `out` block by block, and checks each frame's XXH64.
/// Reads every format version from kOldestFormatVersion to kFormatVersion.
/// Errors (messages name `source` and the byte offset in the frame):
/// Errc::bad_magic, bad_version, reserved_bits, truncated, corrupt, limit,
/// checksum, io. On error, bytes already passed to `out` must be discarded.
/// Thread-safe across calls. Does not promise to detect every corruption
/// before output starts; it does promise never to report success on a frame
/// whose decoded bytes differ from what was compressed (up to XXH64
/// collisions).
Result<FrameInfo> decompress_stream(const ReadFn& in, const WriteFn& out,
                                    std::string_view source = "<input>",
                                    const ProgressFn& progress = {});

/// Reads the structure and counts of the frames of a stream (profile, chains, steps, segments,
/// patent statistics) without rendering it; block checksums are checked but
/// the content XXH64 is not (use decompress_stream for that).
/// Errors: as decompress_stream().
Result<FrameInfo> inspect_stream(const ReadFn& in, std::string_view source = "<input>");

/// True for the errors a decoder reports for a damaged or hostile frame
/// (docs/FORMAT.md): bad_magic, bad_version, reserved_bits, truncated,
/// corrupt, limit, checksum. Errors of the reading or writing ends (io) and
/// of the caller are not among them.
constexpr bool is_frame_error(Errc e) noexcept {
    switch (e) {
        case Errc::bad_magic:
        case Errc::bad_version:
        case Errc::corrupt:
        case Errc::truncated:
        case Errc::reserved_bits:
        case Errc::checksum:
        case Errc::limit: return true;
        default: return false;
    }
}

/// In-memory conveniences over the streaming calls.
Result<std::string> compress(std::string_view input, const CompressOptions& opt = {});
Result<std::string> decompress(std::string_view frame, std::string_view source = "<input>");

}  // namespace stepzip
