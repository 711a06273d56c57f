// Replays every input in tests/regressions/<target>/ (inputs that once made a
// fuzz target fail) and every fuzz seed in fuzz/seeds/<target>/ through the
// same target functions the fuzzers run (fuzz/targets.hpp), without
// libFuzzer: each must now satisfy all of the target's properties.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "../fuzz/targets.hpp"

namespace stepzip {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}

// Runs every file under `root`/<target>/; returns how many ran.
int replay(const fs::path& root) {
    int ran = 0;
    for (std::string_view target : fuzz::kTargets) {
        const fs::path dir = root / target;
        if (!fs::is_directory(dir)) continue;
        for (const auto& entry : fs::directory_iterator(dir)) {
            if (!entry.is_regular_file()) continue;
            const std::string bytes = slurp(entry.path());
            const auto failure = fuzz::run_target(
                target, reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
            EXPECT_EQ(failure.value_or("unknown target"), "") << entry.path();
            ++ran;
        }
    }
    return ran;
}

TEST(HardeningRegressions, EveryRecordedFailingInputNowPasses) {
    // The directory holds three recorded inputs (see its README.md); a
    // missing or emptied directory must fail here, not pass with nothing run.
    const fs::path root = fs::path(STEPZIP_SOURCE_DIR) / "tests" / "regressions";
    ASSERT_TRUE(fs::is_directory(root)) << root;
    EXPECT_GE(replay(root), 3) << "recorded regression inputs went missing from " << root;
}

TEST(HardeningRegressions, EveryFuzzSeedPasses) {
    EXPECT_GT(replay(fs::path(STEPZIP_SOURCE_DIR) / "fuzz" / "seeds"), 20);
}

TEST(HardeningRegressions, TargetsRejectNothingOnTrivialInputs) {
    for (std::string_view target : fuzz::kTargets) {
        for (std::string_view bytes : {std::string_view(), std::string_view("\0", 1),
                                       std::string_view("\x05\x00\x00\x00\x00", 5)}) {
            const auto failure = fuzz::run_target(
                target, reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
            ASSERT_TRUE(failure.has_value()) << target;
            EXPECT_EQ(*failure, "") << target;
        }
    }
}

}  // namespace
}  // namespace stepzip
