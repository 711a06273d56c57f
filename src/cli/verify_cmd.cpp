// stepzip verify: exit 0 only if the .stz decodes exactly (SPEC section 6).
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

int cmd_verify(const std::vector<std::string>& args) {
    std::vector<std::string> files;
    bool quiet = false;
    po::options_description desc(
        "Usage: stepzip verify INPUT.stz [ORIGINAL]\n"
        "Decodes INPUT.stz and checks every block and the content XXH64; with ORIGINAL,\n"
        "also compares the decoded bytes with it. Exit 0 only if the round trip is exact.\n"
        "Options");
    desc.add_options()("help,h", "show this help")("quiet,q", po::bool_switch(&quiet),
                                                   "print nothing on success");
    po::variables_map vm;
    if (auto exit_code = parse_command("verify", args, desc, "file", po::value(&files), 2, vm))
        return *exit_code;
    if (files.empty()) return usage_error("verify: INPUT.stz is required");
    InputStream in;
    if (auto r = in.open(files[0]); !r) return report(r.error());
    InputStream orig;
    const bool compare = files.size() > 1;
    if (compare)
        if (auto r = orig.open(files[1]); !r) return report(r.error());
    std::uint64_t offset = 0;
    bool differs = false;
    std::string buf;
    WriteFn sink = [&](std::string_view b) -> Result<void> {
        if (!compare || differs) return {};
        buf.resize(b.size());
        auto n = orig.read(buf.data(), b.size());
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
        auto n = orig.read(&c, 1);
        if (!n) return report(n.error());
        differs = *n != 0;
    }
    if (differs)
        return report(make_error(Errc::mismatch, in.name() + ": decoded bytes differ from " +
                                                     orig.name() + " at byte " +
                                                     std::to_string(offset)));
    if (!quiet)
        std::printf("%s: OK (%llu bytes%s)\n", in.name().c_str(),
                    static_cast<unsigned long long>(info->decoded_bytes),
                    compare ? (", identical to " + orig.name()).c_str() : "");
    return 0;
}

}  // namespace stepzip::cli
