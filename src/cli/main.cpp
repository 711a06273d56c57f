// stepzip command line entry point: dispatches to a subcommand.
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <sys/stat.h>

#include "cli_common.hpp"
#include "commands.hpp"
#include "options.hpp"
#include "stepzip/version.hpp"

namespace stepzip::cli {

const std::vector<Command>& commands() {
    static const std::vector<Command> table = {
        {"compress", "-z", cmd_compress, "chain files -> .stz (lossless, verified)"},
        {"decompress", "-d", cmd_decompress, ".stz -> the original chain files"},
        {"verify", nullptr, cmd_verify, "INPUT.stz [ORIGINAL]: exit 0 only if the round trip is exact"},
        {"info", "-l", cmd_info, "profile, chains, steps, segments, bits/step"},
        {"interpolate", nullptr, cmd_interpolate, "vectors (G-code, HP-GL) -> steps (forward)"},
        {"segment", nullptr, cmd_segment, "steps -> vectors (G-code, HP-GL, SVG, JSON)"},
    };
    return table;
}

namespace {

void print_usage(std::FILE* out) {
    std::fprintf(out,
                 "Usage: stepzip COMMAND [OPTIONS] [INPUT... | -]\n"
                 "       stepzip [-z|-d|-t|-l] [OPTIONS] [INPUT... | -]   (as zstd: no mode compresses)\n"
                 "Lossless compression of unit-step chains by reverse interpolation.\n\n"
                 "Commands:\n");
    for (const Command& c : commands()) {
        const std::string name = c.alias ? std::string(c.name) + ", " + c.alias : c.name;
        std::fprintf(out, "  %-16s %s\n", name.c_str(), c.summary);
    }
    std::fprintf(out,
                 "\n-t tests every file named, as zstd's does ('stepzip -t a.stz b.stz');\n"
                 "'stepzip verify X.stz Y' compares X.stz's content with the original Y.\n"
                 "Short options bundle as in zstd (-zc, -dc, -19 = -L 19, -T4); of -c and -o\n"
                 "the last one given wins. 'stepzip COMMAND --help' describes a command's options.\n");
}

// The commands whose options follow zstd's command line.
bool zstd_like(std::string_view name) {
    return name == "compress" || name == "decompress" || name == "verify" || name == "info";
}

int run(const std::string& name, std::vector<std::string> rest) {
    if (name == "test") {  // zstd's -t: every file named is tested (see cmd_test)
        rest.insert(rest.begin(), "-t");
        return cmd_test(rest);
    }
    for (const Command& c : commands())
        if (name == c.name) {
            std::vector<std::string> args{name};
            args.insert(args.end(), rest.begin(), rest.end());
            return c.run(args);
        }
    std::fprintf(stderr, "stepzip: unknown command '%s' (try 'stepzip --help')\n", name.c_str());
    return 2;
}

}  // namespace
}  // namespace stepzip::cli

#if defined(STEPZIP_CLI_JEMALLOC)
// The CLI allocates through jemalloc (linked in place of the C library's
// malloc, CMakeLists.txt), whose memory is asked for in 2 MiB pages: a
// several-MB input's blocks, window and tables touch tens of MB, which in
// 4 KiB pages cost a page fault each, again whenever freed memory went back
// to the system (docs/benchmarks.md "The CLI's allocator"). MALLOC_CONF
// still overrides it.
extern "C" {
extern const char* malloc_conf;
const char* malloc_conf = "thp:always,metadata_thp:auto";
}
#endif

int main(int argc, char** argv) {
    using namespace stepzip::cli;
    if (argc < 2) return run("compress", {});  // as zstd: stdin -> stdout, a console refused
    const std::string first = argv[1];
    if (first == "-h" || first == "--help") {
        print_usage(stdout);
        return 0;
    }
    if (first == "-V" || first == "--version") {
        std::printf("stepzip %s\n", stepzip::version_string());
        return 0;
    }
    std::vector<std::string> rest(argv + 2, argv + argc);
    for (const Command& c : commands())
        if (first == c.name) return run(c.name, zstd_like(c.name) ? split_zstd_options(rest) : rest);
    // zstd's form: a mode option anywhere (-z, -d, -t, -l) or none, which
    // compresses. A first word that is neither a command nor a file nor an
    // option is most likely a mistyped command.
    struct stat st {};
    if (first[0] != '-' && first.find_first_of("./") == std::string::npos &&
        ::stat(first.c_str(), &st) != 0) {
        std::fprintf(stderr, "stepzip: '%s' is neither a command nor a file (try 'stepzip --help')\n",
                     first.c_str());
        return 2;
    }
    std::vector<std::string> args = split_zstd_options(std::vector<std::string>(argv + 1, argv + argc));
    const std::string mode = take_zstd_mode(args);
    return run(mode, args);
}
