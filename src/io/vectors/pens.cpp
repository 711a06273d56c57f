// stepzip — pens in chain files: "# pen N" comment lines before the chains
// drawn with pen N (what `stepzip interpolate` writes for HP-GL with pens
// and `stepzip segment` reads back).
#include <cstdlib>
#include <string>

#include "stepzip/vectors.hpp"

namespace stepzip {

namespace {

// The pen named by a "# pen N" line, or -1.
int pen_comment(std::string_view line) {
    std::size_t i = 0;
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::string_view tag = "# pen ";
    if (line.substr(i, tag.size()) != tag) return -1;
    i += tag.size();
    int pen = 0;
    std::size_t digits = 0;
    while (i < line.size() && line[i] >= '0' && line[i] <= '9' && digits < 7) {
        pen = pen * 10 + (line[i] - '0');
        ++i;
        ++digits;
    }
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    return digits > 0 && i == line.size() ? pen : -1;
}

bool blank(std::string_view line) {
    for (const char c : line)
        if (c != ' ' && c != '\t' && c != '\r') return false;
    return true;
}

}  // namespace

Result<std::string> write_chains_with_pens(InputFormat format, const std::vector<Chain>& chains,
                                           const std::vector<int>& pens) {
    bool plain = true;
    for (const int p : pens) plain = plain && p == 1;
    if (plain) return write_chains(format, chains);
    if (format == InputFormat::steps)
        return make_error(Errc::unsupported, "a steps file cannot carry pens");
    std::string out;
    for (std::size_t i = 0; i < chains.size();) {
        std::size_t j = i;
        while (j < chains.size() && pens[j] == pens[i]) ++j;
        auto text = write_chains(format, std::vector<Chain>(chains.begin() + static_cast<std::ptrdiff_t>(i),
                                                            chains.begin() + static_cast<std::ptrdiff_t>(j)));
        if (!text) return text;
        if (format == InputFormat::points && i > 0) out += "\n";  // the blank line ends a chain
        out += "# pen " + std::to_string(pens[i]) + "\n" + *text;
        i = j;
    }
    return out;
}

std::vector<int> chain_pens(InputFormat format, std::string_view text) {
    std::vector<int> pens;
    int pen = 1;
    bool in_chain = false;  // points: inside a chain (until a blank line)
    for (std::size_t begin = 0; begin < text.size();) {
        std::size_t end = text.find('\n', begin);
        if (end == std::string_view::npos) end = text.size();
        const std::string_view line = text.substr(begin, end - begin);
        begin = end + 1;
        if (const int p = pen_comment(line); p >= 0) {
            pen = p;
            continue;
        }
        std::size_t i = 0;
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
        if (i < line.size() && line[i] == '#') continue;
        if (blank(line)) {
            in_chain = false;
            continue;
        }
        if (format == InputFormat::freeman || !in_chain) pens.push_back(pen);
        in_chain = true;
    }
    return pens;
}

}  // namespace stepzip
