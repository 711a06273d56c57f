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

int cmd_interpolate(const std::vector<std::string>& args);

}  // namespace stepzip::cli
