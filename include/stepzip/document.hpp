// stepzip — chain files (freeman, points, steps) read and written byte-exactly.
//
// A BlockReader parses input bytes, in pieces of any size, into Blocks: the
// chains of a bounded stretch of the input plus a "layout" that records
// everything that is not chain steps (comments, blank lines, spacing, line
// endings, idle ticks ...). A BlockWriter turns the same Blocks back into the
// identical bytes. Memory is bounded by the block size, not the input size:
// a chain longer than a block is split across blocks.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stepzip/chain.hpp"
#include "stepzip/error.hpp"

namespace stepzip {

/// Chain file formats (SPEC section 5). The numeric values are stored in .stz files.
enum class InputFormat : std::uint8_t {
    freeman = 0,  ///< one chain per line: "X0 Y0 CODES", '#' comments
    points = 1,   ///< one point per line ("x y" or "x,y", N columns), blank line ends a chain
    steps = 2,    ///< binary STEP/DIR log, one byte per tick, up to 4 axes
    timed = 3,    ///< the same log read as one chain in (time, axes): a tick is a step
};

/// The format's command-line name ("freeman", "points", "steps", "timed"); "?" for a
/// value outside the enum. Thread-safe.
std::string_view format_name(InputFormat f) noexcept;
/// The format with that name, or nullopt. Thread-safe.
std::optional<InputFormat> parse_format(std::string_view name) noexcept;

/// Guesses the format from the first bytes of an input (up to a few KiB).
/// Returns nullopt when no format fits. Thread-safe. Does not promise that
/// the whole input parses in the guessed format.
std::optional<InputFormat> detect_format(std::string_view head) noexcept;

/// Default number of steps per block.
inline constexpr std::size_t kDefaultBlockSteps = std::size_t{1} << 20;
/// Default number of ticks per block of a timed log (a tick is a step of
/// its time axis): a timed block's adaptive contexts start afresh with each
/// block, and on the timed streams of docs/benchmarks.md over 2^20 ticks
/// blocks of 2^22 came out 1.3-3.8 % smaller.
inline constexpr std::size_t kDefaultTimedBlockTicks = std::size_t{1} << 22;

/// A bounded stretch of an input file.
struct Block {
    int axes = 2;               ///< axis count of every chain in the block
    std::vector<Chain> chains;  ///< chains, or pieces of chains, in input order
    /// chains[0] continues the last chain of the previous block: its start
    /// equals that chain's end point. It holds at least one step unless the
    /// previous block was cut for the size of its layout (docs/formats.md).
    bool continues = false;
    /// The last chain goes on in the next block.
    bool open = false;
    /// Format-private record of all non-step bytes; opaque to the container.
    /// An empty layout means the canonical rendering (for writing only).
    /// Each layout is self-contained: a block renders without the others.
    std::string layout;
};

/// Incremental parser: input bytes in, Blocks out. Not thread-safe (one
/// object per stream); different objects are independent.
class BlockReader {
public:
    /// `source` names the input in error messages ("plot.fc", "<stdin>").
    BlockReader(InputFormat format, std::string source,
                std::size_t block_steps = kDefaultBlockSteps);
    ~BlockReader();
    BlockReader(BlockReader&&) noexcept;
    BlockReader& operator=(BlockReader&&) noexcept;

    /// Feeds the next piece of input; `last` marks the end of the input.
    /// Block boundaries depend only on the input and block_steps, not on how
    /// the input is cut into pieces.
    /// Errors: Errc::syntax / Errc::not_a_step / Errc::limit / Errc::overflow
    /// (a coordinate beyond +-2^62) with a message "SOURCE:LINE:COLUMN: ..."
    /// (text formats; the steps format accepts every byte);
    /// Errc::invalid_argument when fed after `last`. After an error the
    /// reader must not be used again (it repeats the error).
    Result<void> feed(std::string_view data, bool last);

    /// Moves the next finished block into `out`; false when none is ready.
    bool next(Block& out);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// Renderer: Blocks in, the exact input bytes out. Not thread-safe.
class BlockWriter {
public:
    explicit BlockWriter(InputFormat format);
    ~BlockWriter();
    BlockWriter(BlockWriter&&) noexcept;
    BlockWriter& operator=(BlockWriter&&) noexcept;

    /// Appends the bytes of `block` to `out`.
    /// Errors: Errc::corrupt when the layout does not fit the chains.
    Result<void> write(const Block& block, std::string& out);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// Convenience: the canonical text (or bytes) of whole chains in `format`.
/// Thread-safe.
/// Errors: Errc::invalid_argument when a chain does not fit the format
/// (e.g. freeman needs two axes, steps at most four axes and a start at 0).
Result<std::string> write_chains(InputFormat format, const std::vector<Chain>& chains);

/// Convenience: parses a whole input held in memory into chains (pieces of
/// a chain split across blocks are joined). Errors: as BlockReader::feed().
/// Thread-safe. Memory: the whole input's chains (use BlockReader to bound it).
Result<std::vector<Chain>> read_chains(InputFormat format, std::string_view data,
                                       std::string source = "<input>");

}  // namespace stepzip
