// libFuzzer entry point for one target of fuzz/targets.hpp; the target's
// name comes from the build (STEPZIP_FUZZ_TARGET). A violated property is
// reported on stderr and aborts, which libFuzzer records as a crash and
// saves the input.
#include <cstdio>
#include <cstdlib>

#include "targets.hpp"

#ifndef STEPZIP_FUZZ_TARGET
#error "define STEPZIP_FUZZ_TARGET to a target name"
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto failure = stepzip::fuzz::run_target(STEPZIP_FUZZ_TARGET, data, size);
    if (!failure) {
        std::fprintf(stderr, "unknown fuzz target %s\n", STEPZIP_FUZZ_TARGET);
        std::abort();
    }
    if (!failure->empty()) {
        std::fprintf(stderr, "fuzz target %s: %s\n", STEPZIP_FUZZ_TARGET, failure->c_str());
        std::abort();
    }
    return 0;
}
