#include "options.hpp"

#include <iostream>

#include "cli_common.hpp"

namespace stepzip::cli {

namespace po = boost::program_options;

std::optional<int> parse_command(std::string_view command, const std::vector<std::string>& args,
                                 const po::options_description& visible,
                                 const char* positional_name,
                                 const po::value_semantic* positional, int max_positional,
                                 po::variables_map& vm) {
    po::options_description hidden;
    hidden.add_options()(positional_name, positional);
    po::options_description all;
    all.add(visible).add(hidden);
    po::positional_options_description pos;
    pos.add(positional_name, max_positional);
    try {
        po::store(po::command_line_parser(std::vector<std::string>(args.begin() + 1, args.end()))
                      .options(all)
                      .positional(pos)
                      .run(),
                  vm);
        po::notify(vm);
    } catch (const po::error& e) {
        return usage_error(std::string(command) + ": " + e.what());
    }
    if (vm.count("help")) {
        std::cout << visible << "\n";
        return 0;
    }
    return std::nullopt;
}

}  // namespace stepzip::cli
