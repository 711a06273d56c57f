// stepzip segment (not built yet).
#include <cstdio>

#include "commands.hpp"

namespace stepzip::cli {

int cmd_segment(const std::vector<std::string>&) {
    std::fprintf(stderr, "stepzip segment: not built yet\n");
    return 1;
}

}  // namespace stepzip::cli
