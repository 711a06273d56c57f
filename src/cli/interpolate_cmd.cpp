// stepzip interpolate: vectors -> steps. (Placeholder until the vector
// readers land; reports that the command is not available yet.)
#include <cstdio>

#include "commands.hpp"

namespace stepzip::cli {

int cmd_interpolate(const std::vector<std::string>&) {
    std::fprintf(stderr, "stepzip interpolate: not built yet\n");
    return 1;
}

}  // namespace stepzip::cli
