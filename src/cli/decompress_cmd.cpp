// stepzip decompress (not built yet).
#include <cstdio>

#include "commands.hpp"

namespace stepzip::cli {

int cmd_decompress(const std::vector<std::string>&) {
    std::fprintf(stderr, "stepzip decompress: not built yet\n");
    return 1;
}

}  // namespace stepzip::cli
