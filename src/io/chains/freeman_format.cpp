// stepzip — the freeman chain format: one chain per line "X0 Y0 CODES",
// '#' comments. Reader and writer; the layout byte code is described in
// docs/formats.md.
//
// The reader is a byte-driven state machine that never buffers more than one
// line head (bounded by kMaxFieldBytes per field); codes go straight into
// the block's chain in a tight loop. Complexity: O(1) per input byte.
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#include <tmmintrin.h>
#endif

#include "line_scanner.hpp"

namespace stepzip::io {
namespace {

constexpr Step kCodeStep[8] = {0x01, 0x05, 0x04, 0x07, 0x03, 0x0F, 0x0C, 0x0D};

// Codes at memory speed: where SSE2 is there (every x86-64), 16 bytes at a
// time; the scalar loops finish and stand in elsewhere. Same answers.

// Length of the run of Freeman digits '0'..'7' at p, at most n bytes.
std::size_t code_run(const unsigned char* p, std::size_t n) {
    std::size_t k = 0;
#if defined(__SSE2__)
    const __m128i zero = _mm_set1_epi8('0'), high = _mm_set1_epi8(static_cast<char>(0xF8)), none = _mm_setzero_si128();
    for (; n - k >= 16; k += 16) {
        const __m128i d = _mm_sub_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p + k)), zero);
        const auto digit = static_cast<unsigned>(_mm_movemask_epi8(_mm_cmpeq_epi8(_mm_and_si128(d, high), none)));
        if (digit != 0xFFFFu) return k + static_cast<std::size_t>(std::countr_one(digit));
    }
#endif
    while (k < n && static_cast<unsigned char>(p[k] - '0') <= 7u) ++k;
    return k;
}

// The steps of the n Freeman digits at p (each '0'..'7').
void code_steps(const unsigned char* p, std::size_t n, Step* o) {
    std::size_t i = 0;
#if defined(__SSE2__)
    // Per digit d: x moves unless d & 3 == 2, y moves unless d & 3 == 0, x
    // negative for 3 <= d <= 5, y negative for d >= 5 (kCodeStep's bits).
    const __m128i zero = _mm_set1_epi8('0'), three = _mm_set1_epi8(3), two = _mm_set1_epi8(2);
    const __m128i four = _mm_set1_epi8(4), six = _mm_set1_epi8(6), none = _mm_setzero_si128();
    const __m128i b0 = _mm_set1_epi8(1), b1 = _mm_set1_epi8(2), b2 = _mm_set1_epi8(4), b3 = _mm_set1_epi8(8);
    for (; n - i >= 16; i += 16) {
        const __m128i d = _mm_sub_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p + i)), zero);
        const __m128i low = _mm_and_si128(d, three);
        const __m128i x_rest = _mm_cmpeq_epi8(low, two), y_rest = _mm_cmpeq_epi8(low, none);
        const __m128i x_neg = _mm_and_si128(_mm_cmpgt_epi8(d, two), _mm_cmpgt_epi8(six, d));
        const __m128i y_neg = _mm_cmpgt_epi8(d, four);
        const __m128i s = _mm_or_si128(_mm_or_si128(_mm_andnot_si128(x_rest, b0), _mm_and_si128(x_neg, b1)),
                                       _mm_or_si128(_mm_andnot_si128(y_rest, b2), _mm_and_si128(y_neg, b3)));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(o + i), _mm_unpacklo_epi8(s, none));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(o + i + 8), _mm_unpackhi_epi8(s, none));
    }
#endif
    for (; i < n; ++i) o[i] = kCodeStep[(p[i] - '0') & 7];
}
// Two-axis step (0..15) to its Freeman digit, 0 when it has none.
constexpr char kStepCode[16] = {0,   '0', 0, '4', '2', '1', 0, '3',
                                0,   0,   0, 0,   '6', '7', 0, '5'};
// Two steps (the first in the low nibble) to their two digits (the first in
// the low byte), 0 when either has none: the renderer's four steps a round.
constexpr std::array<std::uint16_t, 256> kPairCode = [] {
    std::array<std::uint16_t, 256> t{};
    for (unsigned i = 0; i < 256; ++i) {
        const char a = kStepCode[i & 15], b = kStepCode[i >> 4];
        if (a != 0 && b != 0)
            t[i] = static_cast<std::uint16_t>(static_cast<unsigned char>(a) | (static_cast<unsigned>(static_cast<unsigned char>(b)) << 8));
    }
    return t;
}();

