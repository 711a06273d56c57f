// stepzip — error codes and the Result type returned by every fallible call.
//
// Bad input is not exceptional: parsers, decoders and the container return a
// Result<T> holding either a value or an Error. `assert` is kept for
// programmer errors only.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <variant>

namespace stepzip {

/// Error codes. Values are fixed (they are part of the C API and of the exit
/// status documentation) and grouped by kind.
enum class Errc : int {
    ok = 0,
    // usage: the caller asked for something that is not defined
    invalid_argument = 10,
    unsupported = 11,
    // input format (text or binary input that cannot be read)
    syntax = 20,
    not_a_step = 21,     ///< consecutive points differ by more than one step
    connectivity = 22,   ///< a diagonal step where the profile is 4-connected
    // container corruption
    bad_magic = 30,
    bad_version = 31,
    corrupt = 32,
    truncated = 33,
    reserved_bits = 34,
    // checksum
    checksum = 40,
    // limits
    limit = 50,
    overflow = 51,
    // I/O
    io = 60,
    // round trip (verify)
    mismatch = 70,
};

/// A short fixed name for an error code ("syntax", "checksum", ...); never
/// null, a static string. Thread-safe.
const char* errc_name(Errc code) noexcept;

/// An error: a code and a message that names where (file, line, column or
/// byte offset) when a place is known.
struct Error {
    Errc code = Errc::ok;
    std::string message;
};

/// Either a value or an Error (a small stand-in for C++23 std::expected).
template <class T>
class [[nodiscard]] Result {
public:
    Result(T value) : v_(std::move(value)) {}
    Result(Error error) : v_(std::move(error)) {}

    bool ok() const noexcept { return v_.index() == 0; }
    explicit operator bool() const noexcept { return ok(); }

    T& value() & { return std::get<0>(v_); }
    const T& value() const& { return std::get<0>(v_); }
    T&& value() && { return std::get<0>(std::move(v_)); }
    T& operator*() & { return value(); }
    const T& operator*() const& { return value(); }
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }

    const Error& error() const& { return std::get<1>(v_); }
    Error&& error() && { return std::get<1>(std::move(v_)); }

private:
    std::variant<T, Error> v_;
};

/// Result of an operation that returns nothing on success.
template <>
class [[nodiscard]] Result<void> {
public:
    Result() = default;
    Result(Error error) : error_(std::move(error)) {}

    bool ok() const noexcept { return error_.code == Errc::ok; }
    explicit operator bool() const noexcept { return ok(); }
    const Error& error() const& { return error_; }
    Error&& error() && { return std::move(error_); }

private:
    Error error_{};
};

/// Builds an Error; a convenience for `return make_error(Errc::syntax, "...")`.
inline Error make_error(Errc code, std::string message) {
    return Error{code, std::move(message)};
}

}  // namespace stepzip
