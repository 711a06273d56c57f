// stepzip — the points chain format: one point per line ("x y", "x,y", 2 to
// 6 columns), a blank line ends a chain, '#' comments. Reader and writer; the
// layout byte code is described in docs/formats.md.
//
// The reader buffers one line at a time (at most kMaxLineBytes; comments are
// streamed) and checks that consecutive points differ by one unit step.
// Complexity: O(1) per input byte.
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "line_scanner.hpp"

namespace stepzip::io {
namespace {

// Layout operations.
enum : std::uint8_t {
    kNop = 0,       // nothing
    kLines = 1,     // varint n: n point lines in the current style
    kChains = 2,    // varint n: n whole chains in the current style, each followed by a blank line
    kVerbatim = 3,  // bytes: copied as they are
    kPoint = 4,     // flags, fields: one point line that is not in the current style
    kStyle = 5,     // style byte: the current style from here on (each block starts with 0)
};
// kPoint flags: which parts are given instead of following the style.
enum : std::uint8_t { kLead = 1, kSpell = 2, kGaps = 4, kTail = 8 };

// A style byte: separator code in bits 0-3, bit 4 set for CR LF line ends.
constexpr std::string_view kSeparators[4] = {" ", ",", ", ", "\t"};
constexpr std::uint8_t kCrlf = 0x10;

std::string_view style_sep(std::uint8_t style) { return kSeparators[style & 3]; }
std::string_view style_eol(std::uint8_t style) { return (style & kCrlf) ? "\r\n" : "\n"; }


class PointsLayout : public LayoutText<PointsLayout, kVerbatim> {
public:
    std::uint8_t style() const { return style_; }
    void set_style(std::uint8_t s) {
        if (s == style_) return;
        ops().push_back(static_cast<char>(kStyle));
        out_.push_back(static_cast<char>(s));
        style_ = s;
    }
    void canonical_line(bool chain_first) {
        flush_verbatim();
        if (chain_first) clean_ = lines_ == 0;
        ++lines_;
    }
    /// A blank line that ends a chain.
    void chain_end(std::string_view bytes) {
        if (clean_ && bytes == style_eol(style_)) {
            ++chains_;
            lines_ = 0;
            clean_ = false;
        } else {
            verbatim(bytes);
        }
    }
    /// The layout so far; the next block starts in style 0.
    std::string take() {
        style_ = 0;
        return LayoutText::take();
    }

private:
    friend class LayoutText<PointsLayout, kVerbatim>;
    void flush_runs() {
        if (chains_ != 0) {
            out_.push_back(static_cast<char>(kChains));
            put_varint(out_, chains_);
            chains_ = 0;
        }
        if (lines_ != 0) {
            out_.push_back(static_cast<char>(kLines));
            put_varint(out_, lines_);
            lines_ = 0;
        }
        clean_ = false;
    }
    std::uint64_t chains_ = 0, lines_ = 0;
    bool clean_ = false;  // the current chain's lines are all in `lines_`
    std::uint8_t style_ = 0;
};

struct ParsedLine {
    std::string_view lead, trailing;
    int count = 0;
    std::int64_t value[kMaxAxes]{};
    Spelling spell[kMaxAxes];
    std::size_t col[kMaxAxes]{};  // 1-based column of each coordinate
    std::string_view gap[kMaxAxes];
    std::size_t end_col = 0;  // column just past the last coordinate
};

class PointsParser final : public LineScanner<PointsParser, PointsLayout> {
public:
    // The axis count is the column count of the file's first point.
    PointsParser(std::string source, std::size_t block_steps)
        : LineScanner(std::move(source), block_steps, 0) {}

private:
    friend class LineScanner<PointsParser, PointsLayout>;

    // The grammar, for LineScanner.
    const unsigned char* scan(const unsigned char* p, const unsigned char* end);
    bool end_of_input() { return buf_.empty() || line_done(0); }
    void before_open_cut() {}

    bool line_done(int term);
    const unsigned char* canonical_line(const unsigned char* p, const unsigned char* end);
    bool parse(std::string_view s, ParsedLine& pl);
    bool point_line(const ParsedLine& pl, int term);