// Layout operations.
enum : std::uint8_t {
    kNop = 0,        // nothing
    kCanonLf = 1,    // varint n: n whole canonical lines ending in LF
    kCanonCrlf = 2,  // varint n: the same ending in CR LF
    kVerbatim = 3,   // bytes: copied as they are
    kHead = 4,       // flags, fields: a line head, then the next chain's codes
};
// kHead flags: which fields differ from the canonical head "X Y " (in order).
enum : std::uint8_t { kLead = 1, kX = 2, kWs1 = 4, kY = 8, kWs2 = 16 };

class LayoutBuilder : public LayoutText<LayoutBuilder, kVerbatim> {
public:
    void run(std::uint8_t op) {
        flush_verbatim();
        if (run_n_ != 0 && run_op_ != op) flush_runs();
        run_op_ = op;
        ++run_n_;
    }

private:
    friend class LayoutText<LayoutBuilder, kVerbatim>;
    void flush_runs() {
        if (run_n_ == 0) return;
        out_.push_back(static_cast<char>(run_op_));
        put_varint(out_, run_n_);
        run_n_ = 0;
    }
    std::uint8_t run_op_ = 0;
    std::uint64_t run_n_ = 0;
};

class FreemanParser final : public LineScanner<FreemanParser, LayoutBuilder> {
public:
    FreemanParser(std::string source, std::size_t block_steps)
        : LineScanner(std::move(source), block_steps, 2) {}

private:
    friend class LineScanner<FreemanParser, LayoutBuilder>;
    enum class St : std::uint8_t { lead, x_sign, x_dig, ws1, y_sign, y_dig, ws2, codes, tail, cr };

    // The grammar, for LineScanner.
    const unsigned char* scan(const unsigned char* p, const unsigned char* end);
    bool end_of_input();
    void before_open_cut() {
        if (!head_emitted_) emit_head();
    }

    bool byte(unsigned char c);
    const unsigned char* run_codes(const unsigned char* p, const unsigned char* end);
    bool add_ws(std::string& field, unsigned char c) {
        if (field.size() >= kMaxFieldBytes)
            return fail(Errc::limit, col_, "more than 4096 spaces or tabs in a row in a chain line");
        field.push_back(static_cast<char>(c));
        return true;
    }
    bool add_digit(NumberAccum& n, unsigned char c) {
        if (n.digits >= kMaxFieldBytes)
            return fail(Errc::limit, col_, "a coordinate longer than 4096 digits");
        n.digit(c - '0');
        return true;
    }
    // A coordinate starts with c ('+', '-' or a digit) at the current column.
    void start_number(NumberAccum& n, std::uint64_t& column, unsigned char c, St sign, St digits) {
        n.reset();
        column = col_;
        if (c == '+') n.plus = true;
        if (c == '-') n.negative = true;
        if (is_digit(c)) n.digit(c - '0');
        st_ = is_digit(c) ? digits : sign;
    }
    // A CR: the next byte must be LF.
    void carriage_return(bool in_chain) {
        cr_col_ = col_;
        cr_in_chain_ = in_chain;
        st_ = St::cr;
    }
    // LF or CR after a chain line's head or codes.
    void chain_line_break(unsigned char c) {
        if (c == '\n') end_chain_line(1);
        else carriage_return(true);
    }
    bool end_number(const NumberAccum& n, std::uint64_t column) {
        if (n.too_big)
            return fail(Errc::overflow, column, "coordinate out of range (limit is +-2^62)");
        return true;
    }
    void start_chain() {
        Chain c;
        c.axes = 2;
        c.start[0] = x_.value();
        c.start[1] = y_.value();
        blk_.chains.push_back(std::move(c));
        head_emitted_ = false;
        line_codes_ = 0;
    }
    bool head_canonical() const {
        return lead_.empty() && x_.spelling().canonical() && ws1_ == " " &&
               y_.spelling().canonical() && (line_codes_ == 0 || ws2_ == " ");
    }
    void emit_head();
    void end_chain_line(int term);
    void end_line_checks(int term) {
        lead_.clear();
        ws1_.clear();
        ws2_.clear();
        tail_.clear();
        st_ = St::lead;
        if (term != 0 && full()) cut(false);
    }

