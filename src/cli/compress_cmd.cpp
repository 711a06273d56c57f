// stepzip compress: chain files -> .stz (SPEC section 6).
#include <unistd.h>

#include <boost/program_options.hpp>
#include <cstdio>
#include <iostream>
#include <utility>

#include "cli_common.hpp"
#include "commands.hpp"
#include "options.hpp"
#include "stepzip/container.hpp"
#include "file_driver.hpp"
#include "stz_stream.hpp"

namespace po = boost::program_options;

namespace stepzip::cli {

namespace {

// Where a text format fails on `head`: the parser's message and its
// LINE:COLUMN, for naming the best guess when detection finds no format.
struct Attempt {
    InputFormat format;
    std::string message;
    std::uint64_t line = 0, column = 0;
};

Attempt try_format(InputFormat format, std::string_view head, const std::string& source) {
    Attempt a{format, {}, 0, 0};
    BlockReader reader(format, source);
    auto r = reader.feed(head, true);
    if (r) return a;
    a.message = r.error().message;
    // "SOURCE:LINE:COLUMN: ..." — the numbers after the source name.
    if (a.message.compare(0, source.size() + 1, source + ":") == 0) {
        unsigned long long line = 0, column = 0;
        if (std::sscanf(a.message.c_str() + source.size() + 1, "%llu:%llu", &line, &column) == 2) {
            a.line = line;
            a.column = column;
        }
    }
    return a;
}

// The error for an input whose format detection failed: the text format
// that read furthest into the first bytes and where it stopped.
Error explain_unknown_format(std::string_view head, const std::string& source) {
    const std::size_t nl = head.rfind('\n');
    if (nl != std::string_view::npos) head = head.substr(0, nl + 1);  // whole lines only
    const Attempt fr = try_format(InputFormat::freeman, head, source);
    const Attempt pt = try_format(InputFormat::points, head, source);
    const Attempt& best =
        std::pair(pt.line, pt.column) > std::pair(fr.line, fr.column) ? pt : fr;
    if (best.message.empty() || best.line == 0)
        return make_error(Errc::unsupported, source + ": cannot tell the input format (use "
                                                      "--format freeman|points|steps)");
    return make_error(Errc::unsupported,
                      source + ": cannot tell the input format; it looks most like " +
                          std::string(format_name(best.format)) + ": " + best.message +
                          " (use --format freeman|points|steps)");
}

}  // namespace

int cmd_compress(const std::vector<std::string>& args) {
    FileJobOptions a;
    a.command = "compress";
    a.binary_output = true;
    CompressOptions opt;
    std::string profile = "auto", segmenter, format, arc_arg;
    int level = 3;
    unsigned threads = 1;
    std::size_t block_steps = kDefaultBlockSteps;
    po::options_description desc(
        "Usage: stepzip compress [INPUT... | -] [-o OUT] [-c] [-f] [-k|--rm] [-r] [--profile P]\n"
        "                        [--segmenter greedy|optimal|patent] [-L LEVEL|-#] [-T N] [-q|-v]\n"
        "                        [--arc-method M]\n"
        "       stepzip [-z] ...    (zstd's form: no command compresses)\n"
        "Compresses chain files (freeman, points, steps) into .stz; every block's round trip\n"
        "is proved before it is written. FILE -> FILE.stz (mode, owner and times kept);\n"
        "no INPUT or '-' = stdin -> stdout. With -c or -o, every input's frame is written\n"
        "one after another to that output; 'stepzip -d' restores their bytes in order.\n"
        "Options");
    desc.add_options()
        ("help,h", "show this help")
        ("output,o", po::value(&a.output), "write to OUT (several inputs: with -f, one after another)")
        ("stdout,c", po::bool_switch(&a.to_stdout), "write to standard output (the input is kept)")
        ("force,f", po::bool_switch(&a.force), "overwrite outputs; allow a terminal as input or output")
        ("keep,k", "keep the input (default)")
        ("rm", po::bool_switch(&a.remove), "remove the input after success (never with -c)")
        ("recursive,r", po::bool_switch(&a.recursive), "compress the files under directories "
                                                       "(except *.stz)")
        ("profile", po::value(&profile), "eval4|eval8|patent|grbl|marlin|auto (default auto: "
                                          "smallest output on the first block)")
        ("segmenter", po::value(&segmenter), "greedy|optimal|patent (default: greedy below "
                                             "-L 19, optimal at 19 for two axes)")
        ("level,L", po::value(&level), "1 (fastest) .. 19 (smallest), default 3, also as -1 .. -19; "
                                       "1-9 write table blocks (fast to decode; dense contours "
                                       "also try the step model from 3), the profile and cut "
                                       "chosen on samples; from 10 every encoding is tried, 19 "
                                       "adds the optimal segmenter")
        ("threads,T", po::value(&threads), "compress blocks on N threads (0 = all cores; default 1); "
                                           "output does not depend on N")
        ("format", po::value(&format), "freeman|points|steps|timed (default: detected; timed: a steps log read with time as axis 0)")
        ("block-size", po::value(&block_steps), "steps per block (default 1048576; timed logs: 4194304 ticks)")
        ("arc-method", po::value(&arc_arg),
         "two-axis chains: also code circular arcs drawn by M (evaluation, accelerated, dda, "
         "prediction, recursion; as `interpolate --arc-method`) where that is smaller; default: "
         "lines only (the arc search is slow, see docs/cli.md)")
        ("no-raw", "never carry a block as plain zstd of its bytes, even when smaller")
        ("quiet,q", po::bool_switch(&a.quiet), "no messages but errors")
        ("verbose,v", po::bool_switch(&a.verbose), "print a summary line per input: ratio, sizes, "
                                                   "steps, bits/step, profile")
        ("progress", "show progress on a terminal (default)")
        ("no-progress", "never show progress");
    po::variables_map vm;
    if (auto exit_code = parse_command("compress", args, desc, "input", po::value(&a.inputs), -1, vm))
        return *exit_code;
    if (vm.count("no-progress")) a.progress = false;
    if (vm.count("no-raw")) opt.allow_raw = false;
    if (vm.count("keep") && a.remove) return usage_error("compress: -k and --rm conflict");
    if (a.quiet && a.verbose) return usage_error("compress: -q and -v conflict");
    if (profile != "auto") {
        opt.profile = parse_profile(profile);
        if (!opt.profile) return usage_error("compress: unknown profile '" + profile + "'");
    }
    if (!segmenter.empty()) {
        opt.segmenter = parse_segmenter(segmenter);
        if (!opt.segmenter) return usage_error("compress: unknown segmenter '" + segmenter + "'");
    }
    if (!format.empty()) {
        opt.format = parse_format(format);
        if (!opt.format) return usage_error("compress: unknown format '" + format + "'");
    }
    if (!arc_arg.empty()) {
        opt.arc_method = parse_arc_method(arc_arg);
        if (!opt.arc_method) return usage_error("compress: unknown arc method '" + arc_arg + "'");
        if (opt.format == InputFormat::timed) return usage_error("compress: --arc-method does not go with --format timed");
    }
    if (level < 1 || level > 19) return usage_error("compress: -L must be 1..19");
    if (block_steps < 1 || block_steps > kMaxBlockSteps)
        return usage_error("compress: --block-size must be 1..16777216");
    opt.level = level;
    opt.threads = threads;
    if (vm.count("block-size")) opt.block_steps = block_steps;

    const TargetFn target = [](const std::string& input) -> Result<std::string> {
        return input + ".stz";
    };
    const WantedFn wanted = [](const std::string& path) { return !has_suffix(path, ".stz"); };
    const TransformFn transform = [&](InputStream& in, const ReadFn& read, const WriteFn& write,
                                      const ProgressFn& tick) -> Result<std::string> {
        CompressOptions o = opt;
        o.source = in.name();
        // The first bytes, kept to explain a failed format detection.
        std::string head;
        const ReadFn keep_head = [&](char* buf, std::size_t cap) -> Result<std::size_t> {
            auto n = read(buf, cap);
            if (n && head.empty()) head.assign(buf, *n);
            return n;
        };
        auto info = compress_stream(keep_head, write, o, tick);
        if (!info) {
            if (!o.format && info.error().code == Errc::unsupported && !head.empty() &&
                !detect_format(head))
                return explain_unknown_format(head, in.name());
            return std::move(info).error();
        }
        const double bits = info->steps ? 8.0 * info->compressed_bytes / info->steps : 0.0;
        char detail[128];
        std::snprintf(detail, sizeof detail, "%llu steps, %.3f bits/step, profile %s",
                      static_cast<unsigned long long>(info->steps), bits,
                      std::string(profile_name(info->profile)).c_str());
        return std::string(detail);
    };
    return run_file_jobs(a, target, wanted, transform);
}

}  // namespace stepzip::cli
