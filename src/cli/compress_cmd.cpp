// stepzip compress (not built yet).
#include <cstdio>

#include "commands.hpp"

namespace stepzip::cli {

int cmd_compress(const std::vector<std::string>&) {
    std::fprintf(stderr, "stepzip compress: not built yet\n");
    return 1;
}

}  // namespace stepzip::cli
