// stepzip decompress: .stz -> the original chain files (SPEC section 6).
#include <unistd.h>

#include <boost/program_options.hpp>
#include <cstdio>
#include <cstring>
#include <iostream>

#include "cli_common.hpp"
#include "commands.hpp"
#include "options.hpp"
#include "stepzip/container.hpp"
#include "stz_stream.hpp"

namespace po = boost::program_options;

namespace stepzip::cli {

namespace {

struct DecompressArgs {
    std::vector<std::string> inputs;
    std::string output;
    bool to_stdout = false, force = false, remove = false, quiet = false, progress = true;
};

int decompress_one(const std::string& input, const DecompressArgs& a) {
    std::string target;
    if (!a.output.empty()) {
        target = a.output;
    } else if (a.to_stdout || is_dash(input)) {
        target = "-";
    } else {
        constexpr std::string_view suffix = ".stz";
        if (input.size() <= suffix.size() || input.compare(input.size() - suffix.size(), suffix.size(), suffix) != 0)
            return report(make_error(Errc::invalid_argument,
                                     input + ": unknown suffix, expected .stz (use -o OUT or -c)"));
        target = input.substr(0, input.size() - suffix.size());
    }
    InputStream in;
    if (auto r = in.open(input); !r) return report(r.error());
    auto out = OutputFile::open(target, a.force);
    if (!out) return report(out.error());
    Progress progress("decompress " + in.name(), in.size(), a.progress && !a.quiet);
    WriteFn sink = [&](std::string_view b) { return out->write(b); };
    auto info = decompress_stream(in.reader(), sink, in.name(),
                                  [&](std::uint64_t done) { progress.update(done); });
    progress.finish();
    if (!info) return report(info.error());
    if (auto r = out->commit(); !r) return report(r.error());
    if (a.remove && !is_dash(input) && ::unlink(input.c_str()) != 0)
        return report(make_error(Errc::io, input + ": cannot remove: " + std::strerror(errno)));
    return 0;
}

}  // namespace

int cmd_decompress(const std::vector<std::string>& args) {
    DecompressArgs a;
    po::options_description desc(
        "Usage: stepzip decompress [INPUT.stz... | -] [-o OUT] [-c] [-f] [-k|--rm]\n"
        "Restores the original bytes and checks their XXH64. FILE.stz -> FILE;\n"
        "no INPUT or '-' = stdin -> stdout.\nOptions");
    desc.add_options()
        ("help,h", "show this help")
        ("output,o", po::value(&a.output), "write to OUT (one input only)")
        ("stdout,c", po::bool_switch(&a.to_stdout), "write to standard output")
        ("force,f", po::bool_switch(&a.force), "overwrite existing outputs")
        ("keep,k", "keep the input (default)")
        ("rm", po::bool_switch(&a.remove), "remove the input after success")
        ("quiet,q", po::bool_switch(&a.quiet), "no messages but errors")
        ("progress", "show progress on a terminal (default)")
        ("no-progress", "never show progress");
    po::variables_map vm;
    if (auto exit_code = parse_command("decompress", args, desc, "input", po::value(&a.inputs), -1, vm))
        return *exit_code;
    if (vm.count("no-progress")) a.progress = false;
    if (vm.count("keep") && a.remove) return usage_error("decompress: -k and --rm conflict");
    if (a.inputs.empty()) a.inputs.push_back("-");
    if (!a.output.empty() && a.inputs.size() > 1)
        return usage_error("decompress: -o takes a single input");
    if (!a.output.empty() && a.to_stdout) return usage_error("decompress: -o and -c conflict");
    int status = 0;
    for (const std::string& in : a.inputs)
        if (decompress_one(in, a) != 0) status = 1;
    return status;
}

}  // namespace stepzip::cli
