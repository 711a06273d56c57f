// stepzip command line: streaming input for compress, decompress, verify and
// info (files of many GB are read in pieces, never whole). Header-only;
// complements cli_common.hpp, whose read_input() loads a whole input.
#pragma once

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <optional>
#include <string>

#include "cli_common.hpp"
#include "stepzip/container.hpp"

namespace stepzip::cli {

/// An input file (or standard input for "-" / empty) read piece by piece.
class InputStream {
public:
    InputStream() = default;
    ~InputStream() {
        if (fd_ > STDIN_FILENO) ::close(fd_);
    }
    InputStream(const InputStream&) = delete;
    InputStream& operator=(const InputStream&) = delete;

    /// Opens `path`. Errors: Errc::io "PATH: <reason>".
    Result<void> open(const std::string& path) {
        name_ = input_name(path);
        fd_ = is_dash(path) ? STDIN_FILENO : ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd_ < 0) return make_error(Errc::io, name_ + ": " + std::strerror(errno));
        struct stat st {};
        if (::fstat(fd_, &st) == 0) {
            if (S_ISDIR(st.st_mode)) return make_error(Errc::io, name_ + ": is a directory");
            if (S_ISREG(st.st_mode)) {
                size_ = static_cast<std::uint64_t>(st.st_size);
                if (!is_dash(path)) stat_ = st;
            }
        }
        return {};
    }

    /// Fills `buf` as far as the input allows (short only at the end).
    Result<std::size_t> read(char* buf, std::size_t cap) {
        std::size_t got = 0;
        while (got < cap) {
            const ssize_t n = ::read(fd_, buf + got, cap - got);
            if (n == 0) break;
            if (n < 0) {
                if (errno == EINTR) continue;
                return make_error(Errc::io, name_ + ": " + std::strerror(errno));
            }
            got += static_cast<std::size_t>(n);
        }
        return got;
    }

    /// A ReadFn over this stream.
    ReadFn reader() {
        return [this](char* buf, std::size_t cap) { return read(buf, cap); };
    }

    const std::string& name() const noexcept { return name_; }
    /// Size of a regular file, 0 when unknown.
    std::uint64_t size() const noexcept { return size_; }
    /// The status of a named regular file (mode, owner, times); nullopt for
    /// standard input and anything else.
    const std::optional<struct stat>& file_status() const noexcept { return stat_; }

private:
    int fd_ = -1;
    std::string name_;
    std::uint64_t size_ = 0;
    std::optional<struct stat> stat_;
};

}  // namespace stepzip::cli
