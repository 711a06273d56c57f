// stepzip — library version (independent of the .stz format version).
#pragma once

namespace stepzip {

inline constexpr int kVersionMajor = 0;
inline constexpr int kVersionMinor = 1;
inline constexpr int kVersionPatch = 0;

/// "MAJOR.MINOR.PATCH" of the library.
constexpr const char* version_string() noexcept { return "0.1.0"; }

}  // namespace stepzip
