// stepzip command line: the option parsing every subcommand shares.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <boost/program_options.hpp>

namespace stepzip::cli {

/// Parses a subcommand's arguments (args[0] is the subcommand name) against
/// the visible options `visible` (which should hold "help,h") plus one hidden
/// positional option `positional_name` taking `positional` (up to
/// `max_positional` values, -1 = any number). Fills `vm`.
/// Returns nullopt when the command should go on, otherwise the exit code to
/// return: 0 after printing the help for --help, 2 after a usage error line.
std::optional<int> parse_command(std::string_view command, const std::vector<std::string>& args,
                                 const boost::program_options::options_description& visible,
                                 const char* positional_name,
                                 const boost::program_options::value_semantic* positional,
                                 int max_positional, boost::program_options::variables_map& vm);

}  // namespace stepzip::cli