    St st_ = St::lead;
    bool cr_in_chain_ = false;
    std::uint64_t cr_col_ = 0;
    std::uint64_t x_col_ = 0, y_col_ = 0;
    NumberAccum x_, y_;
    std::string lead_, ws1_, ws2_, tail_;
    bool head_emitted_ = false;
    std::uint64_t line_codes_ = 0;
};

void FreemanParser::emit_head() {
    std::string& o = lb_.ops();
    std::uint8_t flags = 0;
    const Spelling xs = x_.spelling(), ys = y_.spelling();
    if (!lead_.empty()) flags |= kLead;
    if (!xs.canonical()) flags |= kX;
    if (ws1_ != " ") flags |= kWs1;
    if (!ys.canonical()) flags |= kY;
    if (line_codes_ != 0 && ws2_ != " ") flags |= kWs2;
    o.push_back(static_cast<char>(kHead));
    o.push_back(static_cast<char>(flags));
    if (flags & kLead) wire::put_sized(o, lead_);
    if (flags & kX) put_spelling(o, xs);
    if (flags & kWs1) wire::put_sized(o, ws1_);
    if (flags & kY) put_spelling(o, ys);
    if (flags & kWs2) wire::put_sized(o, ws2_);
    head_emitted_ = true;
}

// term: 0 none (end of input), 1 LF, 2 CR LF.
void FreemanParser::end_chain_line(int term) {
    const std::string_view t = term == 1 ? "\n" : term == 2 ? "\r\n" : "";
    if (head_emitted_) {
        lb_.verbatim(tail_);
        lb_.verbatim(t);
    } else if (term != 0 && tail_.empty() && head_canonical()) {
        lb_.run(term == 1 ? kCanonLf : kCanonCrlf);
    } else {
        emit_head();
        lb_.verbatim(tail_);
        lb_.verbatim(t);
    }
    head_emitted_ = false;
    end_line_checks(term);
}

const unsigned char* FreemanParser::run_codes(const unsigned char* p, const unsigned char* end) {
    while (p < end) {
        if (static_cast<unsigned>(*p - '0') > 7u) return p;
        if (blk_steps_ >= block_steps_) cut(true);
        std::vector<Step>& steps = blk_.chains.back().steps;
        const std::size_t room = block_steps_ - blk_steps_;
        const unsigned char* lim = p + std::min<std::size_t>(room, static_cast<std::size_t>(end - p));
        // The run of codes first, then all its steps at once.
        const std::size_t k = code_run(p, static_cast<std::size_t>(lim - p));
        const unsigned char* q = p + k;
        const std::size_t base = steps.size();
        steps.resize(base + k);
        code_steps(p, k, steps.data() + base);
        blk_steps_ += k;
        col_ += k;
        line_codes_ += k;
        p = q;
    }
    return p;
}

