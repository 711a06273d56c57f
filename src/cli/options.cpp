#include "options.hpp"

#include <algorithm>
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

namespace {

// Short options that take a value, and long ones given without "=value".
bool short_takes_value(char c) noexcept { return c == 'o' || c == 'L' || c == 'T'; }
bool long_takes_value(std::string_view a) noexcept {
    for (std::string_view name : {"--output", "--level", "--threads", "--profile", "--segmenter",
                                  "--format", "--block-size", "--original"})
        if (a == name) return true;
    return false;
}
bool is_digit(char c) noexcept { return c >= '0' && c <= '9'; }

}  // namespace

std::vector<std::string> split_zstd_options(const std::vector<std::string>& args) {
    std::vector<std::string> out;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "--") {
            out.insert(out.end(), args.begin() + static_cast<std::ptrdiff_t>(i), args.end());
            break;
        }
        if (a.size() < 2 || a[0] != '-' || a[1] == '-') {
            out.push_back(a);
            if (long_takes_value(a) && i + 1 < args.size()) out.push_back(args[++i]);
            continue;
        }
        for (std::size_t j = 1; j < a.size();) {
            if (is_digit(a[j])) {
                std::size_t k = j;
                while (k < a.size() && is_digit(a[k])) ++k;
                out.push_back("-L");
                out.push_back(a.substr(j, k - j));
                j = k;
                continue;
            }
            out.push_back(std::string("-") + a[j]);
            if (short_takes_value(a[j])) {
                if (j + 1 < a.size()) out.push_back(a.substr(j + 1));
                else if (i + 1 < args.size()) out.push_back(args[++i]);
                break;
            }
            ++j;
        }
    }
    // -c and -o: the last one wins. Positions of the -o pairs and -c flags
    // before "--".
    std::ptrdiff_t last = -1;
    const auto end = std::find(out.begin(), out.end(), "--");
    for (auto it = out.begin(); it != end; ++it) {
        const std::string& a = *it;
        if (a == "-c" || a == "--stdout" || a == "-o" || a == "--output" || a.rfind("--output=", 0) == 0)
            last = it - out.begin();
        if ((a == "-o" || a == "--output" || long_takes_value(a) || a == "-L" || a == "-T") &&
            it + 1 != end)
            ++it;
    }
    if (last < 0) return out;
    std::vector<std::string> kept;
    for (std::size_t i = 0; i < out.size(); ++i) {
        const std::string& a = out[i];
        if (a == "--") {
            kept.insert(kept.end(), out.begin() + static_cast<std::ptrdiff_t>(i), out.end());
            break;
        }
        const bool value_next = (a == "-o" || a == "--output" || long_takes_value(a) || a == "-L" ||
                                 a == "-T") && i + 1 < out.size();
        const bool sink = a == "-c" || a == "--stdout" || a == "-o" || a == "--output" ||
                          a.rfind("--output=", 0) == 0;
        if (sink && static_cast<std::ptrdiff_t>(i) != last) {
            if (value_next) ++i;
            continue;
        }
        kept.push_back(a);
        if (value_next) kept.push_back(out[++i]);
    }
    return kept;
}

std::string take_zstd_mode(std::vector<std::string>& args) {
    std::string mode = "compress";
    std::vector<std::string> rest;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "--") {
            rest.insert(rest.end(), args.begin() + static_cast<std::ptrdiff_t>(i), args.end());
            break;
        }
        if (a == "-z" || a == "--compress") mode = "compress";
        else if (a == "-d" || a == "--decompress" || a == "--uncompress") mode = "decompress";
        else if (a == "-t" || a == "--test") mode = "verify";
        else if (a == "-l" || a == "--list") mode = "info";
        else {
            rest.push_back(a);
            if ((a == "-o" || a == "-L" || a == "-T" || long_takes_value(a)) && i + 1 < args.size())
                rest.push_back(args[++i]);
        }
    }
    args = std::move(rest);
    return mode;
}

}  // namespace stepzip::cli
