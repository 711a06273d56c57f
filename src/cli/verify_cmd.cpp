// stepzip verify (not built yet).
#include <cstdio>

#include "commands.hpp"

namespace stepzip::cli {

int cmd_verify(const std::vector<std::string>&) {
    std::fprintf(stderr, "stepzip verify: not built yet\n");
    return 1;
}

}  // namespace stepzip::cli
