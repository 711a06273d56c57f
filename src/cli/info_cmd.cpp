// stepzip info (not built yet).
#include <cstdio>

#include "commands.hpp"

namespace stepzip::cli {

int cmd_info(const std::vector<std::string>&) {
    std::fprintf(stderr, "stepzip info: not built yet\n");
    return 1;
}

}  // namespace stepzip::cli