bool FreemanParser::byte(unsigned char c) {
    switch (st_) {
        case St::lead:
            if (is_ws(c)) return add_ws(lead_, c);
            if (c == '#') {
                lb_.verbatim(lead_);
                lb_.verbatim("#");
                lead_.clear();
                start_comment();
                return true;
            }
            if (c == '+' || c == '-' || is_digit(c)) {
                start_number(x_, x_col_, c, St::x_sign, St::x_dig);
                return true;
            }
            if (c == '\r') {
                carriage_return(false);
                return true;
            }
            if (c == '\n') {
                lb_.verbatim(lead_);
                lb_.verbatim("\n");
                end_line_checks(1);
                return true;
            }
            return fail(Errc::syntax, col_,
                        "expected a chain line \"X0 Y0 CODES\" or a '#' comment, found " +
                            describe_byte(c));
        case St::x_sign:
        case St::y_sign:
            if (is_digit(c)) {
                NumberAccum& n = st_ == St::x_sign ? x_ : y_;
                n.digit(c - '0');
                st_ = st_ == St::x_sign ? St::x_dig : St::y_dig;
                return true;
            }
            return fail(Errc::syntax, col_, "expected a digit after the sign, found " + describe_byte(c));
        case St::x_dig:
            if (is_digit(c)) return add_digit(x_, c);
            if (is_ws(c)) {
                if (!end_number(x_, x_col_)) return false;
                ws1_.assign(1, static_cast<char>(c));
                st_ = St::ws1;
                return true;
            }
            if (c == '\n' || c == '\r')
                return fail(Errc::syntax, col_, "the line ends after X0; expected \"X0 Y0 CODES\"");
            return fail(Errc::syntax, col_, "expected a digit or a space after X0, found " + describe_byte(c));
        case St::ws1:
            if (is_ws(c)) return add_ws(ws1_, c);
            if (c == '+' || c == '-' || is_digit(c)) {
                start_number(y_, y_col_, c, St::y_sign, St::y_dig);
                return true;
            }
            if (c == '\n' || c == '\r')
                return fail(Errc::syntax, col_, "the line ends after X0; expected \"X0 Y0 CODES\"");
            return fail(Errc::syntax, col_, "expected the start point's Y0, found " + describe_byte(c));
        case St::y_dig:
            if (is_digit(c)) return add_digit(y_, c);
            if (!end_number(y_, y_col_)) return false;
            if (is_ws(c)) {
                ws2_.assign(1, static_cast<char>(c));
                st_ = St::ws2;
                return true;
            }
            if (c == '\r' || c == '\n') {
                start_chain();
                chain_line_break(c);
                return true;
            }
            return fail(Errc::syntax, col_,
                        "expected a space and the Freeman codes after Y0, found " + describe_byte(c));
        case St::ws2:
            if (is_ws(c)) return add_ws(ws2_, c);
            if (c == '8' || c == '9')
                return fail(Errc::syntax, col_, describe_byte(c) + " is not a Freeman code 0-7");
            if (c == '\r' || c == '\n') {
                start_chain();
                tail_ = std::move(ws2_);
                ws2_.clear();
                chain_line_break(c);
                return true;
            }
            return fail(Errc::syntax, col_, "expected Freeman codes 0-7, found " + describe_byte(c));
        case St::codes:
            if (c == '8' || c == '9')
                return fail(Errc::syntax, col_, describe_byte(c) + " is not a Freeman code 0-7");
            if (is_ws(c)) {
                tail_.assign(1, static_cast<char>(c));
                st_ = St::tail;
                return true;
            }
            [[fallthrough]];
        case St::tail:
            if (is_ws(c)) return add_ws(tail_, c);
            if (c == '\n' || c == '\r') {
                chain_line_break(c);
                return true;
            }
            return fail(Errc::syntax, col_,
                        (st_ == St::codes ? "expected a Freeman code 0-7, found "
                                          : "unexpected text after the codes: ") +
                            describe_byte(c));
        case St::cr:
            if (c != '\n')
                return fail(Errc::syntax, cr_col_, "a carriage return not followed by a line feed");
            if (cr_in_chain_) {
                end_chain_line(2);
            } else {
                lb_.verbatim(lead_);
                lb_.verbatim("\r\n");
                end_line_checks(2);
            }
            return true;
    }
    return true;
}

bool FreemanParser::end_of_input() {
    switch (st_) {
        case St::lead:
            lb_.verbatim(lead_);
            lead_.clear();
            break;
        case St::x_sign:
        case St::x_dig:
        case St::ws1:
        case St::y_sign:
            return fail(Errc::syntax, col_, "the input ends inside a chain line; expected \"X0 Y0 CODES\"");
        case St::y_dig:
            if (!end_number(y_, y_col_)) return false;
            start_chain();
            end_chain_line(0);
            break;
        case St::ws2:
            start_chain();
            tail_ = std::move(ws2_);
            ws2_.clear();
            end_chain_line(0);
            break;
        case St::codes:
        case St::tail:
            end_chain_line(0);
            break;
        case St::cr:
            return fail(Errc::syntax, cr_col_, "a carriage return not followed by a line feed");
    }
    return true;
}

const unsigned char* FreemanParser::scan(const unsigned char* p, const unsigned char* end) {
    while (p < end && !in_comment()) {
        if (st_ == St::codes) {
            p = run_codes(p, end);
            if (p == end) break;
        } else if (st_ == St::ws2 && static_cast<unsigned>(*p - '0') <= 7u) {
            start_chain();
            st_ = St::codes;
            continue;
        }
        const unsigned char c = *p++;
        if (is_binary_byte(c)) return binary_byte(c), nullptr;
        if (!byte(c)) return nullptr;
        if (c == '\n') next_line();
        else ++col_;
    }
    return p;
}

