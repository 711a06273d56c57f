// Helpers of the pinned-bytes tests (container_format_bytes_test.cpp,
// container_mix_test.cpp): a block from Freeman text, its greedy cut, and
// bytes as hex.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <vector>

#include "../../src/container/block_codec.hpp"
#include "stepzip/document.hpp"
#include "stepzip/segmenter.hpp"

namespace stepzip::stz {

/// "01 ab ..." (lower-case, one space between bytes).
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

}  // namespace stepzip::stz
