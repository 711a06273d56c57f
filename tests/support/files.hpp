// Helper of the tests: a file's bytes, and a file of corpora/ (which must
// not be empty).
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace stepzip::test {

/// The bytes of the file at `p` (empty when it cannot be read).
inline std::string slurp(const std::filesystem::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}

/// corpora/`rel` of the source tree; a test expectation fails when it is empty.
inline std::string corpus(const char* rel) {
    std::string s = slurp(std::filesystem::path(STEPZIP_SOURCE_DIR) / "corpora" / rel);
    EXPECT_FALSE(s.empty()) << rel;
    return s;
}

}  // namespace stepzip::test
