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
#include "file_driver.hpp"
#include "stz_stream.hpp"

namespace po = boost::program_options;

namespace stepzip::cli {

int cmd_decompress(const std::vector<std::string>& args) {
    FileJobOptions a;
    a.command = "decompress";
    unsigned threads = 1;
    po::options_description desc(
        "Usage: stepzip decompress [INPUT.stz... | -] [-o OUT] [-c] [-f] [-k|--rm] [-r] [-q|-v]\n"
        "       stepzip -d ...      (zstd's form; -dc = -d -c)\n"
        "Restores the original bytes and checks their XXH64. FILE.stz -> FILE (mode, owner\n"
        "and times kept); no INPUT or '-' = stdin -> stdout. Frames written one after\n"
        "another (cat a.stz b.stz, compress -c a b) decode one after another.\nOptions");
    desc.add_options()
        ("help,h", "show this help")
        ("output,o", po::value(&a.output), "write to OUT (several inputs: with -f, one after another)")
        ("stdout,c", po::bool_switch(&a.to_stdout), "write to standard output (the input is kept)")
        ("force,f", po::bool_switch(&a.force), "overwrite existing outputs; allow a terminal as input")
        ("keep,k", "keep the input (default)")
        ("rm", po::bool_switch(&a.remove), "remove the input after success (never with -c)")
        ("recursive,r", po::bool_switch(&a.recursive), "decompress the *.stz files under directories")
        ("threads,T", po::value(&threads), "accepted as zstd accepts it; decoding uses one thread")
        ("quiet,q", po::bool_switch(&a.quiet), "no messages but errors")
        ("verbose,v", po::bool_switch(&a.verbose), "print a summary line per input")
        ("progress", "show progress on a terminal (default)")
        ("no-progress", "never show progress");
    po::variables_map vm;
    if (auto exit_code = parse_command("decompress", args, desc, "input", po::value(&a.inputs), -1, vm))
        return *exit_code;
    if (vm.count("no-progress")) a.progress = false;
    if (vm.count("keep") && a.remove) return usage_error("decompress: -k and --rm conflict");
    if (a.quiet && a.verbose) return usage_error("decompress: -q and -v conflict");
    const TargetFn target = [](const std::string& input) -> Result<std::string> {
        if (!has_suffix(input, ".stz"))
            return make_error(Errc::invalid_argument,
                              input + ": unknown suffix, expected .stz (use -o OUT or -c)");
        return input.substr(0, input.size() - 4);
    };
    const WantedFn wanted = [](const std::string& path) { return has_suffix(path, ".stz"); };
    const TransformFn transform = [](InputStream& in, const ReadFn& read, const WriteFn& write,
                                     const ProgressFn& tick) -> Result<std::string> {
        auto info = decompress_stream(read, write, in.name(), tick);
        if (!info) return std::move(info).error();
        return std::string("profile ") + std::string(profile_name(info->profile));
    };
    return run_file_jobs(a, target, wanted, transform);
}

}  // namespace stepzip::cli