// ---- writer ----------------------------------------------------------------------

class FreemanRenderer final : public FormatRenderer {
public:
    Result<void> write(const Block& block, std::string& out) override;
};

#if defined(__SSE2__) && defined(__GNUC__)
// Sixteen steps a round where the CPU has SSSE3 (a byte shuffle looks the
// sixteen codes up at once): w[0, k) for the first k = 16·floor(n / 16)
// steps; k, or SIZE_MAX when one of them is above 15 or has no code.
// Checked once per call: high bytes or-ed, codes of zero (none) or-ed.
[[gnu::target("ssse3")]] std::size_t codes_by_shuffle(const Step* s, std::size_t n, char* w) {
    const __m128i table = _mm_setr_epi8(0, '0', 0, '4', '2', '1', 0, '3', 0, 0, 0, 0, '6', '7', 0, '5');
    const __m128i none = _mm_setzero_si128();
    __m128i high = none, bad = none;
    std::size_t i = 0;
    for (; n - i >= 16; i += 16) {
        const __m128i a = _mm_loadu_si128(reinterpret_cast<const __m128i*>(s + i));
        const __m128i b = _mm_loadu_si128(reinterpret_cast<const __m128i*>(s + i + 8));
        high = _mm_or_si128(high, _mm_or_si128(a, b));
        const __m128i d = _mm_shuffle_epi8(table, _mm_packus_epi16(a, b));  // the high bit of 0xFF: 0
        bad = _mm_or_si128(bad, _mm_cmpeq_epi8(d, none));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(w + i), d);
    }
    const __m128i over = _mm_and_si128(high, _mm_set1_epi16(static_cast<short>(0xFFF0)));
    if (_mm_movemask_epi8(_mm_or_si128(bad, _mm_xor_si128(_mm_cmpeq_epi8(over, none), _mm_set1_epi8(-1)))) != 0)
        return SIZE_MAX;
    return i;
}
const bool kHasShuffle = __builtin_cpu_supports("ssse3");
#endif

// The Freeman digits of the n steps at s into w[0, n); false when a step
// has none.
bool codes_into(const Step* s, std::size_t n, char* w) {
    std::size_t i = 0;
#if defined(__SSE2__) && defined(__GNUC__)
    if (kHasShuffle && n >= 16 && (i = codes_by_shuffle(s, n, w)) == SIZE_MAX) return false;
#endif
    if constexpr (std::endian::native == std::endian::little) {
        // Four steps a round: one 64-bit load, one multiply that gathers the
        // four low nibbles into the top 16 bits (nibble k of lane k lands on
        // bit 48 + 4k; the product's other terms fall on distinct nibbles
        // below bit 48 or past bit 63, so nothing carries into them), two
        // pair look-ups, one store. A step above 15 or without a code is
        // found once, after the loop: high bits or-ed, digit pairs and-ed
        // (every digit has the bits 0x30, a pair without a code is 0).
        std::uint64_t high = 0;
        std::uint32_t digits = 0x30303030u;
        for (; i + 4 <= n; i += 4) {
            std::uint64_t v;
            std::memcpy(&v, s + i, 8);
            high |= v;
            const auto nib = static_cast<std::uint32_t>((v * 0x0001001001001000ull) >> 48);
            const std::uint32_t d = kPairCode[nib & 0xFF] | (std::uint32_t{kPairCode[nib >> 8]} << 16);
            digits &= d;
            std::memcpy(w + i, &d, 4);
        }
        if ((high & 0xFFF0FFF0FFF0FFF0ull) != 0 || digits != 0x30303030u) return false;
    }
    for (; i < n; ++i) {
        const char d = s[i] < 16 ? kStepCode[s[i]] : 0;
        if (d == 0) return false;
        w[i] = d;
    }
    return true;
}

// A chain's digits appended in pieces of up to 1 KiB made on the stack
// (growing the string by resize() would write every byte twice: zeros,
// then the digits).
bool append_codes(std::string& out, const Chain& c) {
    char buf[1024];
    const Step* s = c.steps.data();
    for (std::size_t i = 0, n = c.steps.size(); i < n; i += sizeof buf) {
        const std::size_t k = std::min(sizeof buf, n - i);
        if (!codes_into(s + i, k, buf)) return false;
        out.append(buf, k);
    }
    return true;
}

