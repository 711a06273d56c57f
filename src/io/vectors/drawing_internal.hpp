// Shared by the writers that turn cut chains into vector drawings.
// Internal to src/io/vectors.
#pragma once

#include <cstddef>
#include <string>

#include "stepzip/error.hpp"

namespace stepzip {

/// The error for chain `index` (0-based) of `axes` axes, which a vector
/// drawing (two axes only) cannot hold.
inline Error not_two_axis(std::size_t index, int axes) {
    return make_error(Errc::unsupported, "chain " + std::to_string(index + 1) + " has " + std::to_string(axes) +
                                             " axes; vector output needs two-axis chains");
}

}  // namespace stepzip
