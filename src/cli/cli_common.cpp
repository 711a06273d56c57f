// stepzip command line: shared input/output helpers (see cli_common.hpp).
#include "cli_common.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <mutex>
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

// Temporary files to remove if a signal ends the program. A slot holds a
// heap copy of the path (never moved while registered), so the handler only
// loads pointers and calls unlink(), both async-signal-safe.
constexpr int kSignalSlots = 16;
std::atomic<char*> g_temp_files[kSignalSlots];
constexpr int kCleanupSignals[] = {SIGINT, SIGTERM, SIGHUP};

extern "C" void remove_temp_files_and_die(int sig) {
    for (auto& slot : g_temp_files)
        if (char* path = slot.load()) ::unlink(path);
    static const char msg[] = "stepzip: interrupted by a signal; partial output removed\n";
    [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, msg, sizeof msg - 1);
    ::signal(sig, SIG_DFL);
    ::raise(sig);
}

void install_signal_handlers() {
    static std::once_flag once;
    std::call_once(once, [] {
        for (int sig : kCleanupSignals) {
            struct sigaction old {};
            if (::sigaction(sig, nullptr, &old) != 0 || old.sa_handler == SIG_IGN) continue;
            struct sigaction sa {};
            sa.sa_handler = remove_temp_files_and_die;
            sigemptyset(&sa.sa_mask);
            for (int s : kCleanupSignals) sigaddset(&sa.sa_mask, s);
            ::sigaction(sig, &sa, nullptr);
        }
    });
}

// Registers `path` for removal on a signal; returns the slot, or -1 when all
// slots are taken (the file is then only removed by the destructor).
int register_temp_file(const std::string& path) {
    install_signal_handlers();
    char* copy = ::strdup(path.c_str());
    if (!copy) return -1;
    for (int i = 0; i < kSignalSlots; ++i) {
        char* expected = nullptr;
        if (g_temp_files[i].compare_exchange_strong(expected, copy)) return i;
    }
    std::free(copy);
    return -1;
}

