// stepzip command line: helpers shared by the subcommands — reading an input
// (file or stdin), writing an output atomically (temporary file + rename),
// the one-line error report, and a terminal progress line.
//
// None of these are thread-safe; the command line is single-threaded where it
// calls them.
#pragma once

#include <sys/stat.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stepzip/error.hpp"

namespace stepzip::cli {

/// True when `path` names standard input or output ("-" or empty).
bool is_dash(std::string_view path) noexcept;

/// The name of an input in messages: "<stdin>" for "-" / empty, else `path`.
std::string input_name(std::string_view path);

/// Reads a whole input into memory: the file `path`, or standard input for
/// "-" / empty. Errors: Errc::io "PATH: <reason>".
Result<std::string> read_input(const std::string& path);

/// True when the stream is a terminal.
bool is_terminal(std::FILE* stream) noexcept;

/// The error for reading chains or frames typed at a keyboard, as zstd
/// refuses them: when `inputs` name standard input and it is a terminal,
/// unless `force`. Errc::io "stdin is a console, aborting (...)".
std::optional<Error> console_stdin_refused(const std::vector<std::string>& inputs, bool force);

/// The inputs with every directory replaced by the regular files under it
/// (recursively, sorted by name) for which `wanted(path)` is true; files
/// named directly are kept as they are. For -r. Errors: Errc::io naming the
/// directory that cannot be read.
Result<std::vector<std::string>> expand_directories(const std::vector<std::string>& inputs,
                                                    const std::function<bool(const std::string&)>& wanted);

/// True when `path` ends with `suffix` and has something before it.
bool has_suffix(std::string_view path, std::string_view suffix) noexcept;

/// A byte count as zstd prints it: "512 B", "1.50 KiB", "12.3 MiB".
std::string format_size(std::uint64_t bytes);

/// Prints "stepzip: <message>" on stderr; returns 1 (the error exit code).
int report(const Error& error);
/// Prints "stepzip: <message>" and a hint to use the --help of the command
/// that <message> starts with ("compress: ...") on stderr; returns 2 (the
/// usage-error exit code).
int usage_error(std::string_view message);
/// Prints "stepzip: <message>" on stderr (a note or warning; no exit code).
void note(std::string_view message);

/// An output written in one piece: to standard output, or to a temporary file
/// next to the target that commit() flushes, syncs and renames over the target.
/// If commit() is never reached (an error, an early return) the destructor
/// removes the temporary file, so a failure never leaves a partial output and
/// never touches an existing file. SIGINT, SIGTERM and SIGHUP (unless they
/// were ignored when the program started) remove every open temporary file
/// before the program dies of the signal. A target that exists and is not a
/// regular file (/dev/null, a FIFO, a terminal) is written directly, never
/// replaced.
class OutputFile {
public:
    OutputFile() = default;
    ~OutputFile();
    OutputFile(OutputFile&& other) noexcept;
    OutputFile& operator=(OutputFile&& other) noexcept;
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;

    /// Opens the output `path` ("-" / empty: standard output). An existing
    /// regular file is refused unless `force`. Errors: Errc::io
    /// "PATH: already exists (use -f to overwrite)" or "PATH: <reason>".
    static Result<OutputFile> open(const std::string& path, bool force);

    /// Gives the output, when commit() renames it into place, the mode, owner,
    /// group and access/modification times of `source` (as zstd does): the
    /// owner only where the system allows it, the rest always. No effect on
    /// standard output or a device written in place.
    void keep_attributes_of(const struct stat& source) { attributes_ = source; }

    /// Appends bytes. Errors: Errc::io naming the target.
    Result<void> write(std::string_view data);
    /// Finishes the output: flush, fsync and rename for a file; flush for
    /// standard output. Errors: Errc::io naming the target.
    Result<void> commit();

    /// True when the output is standard output.
    bool is_stdout() const noexcept { return to_stdout_; }
    /// The target's name for messages ("<stdout>" or the path).
    const std::string& name() const noexcept { return target_; }

private:
    void discard() noexcept;

    std::string target_;
    std::string temp_;
    std::FILE* file_ = nullptr;
    int signal_slot_ = -1;  ///< registration of temp_ for the signal handler
    bool to_stdout_ = false;
    bool direct_ = false;   ///< an existing non-regular target, written in place
    bool done_ = false;
    std::optional<struct stat> attributes_;
};

/// A progress line on stderr, as zstd's: "label: 42% 1.20 MiB => 310 KiB
/// (25.23%)" (the percentage only when the input size is known), shown only
/// when enabled and stderr is a terminal, updated at most a few times a
/// second, erased by finish() or the destructor.
class Progress {
public:
    /// `compressing`: the output is the frame (else the input is), for the
    /// ratio frame / original.
    Progress(std::string label, std::uint64_t total, bool enabled, bool compressing);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    /// Reports `read` of `total` input bytes consumed and `written` output bytes.
    void update(std::uint64_t read, std::uint64_t written);
    /// Erases the line (idempotent).
    void finish();

private:
    std::string label_;
    std::uint64_t total_;
    bool active_;
    bool compressing_;
    bool shown_ = false;
    std::chrono::steady_clock::time_point last_{};
};

}  // namespace stepzip::cli
