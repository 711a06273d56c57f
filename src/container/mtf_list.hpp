// A short move-to-front list of ids (at most N, most recent first), used by
// the segment model's and the table block's successor lists. Internal to
// src/container.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace stepzip::stz {

template <std::size_t N>
struct MtfList {
    std::array<std::uint32_t, N> id{};
    std::uint32_t size = 0;
    /// Moves `s` to the front (inserting it, and dropping the last id when full).
    void use(std::uint32_t s) {
        std::uint32_t k = 0;
        while (k < size && id[k] != s) ++k;
        if (k == size) {
            if (size < N) ++size;
            k = size - 1;
        }
        for (; k > 0; --k) id[k] = id[k - 1];
        id[0] = s;
    }
};

}  // namespace stepzip::stz