void unregister_temp_file(int slot) noexcept {
    if (slot < 0) return;
    std::free(g_temp_files[slot].exchange(nullptr));
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

std::optional<Error> console_stdin_refused(const std::vector<std::string>& inputs, bool force) {
    if (force || !is_terminal(stdin)) return std::nullopt;
    if (std::none_of(inputs.begin(), inputs.end(), [](const std::string& p) { return is_dash(p); }))
        return std::nullopt;
    return make_error(Errc::io, "stdin is a console, aborting (pipe or name an input, -f reads "
                                "the terminal; 'stepzip --help' lists the commands)");
}

bool has_suffix(std::string_view path, std::string_view suffix) noexcept {
    return path.size() > suffix.size() &&
           path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0;
}

namespace {

Result<void> walk_directory(const std::string& dir,
                            const std::function<bool(const std::string&)>& wanted,
                            std::vector<std::string>& out) {
    DIR* d = ::opendir(dir.c_str());
    if (!d) return io_error(dir, errno);
    std::vector<std::string> names;
    while (const dirent* e = ::readdir(d)) {
        const std::string_view n = e->d_name;
        if (n != "." && n != "..") names.emplace_back(n);
    }
    ::closedir(d);
    std::sort(names.begin(), names.end());
    for (const std::string& n : names) {
        const std::string path = dir.back() == '/' ? dir + n : dir + "/" + n;
        struct stat st {};
        if (::lstat(path.c_str(), &st) != 0) return io_error(path, errno);
        if (S_ISDIR(st.st_mode)) {
            if (auto r = walk_directory(path, wanted, out); !r) return r;
        } else if (S_ISREG(st.st_mode) && wanted(path)) {
            out.push_back(path);
        }
    }
    return {};
}

}  // namespace

Result<std::vector<std::string>> expand_directories(
    const std::vector<std::string>& inputs, const std::function<bool(const std::string&)>& wanted) {
    std::vector<std::string> out;
    for (const std::string& in : inputs) {
        struct stat st {};
        if (!is_dash(in) && ::stat(in.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) {
            if (auto r = walk_directory(in, wanted, out); !r) return std::move(r).error();
        } else {
            out.push_back(in);
        }
    }
    return out;
}

std::string format_size(std::uint64_t bytes) {
    static constexpr const char* kUnits[] = {"KiB", "MiB", "GiB", "TiB"};
    if (bytes < 1024) return std::to_string(bytes) + " B";
    double v = static_cast<double>(bytes) / 1024;
    int unit = 0;
    while (v >= 1024 && unit < 3) {
        v /= 1024;
        ++unit;
    }
    char buf[32];
    std::snprintf(buf, sizeof buf, v < 10 ? "%.2f %s" : v < 100 ? "%.1f %s" : "%.0f %s", v,
                  kUnits[unit]);
    return buf;
}

int report(const Error& error) {
    std::fprintf(stderr, "stepzip: %s\n", error.message.c_str());
    return 1;
}

int usage_error(std::string_view message) {
    // messages start with the subcommand's name: "compress: ..."
    const std::size_t colon = message.find(':');
    const std::string_view command =
        colon == std::string_view::npos ? std::string_view("COMMAND") : message.substr(0, colon);
    std::fprintf(stderr, "stepzip: %.*s (try 'stepzip %.*s --help')\n",
                 static_cast<int>(message.size()), message.data(),
                 static_cast<int>(command.size()), command.data());
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
      signal_slot_(std::exchange(other.signal_slot_, -1)),
      to_stdout_(other.to_stdout_),
      direct_(other.direct_),
      done_(std::exchange(other.done_, true)) {}

OutputFile& OutputFile::operator=(OutputFile&& other) noexcept {
    if (this != &other) {
        discard();
        target_ = std::move(other.target_);
        temp_ = std::move(other.temp_);
        file_ = std::exchange(other.file_, nullptr);
        signal_slot_ = std::exchange(other.signal_slot_, -1);
        to_stdout_ = other.to_stdout_;
        direct_ = other.direct_;
        done_ = std::exchange(other.done_, true);
    }
    return *this;
}

void OutputFile::discard() noexcept {
    if (file_ && !to_stdout_) {
        std::fclose(file_);
        if (!done_ && !temp_.empty()) ::unlink(temp_.c_str());
    }
    unregister_temp_file(std::exchange(signal_slot_, -1));
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
        if (!S_ISREG(st.st_mode)) {
            // A device or FIFO: write to it in place; renaming a temporary
            // file over it would replace the device node.
            const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY);
            if (fd < 0) return io_error(path, errno);
            out.file_ = ::fdopen(fd, "wb");
            if (!out.file_) {
                const int err = errno;
                ::close(fd);
                return io_error(path, err);
            }
            out.direct_ = true;
            return out;
        }
        if (!force) return make_error(Errc::io, path + ": already exists (use -f to overwrite)");
    }
    const auto [dir, base] = split_path(path);
    std::string temp = dir + "/." + base + ".stepzip-XXXXXX";
    // Signals are held while the file is created and registered, so that
    // none can leave it behind.
    install_signal_handlers();
    sigset_t hold, previous;
    sigemptyset(&hold);
    for (int sig : kCleanupSignals) sigaddset(&hold, sig);
    ::sigprocmask(SIG_BLOCK, &hold, &previous);
    const int fd = ::mkstemp(temp.data());
    const int mkstemp_errno = errno;
    if (fd >= 0) out.signal_slot_ = register_temp_file(temp);
    ::sigprocmask(SIG_SETMASK, &previous, nullptr);
    if (fd < 0) return io_error(path, mkstemp_errno);
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
    if (direct_) {
        const int err = std::fclose(file_) != 0 ? errno : 0;
        file_ = nullptr;
        done_ = true;
        if (err != 0) return io_error(target_, err);
        return {};
    }
    if (attributes_) {
        // Owner first: chown clears the set-id bits that fchmod then restores.
        // Only root may give a file away; like zstd, a refusal is not an error.
        const int fd = ::fileno(file_);
        [[maybe_unused]] const int owned = ::fchown(fd, attributes_->st_uid, attributes_->st_gid);
        if (::fchmod(fd, attributes_->st_mode & 07777) != 0) return io_error(target_, errno);
        const struct timespec times[2] = {attributes_->st_atim, attributes_->st_mtim};
        if (::futimens(fd, times) != 0) return io_error(target_, errno);
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
    unregister_temp_file(std::exchange(signal_slot_, -1));
    return {};
}

// ------------------------------------------------------------------ Progress

Progress::Progress(std::string label, std::uint64_t total, bool enabled, bool compressing)
    : label_(std::move(label)),
      total_(total),
      active_(enabled && is_terminal(stderr)),
      compressing_(compressing) {}

Progress::~Progress() { finish(); }

void Progress::update(std::uint64_t read, std::uint64_t written) {
    if (!active_) return;
    const auto now = std::chrono::steady_clock::now();
    if (shown_ && now - last_ < std::chrono::milliseconds(250)) return;
    last_ = now;
    shown_ = true;
    std::string line = "\r" + label_ + ": ";
    if (total_ > 0)
        line += std::to_string(read >= total_ ? 100 : read * 100 / total_) + "% ";
    line += format_size(read) + " => " + format_size(written);
    // The ratio is frame size / original size in both directions.
    const std::uint64_t frame = compressing_ ? written : read;
    const std::uint64_t original = compressing_ ? read : written;
    if (original > 0) {
        char ratio[32];
        std::snprintf(ratio, sizeof ratio, " (%.2f%%)", 100.0 * static_cast<double>(frame) / original);
        line += ratio;
    }
    line += "\033[K";
    std::fputs(line.c_str(), stderr);
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
