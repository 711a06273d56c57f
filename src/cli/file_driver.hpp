// stepzip command line: the file handling compress and decompress share, as
// zstd does it — which output each input goes to, one output for all inputs
// with -c or -o, --rm, the input's mode/owner/times carried to the output,
// console stdin refused, progress and the -v summary line.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "stepzip/container.hpp"
#include "stz_stream.hpp"

namespace stepzip::cli {

struct FileJobOptions {
    std::string command;               ///< "compress" / "decompress", for messages
    std::vector<std::string> inputs;   ///< "-" = standard input; none = "-"
    std::string output;                ///< -o (empty: none)
    bool to_stdout = false;            ///< -c
    bool force = false, remove = false, quiet = false, verbose = false, progress = true;
    bool recursive = false;            ///< -r: directories stand for the files under them
    bool binary_output = false;        ///< the output is a frame (compress): refuse a terminal
                                       ///< as output without -f; the ratio is output / input
};

/// Output name of one input when neither -c nor -o is given ("x" ->
/// "x.stz"), or an error (Errc::invalid_argument) that skips the input.
using TargetFn = std::function<Result<std::string>(const std::string& input)>;
/// Which files under a directory -r takes.
using WantedFn = std::function<bool(const std::string& path)>;
/// Turns one input into output bytes; returns the text after the sizes on
/// the -v summary line (may be empty). `tick` reports progress.
using TransformFn = std::function<Result<std::string>(InputStream& in, const ReadFn& read,
                                                      const WriteFn& write,
                                                      const ProgressFn& tick)>;

/// Runs `transform` over every input as zstd would: FILE -> target(FILE),
/// standard input -> standard output; with -c every input goes to standard
/// output and with -o to OUT, one after another (several inputs into one -o
/// file need -f, as zstd asks before it concatenates). --rm removes an input
/// only after its own output is complete, never with -c and never when
/// several inputs share one output. An output that is one of the inputs
/// (same file) is refused. Returns the exit code (0, 1 or 2).
int run_file_jobs(const FileJobOptions& options, const TargetFn& target, const WantedFn& wanted,
                  const TransformFn& transform);

}  // namespace stepzip::cli
