#include "stepzip/error.hpp"

namespace stepzip {

const char* errc_name(Errc code) noexcept {
    switch (code) {
        case Errc::ok: return "ok";
        case Errc::invalid_argument: return "invalid argument";
        case Errc::unsupported: return "unsupported";
        case Errc::syntax: return "syntax";
        case Errc::not_a_step: return "not a step";
        case Errc::connectivity: return "connectivity";
        case Errc::bad_magic: return "bad magic";
        case Errc::bad_version: return "bad version";
        case Errc::corrupt: return "corrupt";
        case Errc::truncated: return "truncated";
        case Errc::reserved_bits: return "reserved bits";
        case Errc::checksum: return "checksum";
        case Errc::limit: return "limit";
        case Errc::overflow: return "overflow";
        case Errc::io: return "i/o";
        case Errc::mismatch: return "mismatch";
    }
    return "unknown";
}

}  // namespace stepzip
