// stepzip verify INPUT.stz [ORIGINAL] (SPEC section 6) and zstd's -t FILE...: exit 0
// only if every .stz decodes exactly.
#include <boost/program_options.hpp>
#include <cstdio>
#include <iostream>
#include <string>

#include "cli_common.hpp"
#include "commands.hpp"
#include "options.hpp"
#include "stepzip/container.hpp"
#include "stz_stream.hpp"

namespace po = boost::program_options;

namespace stepzip::cli {

namespace {

// Decodes one frame; with `original` open, compares the decoded bytes with it.
int verify_one(const std::string& file, InputStream* original, bool quiet) {
    InputStream in;
    if (auto r = in.open(file); !r) return report(r.error());
    const bool compare = original != nullptr;
    std::uint64_t offset = 0;
    bool differs = false;
    std::string buf;
    WriteFn sink = [&](std::string_view b) -> Result<void> {
        if (!compare || differs) return {};
        buf.resize(b.size());
        auto n = original->read(buf.data(), b.size());
        if (!n) return std::move(n).error();
        for (std::size_t i = 0; i < b.size(); ++i)
            if (i >= *n || buf[i] != b[i]) {
                offset += i;
                differs = true;
                return {};
            }
        offset += b.size();
        return {};
    };
    auto info = decompress_stream(in.reader(), sink, in.name());
    if (!info) return report(info.error());
    if (compare && !differs) {
        char c;
        auto n = original->read(&c, 1);
        if (!n) return report(n.error());
        differs = *n != 0;
    }
    if (differs)
        return report(make_error(Errc::mismatch, in.name() + ": decoded bytes differ from " +
                                                     original->name() + " at byte " +
                                                     std::to_string(offset)));
    if (!quiet)
        std::printf("%s: OK (%llu bytes%s)\n", in.name().c_str(),
                    static_cast<unsigned long long>(info->decoded_bytes),
                    compare ? (", identical to " + original->name()).c_str() : "");
    return 0;
}

// The two forms of the command: SPEC's `verify INPUT.stz [ORIGINAL]` and
// zstd's `-t INPUT.stz...`, which tests every file named (`each`).
int run_verify(const std::vector<std::string>& args, bool each) {
    std::vector<std::string> files;
    std::string original;
    bool quiet = false, recursive = false;
    const std::string name = each ? "-t" : "verify";  // for messages
    po::options_description desc(
        each ? "Usage: stepzip -t INPUT.stz... [--original FILE] [-r] [-q]   (zstd's form)\n"
               "Decodes every INPUT.stz and checks every block and the content XXH64; with\n"
               "--original FILE (one input), also compares the decoded bytes with FILE.\n"
               "Exit 0 only if every round trip is exact.\n"
               "Options"
             : "Usage: stepzip verify INPUT.stz [ORIGINAL] [-q]\n"
               "       stepzip verify -r DIR [-q]\n"
               "Decodes INPUT.stz and checks every block and the content XXH64; with\n"
               "ORIGINAL, also compares the decoded bytes with it. Exit 0 only if the\n"
               "round trip is exact. ('stepzip -t A.stz B.stz' tests several files.)\n"
               "Options");
    desc.add_options()
        ("help,h", "show this help")
        ("original", po::value(&original),
         each ? "compare the decoded bytes with FILE (one input only)" : "the same as ORIGINAL")
        ("recursive,r", po::bool_switch(&recursive), "test the *.stz files under directories")
        ("quiet,q", po::bool_switch(&quiet), "print nothing on success");
    po::variables_map vm;
    if (auto exit_code = parse_command(name, args, desc, "file", po::value(&files), -1, vm))
        return *exit_code;
    if (!each && files.size() > 2)
        return usage_error("verify: takes INPUT.stz [ORIGINAL], " + std::to_string(files.size()) +
                           " files given ('stepzip -t' tests several files)");
    if (!each && files.size() == 2) {
        if (!original.empty())
            return usage_error("verify: ORIGINAL given twice (" + files[1] + " and --original " +
                               original + ")");
        original = files[1];
        files.pop_back();
    }
    if (files.empty()) files.push_back("-");
    if (recursive) {
        auto expanded = expand_directories(
            files, [](const std::string& path) { return has_suffix(path, ".stz"); });
        if (!expanded) return report(expanded.error());
        files = std::move(*expanded);
    }
    if (!original.empty() && files.size() != 1)
        return usage_error(name + ": an original compares one input, " + std::to_string(files.size()) +
                           " given");
    if (auto refused = console_stdin_refused(files, false)) return report(*refused);
    InputStream orig;
    if (!original.empty())
        if (auto r = orig.open(original); !r) return report(r.error());
    int status = 0;
    for (const std::string& f : files)
        if (verify_one(f, original.empty() ? nullptr : &orig, quiet) != 0) status = 1;
    return status;
}

}  // namespace

int cmd_verify(const std::vector<std::string>& args) { return run_verify(args, false); }

int cmd_test(const std::vector<std::string>& args) { return run_verify(args, true); }

}  // namespace stepzip::cli
