// stepzip info: what a .stz holds (SPEC section 6).
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

int cmd_info(const std::vector<std::string>& args) {
    std::vector<std::string> files;
    po::options_description desc(
        "Usage: stepzip info INPUT.stz...\n"
        "Prints the profile, chains, steps, segments, bits/step and sizes of a .stz\n"
        "(block checksums are checked; 'verify' checks the decoded content).\nOptions");
    desc.add_options()("help,h", "show this help");
    po::variables_map vm;
    if (auto exit_code = parse_command("info", args, desc, "file", po::value(&files), -1, vm))
        return *exit_code;
    if (files.empty()) files.push_back("-");
    if (auto refused = console_stdin_refused(files, false)) return report(*refused);
    int status = 0;
    for (const std::string& f : files) {
        InputStream in;
        if (auto r = in.open(f); !r) {
            status = report(r.error());
            continue;
        }
        auto info = inspect_stream(in.reader(), in.name());
        if (!info) {
            status = report(info.error());
            continue;
        }
        const auto u = [](std::uint64_t v) { return static_cast<unsigned long long>(v); };
        std::printf("file:            %s\n", in.name().c_str());
        std::printf("format version:  %d\n", info->format_version);
        std::printf("profile:         %s\n", std::string(profile_name(info->profile)).c_str());
        std::printf("input format:    %s\n", std::string(format_name(info->format)).c_str());
        std::printf("axes:            %d\n", info->axes);
        std::printf("segmenter:       %s\n", std::string(segmenter_name(info->segmenter)).c_str());
        std::printf("blocks:          %llu (raw: %llu, segment model: %llu, step model: %llu, table: %llu",
                    u(info->blocks), u(info->raw_blocks), u(info->segment_model_blocks),
                    u(info->step_model_blocks), u(info->table_blocks));
        if (info->timed_blocks != 0) std::printf(", timed: %llu", u(info->timed_blocks));
        std::printf(")\n");
        std::printf("chains:          %llu\n", u(info->chains));
        std::printf("steps:           %llu\n", u(info->steps));
        std::printf("segments:        %llu\n", u(info->segments));
        std::printf("original size:   %llu bytes\n", u(info->decoded_bytes));
        std::printf("compressed size: %llu bytes\n", u(info->compressed_bytes));
        if (info->steps)
            std::printf("bits/step:       %.4f\n", 8.0 * info->compressed_bytes / info->steps);
        else
            std::printf("bits/step:       -\n");
        std::printf("xxh64:           %016llx\n", u(info->checksum));
        if (info->segmenter == SegmenterKind::patent)
            std::printf("patent:          %llu segments read out, %llu exact, max deviation %lld steps\n",
                        u(info->stats.patent_segments), u(info->stats.patent_exact),
                        static_cast<long long>(info->stats.patent_max_deviation));
    }
    return status;
}

}  // namespace stepzip::cli
