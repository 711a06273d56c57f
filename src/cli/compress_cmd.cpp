// stepzip compress: chain files -> .stz (SPEC section 6).
#include <unistd.h>

#include <boost/program_options.hpp>
#include <cstdio>
#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "options.hpp"
#include "stepzip/container.hpp"
#include "stz_stream.hpp"

namespace po = boost::program_options;

namespace stepzip::cli {

namespace {

struct CompressArgs {
    std::vector<std::string> inputs;
    std::string output;
    bool to_stdout = false, force = false, remove = false, quiet = false, verbose = false;
    bool progress = true;
    CompressOptions opt;
};

int compress_one(const std::string& input, const CompressArgs& a) {
    InputStream in;
    if (auto r = in.open(input); !r) return report(r.error());
    std::string target;
    if (!a.output.empty()) target = a.output;
    else if (a.to_stdout || is_dash(input)) target = "-";
    else target = input + ".stz";
    if (is_dash(target) && is_terminal(stdout) && !a.force)
        return report(make_error(Errc::io, in.name() +
                                               ": refusing to write compressed data to a terminal "
                                               "(use -f, -c with a redirect, or -o FILE)"));
    auto out = OutputFile::open(target, a.force);
    if (!out) return report(out.error());
    CompressOptions opt = a.opt;
    opt.source = in.name();
    Progress progress("compress " + in.name(), in.size(), a.progress && !a.quiet);
    WriteFn sink = [&](std::string_view b) { return out->write(b); };
    auto info = compress_stream(in.reader(), sink, opt,
                                [&](std::uint64_t done) { progress.update(done); });
    progress.finish();
    if (!info) return report(info.error());
    if (auto r = out->commit(); !r) return report(r.error());
    if (a.verbose) {
        const double bits = info->steps ? 8.0 * info->compressed_bytes / info->steps : 0.0;
        std::fprintf(stderr, "%s: %llu -> %llu bytes, %llu steps, %.3f bits/step, profile %s\n",
                     in.name().c_str(), static_cast<unsigned long long>(info->decoded_bytes),
                     static_cast<unsigned long long>(info->compressed_bytes),
                     static_cast<unsigned long long>(info->steps), bits,
                     std::string(profile_name(info->profile)).c_str());
    }
    if (a.remove && !is_dash(input) && ::unlink(input.c_str()) != 0)
        return report(make_error(Errc::io, input + ": cannot remove: " + std::strerror(errno)));
    return 0;
}

}  // namespace

int cmd_compress(const std::vector<std::string>& args) {
    CompressArgs a;
    std::string profile = "auto", segmenter, format;
    int level = 3;
    unsigned threads = 1;
    std::size_t block_steps = kDefaultBlockSteps;
    po::options_description desc(
        "Usage: stepzip compress [INPUT... | -] [-o OUT] [-c] [-f] [-k|--rm] [--profile P]\n"
        "                        [--segmenter greedy|optimal|patent] [-L LEVEL] [-T N] [-q|-v]\n"
        "Compresses chain files (freeman, points, steps) into .stz; every block's round trip\n"
        "is proved before it is written. FILE -> FILE.stz; no INPUT or '-' = stdin -> stdout.\n"
        "Options");
    desc.add_options()
        ("help,h", "show this help")
        ("output,o", po::value(&a.output), "write to OUT (one input only)")
        ("stdout,c", po::bool_switch(&a.to_stdout), "write to standard output")
        ("force,f", po::bool_switch(&a.force), "overwrite outputs; allow a terminal as output")
        ("keep,k", "keep the input (default)")
        ("rm", po::bool_switch(&a.remove), "remove the input after success")
        ("profile", po::value(&profile), "eval4|eval8|patent|grbl|marlin|auto (default auto: "
                                          "smallest output on the first block)")
        ("segmenter", po::value(&segmenter), "greedy|optimal|patent (default: greedy below "
                                             "-L 19, optimal at 19)")
        ("level,L", po::value(&level), "1 (fastest) .. 19 (smallest), default 3; below 10 the "
                                       "profile, cut and block kind are chosen on samples, from 10 "
                                       "every encoding is tried, 19 adds the optimal segmenter")
        ("threads,T", po::value(&threads), "compress blocks on N threads (0 = all cores; default 1); "
                                           "output does not depend on N")
        ("format", po::value(&format), "freeman|points|steps|timed (default: detected; timed: a steps log read with time as axis 0)")
        ("block-size", po::value(&block_steps), "steps per block (default 1048576)")
        ("no-raw", "never carry a block as plain zstd of its bytes, even when smaller")
        ("quiet,q", po::bool_switch(&a.quiet), "no messages but errors")
        ("verbose,v", po::bool_switch(&a.verbose), "print sizes and bits/step")
        ("progress", "show progress on a terminal (default)")
        ("no-progress", "never show progress");
    po::variables_map vm;
    if (auto exit_code = parse_command("compress", args, desc, "input", po::value(&a.inputs), -1, vm))
        return *exit_code;
    if (vm.count("no-progress")) a.progress = false;
    if (vm.count("no-raw")) a.opt.allow_raw = false;
    if (vm.count("keep") && a.remove) return usage_error("compress: -k and --rm conflict");
    if (a.quiet && a.verbose) return usage_error("compress: -q and -v conflict");
    if (profile != "auto") {
        a.opt.profile = parse_profile(profile);
        if (!a.opt.profile) return usage_error("compress: unknown profile '" + profile + "'");
    }
    if (!segmenter.empty()) {
        a.opt.segmenter = parse_segmenter(segmenter);
        if (!a.opt.segmenter) return usage_error("compress: unknown segmenter '" + segmenter + "'");
    }
    if (!format.empty()) {
        a.opt.format = parse_format(format);
        if (!a.opt.format) return usage_error("compress: unknown format '" + format + "'");
    }
    if (level < 1 || level > 19) return usage_error("compress: -L must be 1..19");
    if (block_steps < 1 || block_steps > kMaxBlockSteps)
        return usage_error("compress: --block-size must be 1..16777216");
    a.opt.level = level;
    a.opt.threads = threads;
    a.opt.block_steps = block_steps;
    if (a.inputs.empty()) a.inputs.push_back("-");
    if (!a.output.empty() && a.inputs.size() > 1)
        return usage_error("compress: -o takes a single input");
    if (!a.output.empty() && a.to_stdout) return usage_error("compress: -o and -c conflict");
    int status = 0;
    for (const std::string& in : a.inputs)
        if (compress_one(in, a) != 0) status = 1;
    return status;
}

}  // namespace stepzip::cli
