// Helper of the container tests: the block records of a one-frame
// version-2 file, walked with the library's varint reader.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "../../src/common/bytes.hpp"
#include "../../src/container/block_codec.hpp"

namespace stepzip::test {

struct BlockRecord {
    unsigned type = 0;         ///< block type (bits 0-2 of the block byte)
    std::string_view payload;  ///< the payload (before zstd for types 1 and 2)
};

/// The block records of `frame` (one version-2 frame), up to the end mark
/// or the first record that does not parse.
inline std::vector<BlockRecord> block_records(std::string_view frame) {
    wire::Cursor cur(frame.substr(8));  // after the frame header
    std::vector<BlockRecord> out;
    unsigned first = 0;
    std::uint64_t csize = 0, dsize = 0;
    while (cur.u8(first) && first != 0 && cur.varint(csize)) {
        const unsigned type = first & 7u;
        if ((type == stz::kChains || type == stz::kRaw) && !cur.varint(dsize)) break;
        std::string_view payload, check;
        if (!cur.bytes(static_cast<std::size_t>(csize), payload) || !cur.bytes(4, check)) break;  // payload, block checksum
        out.push_back({type, payload});
    }
    return out;
}

}  // namespace stepzip::test
