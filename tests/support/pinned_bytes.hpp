// Helpers of the pinned-bytes tests: bytes as "0a 1b ..." hex and back, the
// first whole chains of a corpus file as one block, a block of Freeman text
// and its greedy cut.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <cstdint>
#include <vector>

#include "stepzip/document.hpp"
#include "stepzip/segmenter.hpp"

namespace stepzip::test {

inline std::string hex(std::string_view b) {
    static const char* digits = "0123456789abcdef";
    std::string s;
    for (unsigned char c : b) {
        if (!s.empty()) s += ' ';
        s += digits[c >> 4];
        s += digits[c & 15];
    }
    return s;
}

inline std::string unhex(std::string_view h) {
    std::string out;
    for (std::size_t i = 0; i + 1 < h.size(); i += 3)
        out.push_back(static_cast<char>(std::stoi(std::string(h.substr(i, 2)), nullptr, 16)));
    return out;
}

/// The whole chains of `text` (in `format`) that fit in `max_steps` steps,
/// as one block on the first chain's axes (two when there is none).
inline Block block_of(InputFormat format, const std::string& text, std::size_t max_steps = SIZE_MAX,
                      const char* source = "test") {
    auto chains = read_chains(format, text, source);
    EXPECT_TRUE(chains.ok()) << source;
    Block b;
    b.axes = chains.ok() && !chains->empty() ? (*chains)[0].axes : 2;
    std::size_t total = 0;
    if (chains.ok())
        for (Chain& c : *chains) {
            if (total + c.steps.size() > max_steps) break;
            total += c.steps.size();
            b.chains.push_back(std::move(c));
        }
    return b;
}

/// The whole chains of corpora/`rel` (Freeman) that fit in `max_steps`
/// steps, as one block; they are expected to fill at least half of it.
inline Block corpus_block(const char* rel, std::size_t max_steps) {
    std::ifstream f(std::filesystem::path(STEPZIP_SOURCE_DIR) / "corpora" / rel, std::ios::binary);
    std::ostringstream text;
    text << f.rdbuf();
    Block b = block_of(InputFormat::freeman, text.str(), max_steps, rel);
    std::size_t total = 0;
    for (const Chain& c : b.chains) total += c.steps.size();
    EXPECT_GT(total, max_steps / 2) << rel;
    return b;
}

/// A two-axis block of the chains of `freeman` (Freeman chain text).
inline Block fixed_block(std::string_view freeman) {
    auto chains = read_chains(InputFormat::freeman, freeman, "pinned");
    EXPECT_TRUE(chains.ok());
    Block b;
    b.axes = 2;
    if (chains.ok()) b.chains = *chains;
    return b;
}

/// The greedy cut of every chain of `b` under `p`.
inline std::vector<std::vector<Segment>> greedy_cut(const Block& b, Profile p) {
    std::vector<std::vector<Segment>> segs(b.chains.size());
    for (std::size_t i = 0; i < b.chains.size(); ++i)
        EXPECT_TRUE(segment_steps(b.chains[i].steps, 2, p, SegmenterKind::greedy, segs[i]).ok());
    return segs;
}

}  // namespace stepzip::test