    bool ws_only_ = true;  // buf_ holds spaces and tabs only
    std::string buf_;
    Point prev_{};
};

bool PointsParser::parse(std::string_view s, ParsedLine& pl) {
    const std::size_t len = s.size();
    std::size_t pos = 0;
    while (pos < len && is_ws(s[pos])) ++pos;
    pl.lead = s.substr(0, pos);
    pl.count = 0;
    for (;;) {
        const std::size_t start = pos;
        NumberAccum n;
        if (pos < len && (s[pos] == '+' || s[pos] == '-')) {
            n.plus = s[pos] == '+';
            n.negative = s[pos] == '-';
            ++pos;
        }
        if (pos >= len || !is_digit(s[pos])) {
            const std::string found =
                pos >= len ? std::string("the end of the line") : describe_byte(s[pos]);
            return fail(Errc::syntax, pos + 1,
                        (pl.count == 0 ? "expected a point \"x y\" or \"x,y\", found "
                                       : "expected a coordinate, found ") + found);
        }
        while (pos < len && is_digit(s[pos])) {
            if (n.digits >= kMaxFieldBytes)
                return fail(Errc::limit, pos + 1, "a coordinate longer than 4096 digits");
            n.digit(s[pos] - '0');
            ++pos;
        }
        if (n.too_big) return fail(Errc::overflow, start + 1, "coordinate out of range (limit is +-2^62)");
        if (pl.count == kMaxAxes)
            return fail(Errc::syntax, start + 1, "a point has at most 6 coordinates");
        pl.value[pl.count] = n.value();
        pl.spell[pl.count] = n.spelling();
        pl.col[pl.count] = start + 1;
        ++pl.count;
        const std::size_t gap_start = pos;
        while (pos < len && is_ws(s[pos])) ++pos;
        if (pos < len && s[pos] == ',') {
            ++pos;
            while (pos < len && is_ws(s[pos])) ++pos;
            pl.gap[pl.count - 1] = s.substr(gap_start, pos - gap_start);
            continue;
        }
        if (pos == len) {
            pl.trailing = s.substr(gap_start);
            pl.end_col = gap_start + 1;
            break;
        }
        if (pos > gap_start && (is_digit(s[pos]) || s[pos] == '+' || s[pos] == '-')) {
            pl.gap[pl.count - 1] = s.substr(gap_start, pos - gap_start);
            continue;
        }
        if (s[pos] == '\r') return fail(Errc::syntax, pos + 1, "a carriage return not followed by a line feed");
        return fail(Errc::syntax, pos + 1,
                    "expected a space, ',' or the end of the line, found " + describe_byte(s[pos]));
    }
    if (pl.count < 2)
        return fail(Errc::syntax, pl.end_col, "a point needs at least two coordinates");
    return true;
}

bool PointsParser::point_line(const ParsedLine& pl, int term) {
    if (axes_ == 0) axes_ = pl.count;
    if (pl.count != axes_) {
        const std::size_t c = pl.count > axes_ ? pl.col[axes_] : pl.end_col;
        return fail(Errc::syntax, c,
                    "this point has " + std::to_string(pl.count) + " coordinates; the file's first "
                    "point has " + std::to_string(axes_));
    }
    Point pt{};
    for (int a = 0; a < axes_; ++a) pt[a] = pl.value[a];
    const bool first = !in_chain_;
    if (first) {
        Chain c;
        c.axes = axes_;
        c.start = pt;
        blk_.chains.push_back(std::move(c));
        in_chain_ = true;
    } else {
        int d[kMaxAxes] = {};
        bool moved = false;
        for (int a = 0; a < axes_; ++a) {
            const std::int64_t diff = pt[a] - prev_[a];
            if (diff < -1 || diff > 1)
                return fail(Errc::not_a_step, pl.col[a],
                            "coordinate " + std::to_string(a + 1) + " moves by " + std::to_string(diff) +
                                " from the previous point; consecutive points must differ by one step");
            d[a] = static_cast<int>(diff);
            moved = moved || diff != 0;
        }
        if (!moved)
            return fail(Errc::not_a_step, pl.col[0],
                        "the point repeats the previous one; consecutive points must differ by one step");
        if (full()) cut(true);
        blk_.chains.back().steps.push_back(make_step(d, axes_));
        ++blk_steps_;
    }
    prev_ = pt;

    // Layout: a line in one of the standard styles, or a kPoint record.
    bool canon = pl.lead.empty() && pl.trailing.empty() && term != 0;
    for (int a = 0; canon && a < pl.count; ++a) canon = pl.spell[a].canonical();
    int sep = -1;
    for (int k = 0; canon && k < 4; ++k)
        if (pl.gap[0] == kSeparators[k]) sep = k;
    for (int a = 1; canon && a + 1 < pl.count; ++a) canon = pl.gap[a] == pl.gap[0];
    if (canon && sep >= 0) {
        lb_.set_style(static_cast<std::uint8_t>(sep | (term == 2 ? kCrlf : 0)));
        lb_.canonical_line(first);
        return true;
    }
    const std::uint8_t style = lb_.style();
    std::uint8_t flags = 0;
    if (!pl.lead.empty()) flags |= kLead;
    for (int a = 0; a < pl.count; ++a)
        if (!pl.spell[a].canonical()) flags |= kSpell;
    for (int a = 0; a + 1 < pl.count; ++a)
        if (pl.gap[a] != style_sep(style)) flags |= kGaps;
    std::string tail(pl.trailing);
    tail += term == 1 ? "\n" : term == 2 ? "\r\n" : "";
    if (tail != style_eol(style)) flags |= kTail;
    std::string& o = lb_.ops();
    o.push_back(static_cast<char>(kPoint));
    o.push_back(static_cast<char>(flags));
    if (flags & kLead) wire::put_sized(o, pl.lead);
    if (flags & kSpell)
        for (int a = 0; a < pl.count; ++a) put_spelling(o, pl.spell[a]);
    if (flags & kGaps)
        for (int a = 0; a + 1 < pl.count; ++a) wire::put_sized(o, pl.gap[a]);
    if (flags & kTail) wire::put_sized(o, tail);
    return true;
}

// A whole line is in buf_ (without its LF); term: 0 end of input, 1 LF.
bool PointsParser::line_done(int term) {
    std::string_view s = buf_;
    if (term == 1 && !s.empty() && s.back() == '\r') {
        s.remove_suffix(1);
        term = 2;
    }
    const std::string_view eol = term == 1 ? "\n" : term == 2 ? "\r\n" : "";
    std::size_t pos = 0;
    while (pos < s.size() && is_ws(s[pos])) ++pos;
    if (pos == s.size()) {  // blank line
        std::string bytes(s);
        bytes += eol;
        if (in_chain_) {
            in_chain_ = false;
            lb_.chain_end(bytes);
        } else {
            lb_.verbatim(bytes);
        }
        if (term != 0 && full()) cut(false);
        buf_.clear();
        return true;
    }
    ParsedLine pl;
    if (!parse(s, pl)) return false;
    if (!point_line(pl, term)) return false;
    buf_.clear();
    return true;
}

// The fast path of a whole line at p: a point line in one of the four
// styles (canonical numbers, one separator throughout, LF or CR LF) that is
// one step from the previous point or starts a chain, read in place and
// recorded exactly as line_done() records it. Returns the byte after its LF,
// or nullptr for any other line (line_done() then reads it, errors
// included).
const unsigned char* PointsParser::canonical_line(const unsigned char* p, const unsigned char* end) {
    std::int64_t v[kMaxAxes];
    int count = 0;
    int sep = -1;
    for (;;) {
        const bool neg = p < end && *p == '-';
        if (neg) ++p;
        const unsigned char* digits = p;
        std::uint64_t m = 0;
        while (p < end && is_digit(*p)) m = m * 10 + static_cast<unsigned>(*p++ - '0');
        const auto nd = p - digits;
        // Canonical: 1..18 digits (below the limit), no leading zero, no "-0".
        if (nd == 0 || nd > 18 || (*digits == '0' && (nd > 1 || neg))) return nullptr;
        if (count == kMaxAxes) return nullptr;
        v[count++] = neg ? -static_cast<std::int64_t>(m) : static_cast<std::int64_t>(m);
        if (p >= end) return nullptr;
        int k;
        if (*p == ' ') k = 0;
        else if (*p == '\t') k = 3;
        else if (*p == ',') k = (p + 1 < end && p[1] == ' ') ? 2 : 1;
        else break;
        if (sep >= 0 && k != sep) return nullptr;
        sep = k;
        p += k == 2 ? 2 : 1;
        if (p >= end || !(is_digit(*p) || *p == '-')) return nullptr;
    }
    int term = 1;
    if (*p == '\r') {
        ++p;
        term = 2;
    }
    if (p >= end || *p != '\n' || count < 2 || sep < 0) return nullptr;
    if (axes_ != 0 && count != axes_) return nullptr;
    const bool first = !in_chain_;
    if (!first) {
        int d[kMaxAxes] = {};
        bool moved = false;
        for (int a = 0; a < count; ++a) {
            const std::int64_t diff = v[a] - prev_[a];
            if (diff < -1 || diff > 1) return nullptr;
            d[a] = static_cast<int>(diff);
            moved = moved || diff != 0;
        }
        if (!moved) return nullptr;
        if (full()) cut(true);
        blk_.chains.back().steps.push_back(make_step(d, count));
        ++blk_steps_;
    } else {
        if (axes_ == 0) axes_ = count;
        Chain c;
        c.axes = axes_;
        for (int a = 0; a < count; ++a) c.start[a] = v[a];
        blk_.chains.push_back(std::move(c));
        in_chain_ = true;
    }
    for (int a = 0; a < count; ++a) prev_[a] = v[a];
    lb_.set_style(static_cast<std::uint8_t>(sep | (term == 2 ? kCrlf : 0)));
    lb_.canonical_line(first);
    next_line();
    return p + 1;
}

const unsigned char* PointsParser::scan(const unsigned char* p, const unsigned char* end) {
    while (p < end && !in_comment()) {
        if (buf_.empty() && (is_digit(*p) || *p == '-')) {
            if (const unsigned char* q = canonical_line(p, end)) {
                p = q;
                continue;
            }
        }
        const unsigned char c = *p++;
        if (c == '\n') {
            if (!line_done(1)) return nullptr;
            next_line();
            ws_only_ = true;
            continue;
        }
        if (is_binary_byte(c)) return binary_byte(c), nullptr;
        if (c == '#' && ws_only_) {
            buf_.push_back('#');
            lb_.verbatim(buf_);
            buf_.clear();
            start_comment();
            ++col_;
            continue;
        }
        if (!is_ws(c)) ws_only_ = false;
        if (buf_.size() >= kMaxLineBytes) return fail(Errc::limit, col_, "a line longer than 65536 bytes"), nullptr;
        buf_.push_back(static_cast<char>(c));
        ++col_;
    }
    return p;
}

// ---- writer ----------------------------------------------------------------------

class PointsRenderer final : public FormatRenderer {
public:
    Result<void> write(const Block& block, std::string& out) override;
};

class PointCursor {
public:
    explicit PointCursor(const Block& b) : ch_(b.chains) {
        if (b.continues && !ch_.empty()) {
            j_ = 1;
            p_ = ch_[0].start;
        }
    }
    /// Moves to the next chain when the current one is exhausted.
    void advance() {
        if (i_ < ch_.size() && j_ > ch_[i_].steps.size()) {
            ++i_;
            j_ = 0;
        }
    }
    bool at_chain_start() {
        advance();
        return i_ < ch_.size() && j_ == 0;
    }
    bool chain_left() {
        return i_ < ch_.size() && j_ <= ch_[i_].steps.size();
    }
    /// The next point, or nullptr past the block's chains.
    const Point* next() {
        advance();
        if (i_ >= ch_.size()) return nullptr;
        const Chain& c = ch_[i_];
        if (j_ == 0) p_ = c.start;
        else apply_step(p_, c.steps[j_ - 1], c.axes);
        ++j_;
        return &p_;
    }
    bool done() {
        advance();
        return i_ >= ch_.size();
    }
    int axes() const { return ch_[i_ < ch_.size() ? i_ : 0].axes; }

private:
    const std::vector<Chain>& ch_;
    std::size_t i_ = 0, j_ = 0;
    Point p_{};
};

// Point lines in a style, gathered in a buffer and appended to `out` a few
// kilobytes at a time (a call per line was most of the rendering time).
class LineWriter {
public:
    explicit LineWriter(std::string& out) : out_(out) {}
    LineWriter(const LineWriter&) = delete;
    LineWriter& operator=(const LineWriter&) = delete;
    ~LineWriter() { flush(); }
    void line(const Point& p, int axes, std::uint8_t style) {
        if (n_ > sizeof buf_ - kMaxLine) flush();
        char* w = buf_ + n_;
        const std::string_view sep = style_sep(style);
        for (int a = 0; a < axes; ++a) {
            if (a) {
                for (const char c : sep) *w++ = c;
            }
            w = put_int(w, p[a]);
        }
        n_ = static_cast<std::size_t>(w - buf_);
        eol(style);
    }
    /// A line end in the style (a blank line when alone).
    void eol(std::uint8_t style) {
        if (n_ > sizeof buf_ - kMaxLine) flush();
        if (style & kCrlf) buf_[n_++] = '\r';
        buf_[n_++] = '\n';
    }
    void flush() {
        out_.append(buf_, n_);
        n_ = 0;
    }

private:
    // Sign, 19 digits and a separator of up to 2 bytes per axis, CR LF.
    static constexpr std::size_t kMaxLine = kMaxAxes * 22 + 2;
    std::string& out_;
    std::size_t n_ = 0;
    char buf_[8192];
};

Result<void> PointsRenderer::write(const Block& b, std::string& out) {
    if (b.continues && b.chains.empty()) return corrupt("points", "a continued block without chains");
    for (const Chain& c : b.chains) {
        if (c.axes < 2 || c.axes > kMaxAxes) return corrupt("points", "a bad axis count");
        // step_valid() on every step, branch-free: no bit past the axes, no
        // DIR bit on a resting axis, some axis moving.
        const unsigned past = c.axes < kMaxAxes ? ~0u << (2 * c.axes) : ~0u << (2 * kMaxAxes);
        unsigned bad = 0;
        for (const Step s : c.steps)
            bad |= (s & past) | ((s >> 1) & ~s & 0x555u) | static_cast<unsigned>((s & 0x555u) == 0);
        if (bad != 0) return corrupt("points", "an invalid step");
    }
    PointCursor cur(b);
    if (b.layout.empty()) {  // canonical: chains separated by one empty line
        LineWriter lw(out);
        bool first = true;
        while (!cur.done()) {
            if (!first && cur.at_chain_start()) lw.eol(0);
            first = false;
            const int axes = cur.axes();
            const Point* p = cur.next();
            lw.line(*p, axes, 0);
        }
        return {};
    }
    std::uint8_t style = 0;
    LayoutCursor lc(b.layout);
    while (!lc.done()) {
        std::uint8_t op = 0;
        lc.u8(op);
        switch (op) {
            case kNop:
                break;
            case kLines: {
                std::uint64_t k = 0;
                if (!lc.varint(k)) return corrupt("points", "a truncated run");
                LineWriter lw(out);
                for (std::uint64_t j = 0; j < k; ++j) {
                    if (cur.done()) return corrupt("points", "a run of lines past the block's chains");
                    const int axes = cur.axes();
                    lw.line(*cur.next(), axes, style);
                }
                break;
            }
            case kChains: {
                std::uint64_t k = 0;
                if (!lc.varint(k)) return corrupt("points", "a truncated run");
                LineWriter lw(out);
                for (std::uint64_t j = 0; j < k; ++j) {
                    if (!cur.at_chain_start()) return corrupt("points", "a chain run not at a chain");
                    const int axes = cur.axes();
                    do {
                        lw.line(*cur.next(), axes, style);
                    } while (cur.chain_left());
                    lw.eol(style);
                }
                break;
            }
            case kVerbatim: {
                std::string_view s;
                if (!lc.sized(s)) return corrupt("points", "truncated verbatim bytes");
                out.append(s);
                break;
            }
            case kStyle:
                if (!lc.u8(style) || (style & ~(kCrlf | 3u)) != 0) return corrupt("points", "a bad style");
                break;
            case kPoint: {
                std::uint8_t flags = 0;
                if (!lc.u8(flags) || (flags & ~0x0Fu) != 0 || cur.done())
                    return corrupt("points", "a bad point line");
                const int axes = cur.axes();
                const Point p = *cur.next();
                std::string_view s;
                if (flags & kLead) {
                    if (!lc.sized(s)) return corrupt("points", "a bad point line");
                    out.append(s);
                }
                Spelling sp[kMaxAxes];
                if (flags & kSpell)
                    for (int a = 0; a < axes; ++a)
                        if (!get_spelling(lc, p[a], sp[a])) return corrupt("points", "a bad spelling");
                for (int a = 0; a < axes; ++a) {
                    if (a) {
                        if (flags & kGaps) {
                            if (!lc.sized(s)) return corrupt("points", "a bad point line");
                            out.append(s);
                        } else {
                            out.append(style_sep(style));
                        }
                    }
                    append_number(out, p[a], sp[a]);
                }
                if (flags & kTail) {
                    if (!lc.sized(s)) return corrupt("points", "a bad point line");
                    out.append(s);
                } else {
                    out.append(style_eol(style));
                }
                break;
            }
            default:
                return corrupt("points", "an unknown operation");
        }
    }
    if (!cur.done()) return corrupt("points", "points left over after the layout");
    return {};
}

}  // namespace

std::unique_ptr<FormatParser> make_points_parser(std::string source, std::size_t block_steps) {
    return std::make_unique<PointsParser>(std::move(source), block_steps);
}

std::unique_ptr<FormatRenderer> make_points_renderer() { return std::make_unique<PointsRenderer>(); }

}  // namespace stepzip::io
