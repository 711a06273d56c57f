#include "options.hpp"

#include <algorithm>
#include <iostream>
#include <optional>

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

// One command-line item: an option with its value, "--", or a positional
// argument (`positional`; everything after "--" is positional).
struct Item {
    std::string text;
    std::optional<std::string> value;
    bool positional = false;
};

// Splits zstd-style arguments into items (see split_zstd_options).
std::vector<Item> tokenize(const std::vector<std::string>& args) {
    std::vector<Item> items;
    bool options_end = false;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        const auto next = [&]() -> std::optional<std::string> {
            if (i + 1 < args.size()) return args[++i];
            return std::nullopt;
        };
        if (options_end || a.size() < 2 || a[0] != '-') {
            items.push_back({a, std::nullopt, true});
        } else if (a == "--") {
            items.push_back({a, std::nullopt});
            options_end = true;
        } else if (a[1] == '-') {
            items.push_back({a, long_takes_value(a) ? next() : std::nullopt});
        } else {
            for (std::size_t j = 1; j < a.size();) {
                if (is_digit(a[j])) {  // -# is the level
                    std::size_t k = j;
                    while (k < a.size() && is_digit(a[k])) ++k;
                    items.push_back({"-L", a.substr(j, k - j)});
                    j = k;
                } else if (short_takes_value(a[j])) {  // the rest, or the next argument
                    items.push_back({std::string("-") + a[j],
                                     j + 1 < a.size() ? std::optional(a.substr(j + 1)) : next()});
                    break;
                } else {
                    items.push_back({std::string("-") + a[j], std::nullopt});
                    ++j;
                }
            }
        }
    }
    return items;
}

std::vector<std::string> flatten(const std::vector<Item>& items) {
    std::vector<std::string> out;
    for (const Item& it : items) {
        out.push_back(it.text);
        if (it.value) out.push_back(*it.value);
    }
    return out;
}

bool is_sink(const Item& it) {
    return !it.positional && (it.text == "-c" || it.text == "--stdout" || it.text == "-o" ||
                              it.text == "--output" || it.text.rfind("--output=", 0) == 0);
}

}  // namespace

std::vector<std::string> split_zstd_options(const std::vector<std::string>& args) {
    std::vector<Item> items = tokenize(args);
    // Of -c and -o, the last one wins.
    const auto last = std::find_if(items.rbegin(), items.rend(), is_sink);
    if (last != items.rend()) {
        Item keep = *last;
        std::erase_if(items, is_sink);
        items.insert(items.begin(), std::move(keep));  // before any "--"
    }
    return flatten(items);
}

std::string take_zstd_mode(std::vector<std::string>& args) {
    std::string mode = "compress";
    std::vector<Item> items = tokenize(args);
    std::vector<Item> rest;
    for (Item& it : items) {
        const std::string_view t = it.positional ? std::string_view() : std::string_view(it.text);
        if (t == "-z" || t == "--compress") mode = "compress";
        else if (t == "-d" || t == "--decompress" || t == "--uncompress") mode = "decompress";
        else if (t == "-t" || t == "--test") mode = "test";
        else if (t == "-l" || t == "--list") mode = "info";
        else rest.push_back(std::move(it));
    }
    items = std::move(rest);
    args = flatten(items);
    return mode;
}

}  // namespace stepzip::cli
