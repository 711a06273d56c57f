// stepzip command line: one function per subcommand, each in its own file.
#pragma once

#include <string>
#include <vector>

namespace stepzip::cli {

/// Every subcommand takes its own arguments (argv[0] is the subcommand name)
/// and returns the process exit code: 0 success, 1 error, 2 usage error.
using CommandFn = int (*)(const std::vector<std::string>& args);

struct Command {
    const char* name;
    const char* alias;  ///< short option form, e.g. "-d" for decompress, or nullptr
    CommandFn run;
    const char* summary;
};

/// The table of subcommands (defined in main.cpp).
const std::vector<Command>& commands();

int cmd_compress(const std::vector<std::string>& args);     // compress_cmd.cpp
int cmd_decompress(const std::vector<std::string>& args);   // decompress_cmd.cpp
int cmd_verify(const std::vector<std::string>& args);       // verify_cmd.cpp
/// zstd's -t: tests every file named (verify's second operand is ORIGINAL).
int cmd_test(const std::vector<std::string>& args);         // verify_cmd.cpp
int cmd_info(const std::vector<std::string>& args);         // info_cmd.cpp
int cmd_interpolate(const std::vector<std::string>& args);  // interpolate_cmd.cpp
int cmd_segment(const std::vector<std::string>& args);      // segment_cmd.cpp

}  // namespace stepzip::cli
