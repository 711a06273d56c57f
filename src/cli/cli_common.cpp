// stepzip command line: shared input/output helpers (see cli_common.hpp).
#include "cli_common.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

namespace stepzip::cli {

namespace {

Error io_error(std::string_view name, int err) {
    return make_error(Errc::io, std::string(name) + ": " + std::strerror(err));
}

// The directory part of `path` ("." when it has none) and the base name.
std::pair<std::string, std::string> split_path(const std::string& path) {
    const auto slash = path.find_last_of('/');
    if (slash == std::string::npos) return {".", path};
    return {slash == 0 ? "/" : path.substr(0, slash), path.substr(slash + 1)};
}

}  // namespace

bool is_dash(std::string_view path) noexcept { return path.empty() || path == "-"; }

std::string input_name(std::string_view path) {
    return is_dash(path) ? std::string("<stdin>") : std::string(path);
}

Result<std::string> read_input(const std::string& path) {
    const bool stdin_input = is_dash(path);
    const std::string name = input_name(path);
    int fd = stdin_input ? STDIN_FILENO : ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return io_error(name, errno);
    struct stat st {};
    if (::fstat(fd, &st) == 0 && S_ISDIR(st.st_mode)) {
        if (!stdin_input) ::close(fd);
        return make_error(Errc::io, name + ": is a directory");
    }
    std::string data;
    if (S_ISREG(st.st_mode) && st.st_size > 0) data.reserve(static_cast<std::size_t>(st.st_size));
    char buf[1 << 16];
    for (;;) {
        const ssize_t n = ::read(fd, buf, sizeof buf);
        if (n == 0) break;
        if (n < 0) {
            if (errno == EINTR) continue;
            const int err = errno;
            if (!stdin_input) ::close(fd);
            return io_error(name, err);
        }
        data.append(buf, static_cast<std::size_t>(n));
    }
    if (!stdin_input) ::close(fd);
    return data;
}

bool is_terminal(std::FILE* stream) noexcept { return ::isatty(::fileno(stream)) == 1; }

int report(const Error& error) {
    std::fprintf(stderr, "stepzip: %s\n", error.message.c_str());
    return 1;
}

int usage_error(std::string_view message) {
    std::fprintf(stderr, "stepzip: %.*s (try 'stepzip COMMAND --help')\n",
                 static_cast<int>(message.size()), message.data());
    return 2;
}

void note(std::string_view message) {
    std::fprintf(stderr, "stepzip: %.*s\n", static_cast<int>(message.size()), message.data());
}

// ---------------------------------------------------------------- OutputFile

OutputFile::~OutputFile() { discard(); }

OutputFile::OutputFile(OutputFile&& other) noexcept
    : target_(std::move(other.target_)),
      temp_(std::move(other.temp_)),
      file_(std::exchange(other.file_, nullptr)),
      to_stdout_(other.to_stdout_),
      done_(std::exchange(other.done_, true)) {}

OutputFile& OutputFile::operator=(OutputFile&& other) noexcept {
    if (this != &other) {
        discard();
        target_ = std::move(other.target_);
        temp_ = std::move(other.temp_);
        file_ = std::exchange(other.file_, nullptr);
        to_stdout_ = other.to_stdout_;
        done_ = std::exchange(other.done_, true);
    }
    return *this;
}

void OutputFile::discard() noexcept {
    if (file_ && !to_stdout_) {
        std::fclose(file_);
        if (!done_ && !temp_.empty()) ::unlink(temp_.c_str());
    }
    file_ = nullptr;
}

Result<OutputFile> OutputFile::open(const std::string& path, bool force) {
    OutputFile out;
    if (is_dash(path)) {
        out.target_ = "<stdout>";
        out.file_ = stdout;
        out.to_stdout_ = true;
        return out;
    }
    out.target_ = path;
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0) {
        if (S_ISDIR(st.st_mode)) return make_error(Errc::io, path + ": is a directory");
        if (!force) return make_error(Errc::io, path + ": already exists (use -f to overwrite)");
    }
    const auto [dir, base] = split_path(path);
    std::string temp = dir + "/." + base + ".stepzip-XXXXXX";
    const int fd = ::mkstemp(temp.data());
    if (fd < 0) return io_error(path, errno);
    // mkstemp creates the file 0600; give it the mode a plain open() would.
    const mode_t mask = ::umask(0);
    ::umask(mask);
    ::fchmod(fd, 0666 & ~mask);
    out.file_ = ::fdopen(fd, "wb");
    if (!out.file_) {
        const int err = errno;
        ::close(fd);
        ::unlink(temp.c_str());
        return io_error(path, err);
    }
    out.temp_ = std::move(temp);
    return out;
}

Result<void> OutputFile::write(std::string_view data) {
    if (!file_ || done_) return make_error(Errc::io, target_ + ": output is closed");
    if (!data.empty() && std::fwrite(data.data(), 1, data.size(), file_) != data.size())
        return io_error(target_, errno);
    return {};
}

Result<void> OutputFile::commit() {
    if (!file_ || done_) return make_error(Errc::io, target_ + ": output is closed");
    if (std::fflush(file_) != 0) return io_error(target_, errno);
    if (to_stdout_) {
        done_ = true;
        return {};
    }
    if (::fsync(::fileno(file_)) != 0) return io_error(target_, errno);
    if (std::fclose(file_) != 0) {
        const int err = errno;
        file_ = nullptr;
        ::unlink(temp_.c_str());
        return io_error(target_, err);
    }
    file_ = nullptr;
    if (::rename(temp_.c_str(), target_.c_str()) != 0) {
        const int err = errno;
        ::unlink(temp_.c_str());
        return io_error(target_, err);
    }
    done_ = true;
    return {};
}

// ------------------------------------------------------------------ Progress

Progress::Progress(std::string label, std::uint64_t total, bool enabled)
    : label_(std::move(label)), total_(total), active_(enabled && is_terminal(stderr)) {}

Progress::~Progress() { finish(); }

void Progress::update(std::uint64_t done) {
    if (!active_) return;
    const auto now = std::chrono::steady_clock::now();
    if (shown_ && now - last_ < std::chrono::milliseconds(250)) return;
    last_ = now;
    shown_ = true;
    if (total_ > 0) {
        const unsigned pct = static_cast<unsigned>(done >= total_ ? 100 : done * 100 / total_);
        std::fprintf(stderr, "\r%s: %3u%%", label_.c_str(), pct);
    } else {
        std::fprintf(stderr, "\r%s: %llu", label_.c_str(), static_cast<unsigned long long>(done));
    }
    std::fflush(stderr);
}

void Progress::finish() {
    if (active_ && shown_) {
        std::fprintf(stderr, "\r\033[K");
        std::fflush(stderr);
    }
    shown_ = false;
    active_ = false;
}

}  // namespace stepzip::cli
