// Helper of the tests: a frame compressed and checked to decompress to its
// input, as a caller of the library would check it.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "stepzip/container.hpp"

namespace stepzip::test {

/// `input` compressed with `opt`; a test expectation fails, and the result
/// is empty, when compression fails or the frame does not decompress to
/// `input`.
inline std::string compress_proved(const std::string& input, const CompressOptions& opt) {
    auto z = compress(input, opt);
    EXPECT_TRUE(z.ok()) << z.error().message;
    if (!z.ok()) return {};
    auto back = decompress(*z);
    EXPECT_TRUE(back.ok()) << back.error().message;
    if (!back.ok() || *back != input) {
        ADD_FAILURE() << "level " << opt.level << ": the frame does not decompress to its input";
        return {};
    }
    return std::move(*z);
}

}  // namespace stepzip::test
