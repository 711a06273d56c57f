// stepzip command line: the file handling compress and decompress share (see
// file_driver.hpp).
#include "file_driver.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace stepzip::cli {

namespace {

// Byte counts of one input's run, for the progress line and the summary.
struct Counts {
    std::uint64_t read = 0, written = 0;
};

// Runs `transform` on one opened input into `out`; prints the -v summary.
int run_one(const FileJobOptions& o, InputStream& in, OutputFile& out, const TransformFn& transform) {
    Counts n;
    Progress progress(o.command + " " + in.name(), in.size(), o.progress && !o.quiet, o.binary_output);
    const ReadFn read = [&](char* buf, std::size_t cap) -> Result<std::size_t> {
        auto got = in.read(buf, cap);
        if (got) n.read += *got;
        return got;
    };
    const WriteFn write = [&](std::string_view bytes) -> Result<void> {
        n.written += bytes.size();
        return out.write(bytes);
    };
    const ProgressFn tick = [&](std::uint64_t) { progress.update(n.read, n.written); };
    auto detail = transform(in, read, write, tick);
    progress.finish();
    if (!detail) return report(detail.error());
    if (o.verbose) {
        // The ratio is always frame size / original size, as zstd's.
        const std::uint64_t frame = o.binary_output ? n.written : n.read;
        const std::uint64_t original = o.binary_output ? n.read : n.written;
        const double ratio = original ? 100.0 * static_cast<double>(frame) / original : 0.0;
        std::fprintf(stderr, "%s : %.2f%% (%s => %s, %s)%s%s\n", in.name().c_str(), ratio,
                     format_size(n.read).c_str(), format_size(n.written).c_str(),
                     out.name().c_str(), detail->empty() ? "" : " ", detail->c_str());
    }
    return 0;
}

// An output that is the input file itself (the same name, or a hard link)
// would replace the input before it is read to the end: refused, as zstd
// refuses it.
std::optional<Error> overwrites_input(const std::string& input, const std::string& target) {
    if (is_dash(input) || is_dash(target)) return std::nullopt;
    struct stat in {}, out {};
    if (::stat(input.c_str(), &in) != 0 || ::stat(target.c_str(), &out) != 0) return std::nullopt;
    if (in.st_dev != out.st_dev || in.st_ino != out.st_ino) return std::nullopt;
    return make_error(Errc::invalid_argument,
                      input + ": refusing to write the output over the input file");
}

int remove_input(const std::string& input) {
    if (::unlink(input.c_str()) != 0)
        return report(make_error(Errc::io, input + ": cannot remove: " + std::strerror(errno)));
    return 0;
}

Result<OutputFile> open_output(const FileJobOptions& o, const std::string& target,
                               const std::string& first_input) {
    if (o.binary_output && is_dash(target) && is_terminal(stdout) && !o.force)
        return make_error(Errc::io, input_name(first_input) +
                                        ": refusing to write compressed data to a terminal "
                                        "(use -f, -c with a redirect, or -o FILE)");
    return OutputFile::open(target, o.force);
}

}  // namespace

int run_file_jobs(const FileJobOptions& options, const TargetFn& target, const WantedFn& wanted,
                  const TransformFn& transform) {
    FileJobOptions o = options;
    if (o.inputs.empty()) o.inputs.push_back("-");
    if (o.recursive) {
        auto files = expand_directories(o.inputs, wanted);
        if (!files) return report(files.error());
        o.inputs = std::move(*files);
        if (o.inputs.empty()) {
            if (!o.quiet) note(o.command + ": no files to process");
            return 0;
        }
    }
    if (auto refused = console_stdin_refused(o.inputs, o.force)) return report(*refused);
    const bool shared = o.to_stdout || !o.output.empty();
    if (!o.output.empty() && o.inputs.size() > 1 && !o.force)
        return report(make_error(Errc::invalid_argument,
                                 o.command + ": -o with " + std::to_string(o.inputs.size()) +
                                     " inputs writes them one after another into " + o.output +
                                     "; add -f to do that"));
    if (o.remove && (o.to_stdout || (shared && o.inputs.size() > 1))) {
        if (!o.quiet)
            note(o.command + ": --rm ignored: " +
                 (o.to_stdout ? std::string("with -c the input is kept")
                              : std::string("inputs sharing one output are kept")));
        o.remove = false;
    }

    if (shared) {
        const std::string dest = o.to_stdout ? std::string("-") : o.output;
        for (const std::string& input : o.inputs)
            if (auto refused = overwrites_input(input, dest)) return report(*refused);
        auto out = open_output(o, dest, o.inputs.front());
        if (!out) return report(out.error());
        int status = 0;
        for (const std::string& input : o.inputs) {
            InputStream in;
            if (auto r = in.open(input); !r) {
                status = report(r.error());
            } else if (run_one(o, in, *out, transform) != 0) {
                status = 1;
            } else if (o.inputs.size() == 1 && in.file_status()) {
                out->keep_attributes_of(*in.file_status());
            }
            // A file output holding a gap would look complete: stop and
            // discard it. Standard output already carries what was written.
            if (status != 0 && !out->is_stdout()) return status;
        }
        if (auto r = out->commit(); !r) return report(r.error());
        if (status == 0 && o.remove && !is_dash(o.inputs.front())) status = remove_input(o.inputs.front());
        return status;
    }

    int status = 0;
    for (const std::string& input : o.inputs) {
        std::string dest = "-";
        if (!is_dash(input)) {
            auto t = target(input);
            if (!t) {
                status = report(t.error());
                continue;
            }
            dest = std::move(*t);
        }
        if (auto refused = overwrites_input(input, dest)) {
            status = report(*refused);
            continue;
        }
        InputStream in;
        if (auto r = in.open(input); !r) {
            status = report(r.error());
            continue;
        }
        auto out = open_output(o, dest, input);
        if (!out) {
            status = report(out.error());
            continue;
        }
        if (run_one(o, in, *out, transform) != 0) {
            status = 1;
            continue;
        }
        if (in.file_status()) out->keep_attributes_of(*in.file_status());
        if (auto r = out->commit(); !r) {
            status = report(r.error());
            continue;
        }
        if (o.remove && !is_dash(input) && remove_input(input) != 0) status = 1;
    }
    return status;
}

}  // namespace stepzip::cli
