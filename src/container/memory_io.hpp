// In-memory ends for the streaming codec: a ReadFn over a byte string and a
// WriteFn appending to a string. Internal to src/container.
#pragma once

#include <algorithm>
#include <string>
#include <string_view>

#include "stepzip/container.hpp"

namespace stepzip::stz {

/// Reads `bytes` from the start, in pieces of at most the requested size.
/// The returned function refers to `bytes`, which must outlive it.
inline ReadFn memory_reader(std::string_view bytes) {
    return [bytes, pos = std::size_t{0}](char* buf, std::size_t cap) mutable -> Result<std::size_t> {
        const std::size_t n = std::min(cap, bytes.size() - pos);
        std::copy_n(bytes.data() + pos, n, buf);
        pos += n;
        return n;
    };
}

/// Appends everything written to `out`, which must outlive the function.
inline WriteFn string_writer(std::string& out) {
    return [&out](std::string_view b) -> Result<void> {
        out += b;
        return {};
    };
}

}  // namespace stepzip::stz
