// stepzip — the line scanner under the text chain-file readers (freeman,
// points); not installed.
//
// It owns what the two readers share: the place (line, column) and the first
// error, the rejection of bytes no text format holds, '#' comment lines
// (streamed into the layout up to their LF, cutting a block when the layout
// is full), and the cutting and emitting of blocks. A reader derives from it
// (CRTP, no virtual call per byte) and keeps only its grammar:
//   const unsigned char* scan(p, end)  reads from p until the end, until it
//       starts a comment (start_comment()), or until an error (then fail()
//       and return nullptr); line and column are its to advance;
//   bool end_of_input()  completes the last line (not called in a comment);
//   void before_open_cut()  runs before a block is cut inside a chain.
// Complexity: O(1) per input byte besides the reader's own work.
#pragma once

#include <algorithm>
#include <string>
#include <string_view>
#include <utility>

#include "document_internal.hpp"

namespace stepzip::io {

inline bool is_ws(unsigned char c) { return c == ' ' || c == '\t'; }
inline bool is_digit(unsigned char c) { return c >= '0' && c <= '9'; }

/// The part of a text reader's layout builder that every format shares: the
/// operations in `out_`, and verbatim bytes gathered into one `kVerbatimOp`
/// operation (a sized byte string). Derived::flush_runs() writes the runs the
/// format keeps pending.
template <class Derived, std::uint8_t kVerbatimOp>
class LayoutText {
public:
    void verbatim(std::string_view s) {
        if (s.empty()) return;
        derived().flush_runs();
        verb_.append(s);
    }
    std::string& ops() {
        derived().flush_runs();
        flush_verbatim();
        return out_;
    }
    std::size_t size() const { return out_.size() + verb_.size(); }
    std::string take() {
        ops();
        std::string s = std::move(out_);
        out_.clear();
        return s;
    }

protected:
    void flush_verbatim() {
        if (verb_.empty()) return;
        out_.push_back(static_cast<char>(kVerbatimOp));
        wire::put_sized(out_, verb_);
        verb_.clear();
    }
    std::string out_;
    std::string verb_;

private:
    Derived& derived() { return static_cast<Derived&>(*this); }
};

/// Layout: the reader's layout builder (verbatim(), size(), take()); its
/// code 0 is a no-op.
template <class Reader, class Layout>
class LineScanner : public FormatParser {
public:
    Result<void> feed(std::string_view data, bool last) final;
    std::uint64_t line() const final { return line_; }

protected:
    /// `axes`: the axis count of the chains, 0 until the reader knows it.
    LineScanner(std::string source, std::size_t block_steps, int axes)
        : source_(std::move(source)), block_steps_(block_steps), cap_(layout_cap(block_steps)),
          axes_(axes) {}

    /// Records "SOURCE:LINE:COLUMN: what" as the error; returns false.
    bool fail(Errc code, std::uint64_t column, std::string_view what) {
        err_ = make_error(code, at(source_, line_, column, what));
        failed_ = true;
        return false;
    }
    /// The error for a byte no text format holds, at the current column.
    bool binary_byte(unsigned char c) {
        return fail(Errc::syntax, col_, describe_byte(c) + " (text formats hold no binary bytes)");
    }
    void next_line() {
        ++line_;
        col_ = 1;
    }
    /// The rest of the line up to its LF is a comment, copied to the layout.
    void start_comment() { in_comment_ = true; }
    bool in_comment() const { return in_comment_; }
    bool full() const { return blk_steps_ >= block_steps_ || lb_.size() >= cap_; }
    /// Emits the block; `open`: the last chain goes on in the next block.
    void cut(bool open);

    std::string source_;
    std::size_t block_steps_;
    std::size_t cap_;
    std::uint64_t line_ = 1;
    std::uint64_t col_ = 1;  // column of the byte being read
    int axes_;
    bool in_chain_ = false;  // a chain goes on past the current line

    Block blk_;
    std::size_t blk_steps_ = 0;
    Layout lb_;

private:
    Reader& reader() { return static_cast<Reader&>(*this); }
    int block_axes() const { return axes_ != 0 ? axes_ : 2; }
    const unsigned char* run_comment(const unsigned char* p, const unsigned char* end);
    void emit_last();

    bool in_comment_ = false;
    bool emitted_ = false;
    bool failed_ = false;
    bool finished_ = false;
    Error err_;
};

template <class Reader, class Layout>
void LineScanner<Reader, Layout>::cut(bool open) {
    if (open) reader().before_open_cut();
    Block b = std::move(blk_);
    b.axes = block_axes();
    b.open = open;
    b.layout = lb_.take();
    if (b.layout.empty()) b.layout.push_back('\0');
    Point end{};
    if (open) end = b.chains.back().end();
    ready.push_back(std::move(b));
    emitted_ = true;
    blk_ = Block{};
    blk_.axes = block_axes();
    blk_steps_ = 0;
    if (open) {
        blk_.continues = true;
        Chain c;
        c.axes = axes_;
        c.start = end;
        blk_.chains.push_back(std::move(c));
    }
}

template <class Reader, class Layout>
void LineScanner<Reader, Layout>::emit_last() {
    if (!blk_.chains.empty() || lb_.size() != 0 || !emitted_) {
        Block b = std::move(blk_);
        b.axes = block_axes();
        b.open = false;
        b.layout = lb_.take();
        if (b.layout.empty() && !b.chains.empty()) b.layout.push_back('\0');
        ready.push_back(std::move(b));
        emitted_ = true;
        blk_ = Block{};
    }
}

template <class Reader, class Layout>
const unsigned char* LineScanner<Reader, Layout>::run_comment(const unsigned char* p,
                                                              const unsigned char* end) {
    while (p < end) {
        if (lb_.size() >= cap_) cut(in_chain_);
        const std::size_t room = cap_ - lb_.size();
        const unsigned char* lim = p + std::min<std::size_t>(room, static_cast<std::size_t>(end - p));
        const unsigned char* q = p;
        while (q < lim && *q != '\n' && !is_binary_byte(*q)) ++q;
        lb_.verbatim(std::string_view(reinterpret_cast<const char*>(p), static_cast<std::size_t>(q - p)));
        col_ += static_cast<std::uint64_t>(q - p);
        p = q;
        if (q == lim) continue;
        if (*q == '\n') {
            lb_.verbatim("\n");
            next_line();
            in_comment_ = false;
            if (!in_chain_ && full()) cut(false);
            return p + 1;
        }
        fail(Errc::syntax, col_, describe_byte(*q) + " in a comment (text formats hold no binary bytes)");
        return nullptr;
    }
    return p;
}

template <class Reader, class Layout>
Result<void> LineScanner<Reader, Layout>::feed(std::string_view data, bool last) {
    if (failed_) return err_;
    if (finished_) return make_error(Errc::invalid_argument, source_ + ": input fed after its end");
    const auto* p = reinterpret_cast<const unsigned char*>(data.data());
    const auto* end = p + data.size();
    while (p < end) {
        p = in_comment_ ? run_comment(p, end) : reader().scan(p, end);
        if (p == nullptr) return err_;
    }
    if (last) {
        finished_ = true;
        if (!in_comment_ && !reader().end_of_input()) return err_;
        in_chain_ = false;
        emit_last();
    }
    return {};
}

}  // namespace stepzip::io