void append_canonical_head(std::string& out, const Chain& c) {
    char buf[48];  // "X Y ": one append
    char* w = put_int(buf, c.start[0]);
    *w++ = ' ';
    w = put_int(w, c.start[1]);
    if (!c.steps.empty()) *w++ = ' ';
    out.append(buf, w);
}

Result<void> FreemanRenderer::write(const Block& b, std::string& out) {
    const auto& ch = b.chains;
    const std::size_t n = ch.size();
    std::size_t bytes = out.size();  // room for the canonical lines: one growth of `out` at most
    for (const Chain& c : ch) {
        if (c.axes != 2) return corrupt("freeman", "a chain that is not two-axis");
        bytes += c.steps.size() + 48;
    }
    out.reserve(bytes);
    std::size_t i = 0;
    if (b.continues) {
        if (n == 0) return corrupt("freeman", "a continued block without chains");
        if (!append_codes(out, ch[0])) return corrupt("freeman", "a step without a Freeman code");
        i = 1;
    }
    if (b.layout.empty()) {  // canonical rendering
        if (b.continues && !(b.open && n == 1)) out.push_back('\n');
        for (; i < n; ++i) {
            append_canonical_head(out, ch[i]);
            if (!append_codes(out, ch[i])) return corrupt("freeman", "a step without a Freeman code");
            if (!(b.open && i + 1 == n)) out.push_back('\n');
        }
        return {};
    }
    LayoutCursor cur(b.layout);
    while (!cur.done()) {
        std::uint8_t op = 0;
        cur.u8(op);
        switch (op) {
            case kNop:
                break;
            case kCanonLf:
            case kCanonCrlf: {
                std::uint64_t k = 0;
                if (!cur.varint(k) || k > n - i || (b.open && k == n - i))
                    return corrupt("freeman", "a run of lines past the block's chains");
                for (std::uint64_t j = 0; j < k; ++j, ++i) {
                    append_canonical_head(out, ch[i]);
                    if (!append_codes(out, ch[i]))
                        return corrupt("freeman", "a step without a Freeman code");
                    out.append(op == kCanonLf ? "\n" : "\r\n");
                }
                break;
            }
            case kVerbatim: {
                std::string_view s;
                if (!cur.sized(s)) return corrupt("freeman", "truncated verbatim bytes");
                out.append(s);
                break;
            }
            case kHead: {
                std::uint8_t flags = 0;
                if (!cur.u8(flags) || (flags & ~0x1Fu) != 0 || i >= n)
                    return corrupt("freeman", "a bad line head");
                const Chain& c = ch[i++];
                std::string_view ws;
                Spelling sp;
                if (flags & kLead) {
                    if (!cur.sized(ws)) return corrupt("freeman", "a bad line head");
                    out.append(ws);
                }
                if (flags & kX) {
                    if (!get_spelling(cur, c.start[0], sp)) return corrupt("freeman", "a bad spelling");
                    append_number(out, c.start[0], sp);
                } else {
                    append_int(out, c.start[0]);
                }
                if (flags & kWs1) {
                    if (!cur.sized(ws)) return corrupt("freeman", "a bad line head");
                    out.append(ws);
                } else {
                    out.push_back(' ');
                }
                if (flags & kY) {
                    if (!get_spelling(cur, c.start[1], sp)) return corrupt("freeman", "a bad spelling");
                    append_number(out, c.start[1], sp);
                } else {
                    append_int(out, c.start[1]);
                }
                if (flags & kWs2) {
                    if (c.steps.empty() || !cur.sized(ws)) return corrupt("freeman", "a bad line head");
                    out.append(ws);
                } else if (!c.steps.empty()) {
                    out.push_back(' ');
                }
                if (!append_codes(out, c)) return corrupt("freeman", "a step without a Freeman code");
                break;
            }
            default:
                return corrupt("freeman", "an unknown operation");
        }
    }
    if (i != n) return corrupt("freeman", "chains left over after the layout");
    return {};
}

}  // namespace

std::unique_ptr<FormatParser> make_freeman_parser(std::string source, std::size_t block_steps) {
    return std::make_unique<FreemanParser>(std::move(source), block_steps);
}

std::unique_ptr<FormatRenderer> make_freeman_renderer() { return std::make_unique<FreemanRenderer>(); }

}  // namespace stepzip::io
