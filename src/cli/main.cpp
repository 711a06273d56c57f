// stepzip command line entry point: dispatches to a subcommand.
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "commands.hpp"
#include "stepzip/version.hpp"

namespace stepzip::cli {

const std::vector<Command>& commands() {
    static const std::vector<Command> table = {
        {"compress", "-z", cmd_compress, "chain files -> .stz (lossless, verified)"},
        {"decompress", "-d", cmd_decompress, ".stz -> the original chain files"},
        {"verify", "-t", cmd_verify, "exit 0 only if the round trip is exact"},
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
                 "Lossless compression of unit-step chains by reverse interpolation.\n\n"
                 "Commands:\n");
    for (const Command& c : commands()) {
        const std::string name = c.alias ? std::string(c.name) + ", " + c.alias : c.name;
        std::fprintf(out, "  %-16s %s\n", name.c_str(), c.summary);
    }
    std::fprintf(out, "\n'stepzip COMMAND --help' describes a command's options.\n");
}

}  // namespace
}  // namespace stepzip::cli

int main(int argc, char** argv) {
    using namespace stepzip::cli;
    if (argc < 2) {
        print_usage(stderr);
        return 2;
    }
    const std::string first = argv[1];
    if (first == "-h" || first == "--help") {
        print_usage(stdout);
        return 0;
    }
    if (first == "-V" || first == "--version") {
        std::printf("stepzip %s\n", stepzip::version_string());
        return 0;
    }
    for (const Command& c : commands()) {
        if (first == c.name || (c.alias && first == c.alias)) {
            std::vector<std::string> args(argv + 1, argv + argc);
            args[0] = c.name;
            return c.run(args);
        }
    }
    std::fprintf(stderr, "stepzip: unknown command '%s' (try 'stepzip --help')\n", first.c_str());
    return 2;
}
