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

/// zstd's way of writing options, rewritten for Boost.Program_options, for the
/// commands that share zstd's command line (compress, decompress, verify,
/// info): bundled short options are split ("-zc" -> "-z" "-c", "-T4" ->
/// "-T" "4"), a level "-#" becomes "-L" "#" ("-19", "-c19"), and of "-c" and
/// "-o FILE" only the last one given is kept, as zstd lets the last win.
/// Everything after "--" is passed on unchanged.
std::vector<std::string> split_zstd_options(const std::vector<std::string>& args);

/// The command named by a zstd mode option in `args` (already split):
/// "-z"/"--compress" -> "compress", "-d"/"--decompress"/"--uncompress" ->
/// "decompress", "-t"/"--test" -> "test" (verify's check of every file
/// named, see cmd_test), "-l"/"--list" -> "info"; the last one wins,
/// "compress" when there is none. The mode options are
/// removed from `args`.
std::string take_zstd_mode(std::vector<std::string>& args);

}  // namespace stepzip::cli
