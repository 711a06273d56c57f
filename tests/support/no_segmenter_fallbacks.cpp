// Linked into every test executable: after the tests have run, fails the run
// when any segmenter took its fallback (a recognizer claimed a prefix that no
// segment fits). The fallback keeps the output exact, so without this check a
// recognizer that accepts too much would pass every round-trip test in a
// release build (src/segment/internal.hpp, segmenter_fallbacks()).
#include <gtest/gtest.h>

#include "../../src/segment/internal.hpp"

namespace {

class NoSegmenterFallbacks : public ::testing::Environment {
public:
    void TearDown() override {
        EXPECT_EQ(stepzip::segmenter_fallbacks(), 0u)
            << "a segmenter fell back to a shorter cut: some recognizer accepts a prefix "
               "that no segment fits";
    }
};

[[maybe_unused]] ::testing::Environment* const kRegistered =
    ::testing::AddGlobalTestEnvironment(new NoSegmenterFallbacks);

}  // namespace
