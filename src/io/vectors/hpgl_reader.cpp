// stepzip — HP-GL / HP-GL/2 reader: the plotter's interpreter, drawing what
// a plotter (or hp2xx) would draw as pen-down paths.
//
// One pass over the text. An instruction is a two-letter mnemonic and its
// parameters (numbers, or text for LB, BL, CO, DT, SM, PE). Positions are
// kept in plotter units as doubles (exact for the integers of unscaled
// HP-GL), after user scaling (SC, IP) and before the page rotation (RO);
// every drawn line is clipped to the window (IW) and its end points rounded
// to the nearest plotter unit (or step, with a step size) when emitted.
// Curves (CI, AA, AR, AT, RT, EW, WG, BZ, BR) are flattened into chords of
// the chord angle (default 5 degrees) or 16 chords per Bezier; filled shapes
// (RA, RR, WG, FP) are drawn as their outlines; labels (LB, SM) with the
// stroke font of stroke_font.hpp. Complexity: O(bytes + drawn points).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "gcode_units.hpp"
#include "stepzip/vectors.hpp"
#include "stroke_font.hpp"

namespace stepzip {

namespace {

using vec::i128;

struct Pt {
    double x = 0, y = 0;
};

struct Param {
    double value = 0;
    std::string text;
    std::size_t line = 0, column = 0;
};

// Cursor over the text that tracks line and column.
struct Cursor {
    std::string_view text;
    std::size_t pos = 0, line = 1, line_start = 0;
    bool done() const { return pos >= text.size(); }
    char peek() const { return text[pos]; }
    std::size_t column() const { return pos - line_start + 1; }
    void advance() {
        if (text[pos] == '\n') {
            ++line;
            line_start = pos + 1;
        }
        ++pos;
    }
};

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
bool is_alpha(char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; }
bool starts_number(char c) {
    return std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.';
}

constexpr double kPi = std::numbers::pi;
// A parameter as an int, clamped to a range (NaN gives lo).
int clamp_int(double v, int lo, int hi) {
    if (!(v >= lo)) return lo;
    if (v > hi) return hi;
    return static_cast<int>(v);
}

constexpr double kUnitsPerCm = 400;  // plotter units (0.025 mm)
// Default P1 = (0, 0) and P2 = (kHardX, kHardY): hp2xx's hardware range
// (its options -H and -W), so that user scaling without IP agrees with it.
constexpr double kHardX = 33600, kHardY = 47520;

// Mnemonics accepted and without effect on the drawn paths.
bool no_effect(const std::string& m) {
    static constexpr const char* kList[] = {
        "DF", "VS", "LT", "PW", "PG", "FT", "PT", "UL", "LA", "NP", "PC", "CR", "MC", "TR",
        "WU", "PP", "CS", "CA", "SS", "SA", "SD", "AD", "SB", "FN", "FR", "IV", "SV", "TD",
        "BP", "PS", "EC", "AC", "AF", "AH", "CV", "RF", "SG", "SL", "DV", "OP", "OS", "OE",
        "OI", "OH", "OW", "OC", "OF", "OD", "OO", "OT", "OL", "OA", "OG", "GC", "GM", "NR",
        "CT", "AP", "IM", "KY", "CM", "CC", "DL", "DS", "UC", "WD", "XT", "YT", "TL", "FS",
        "QL", "BF", "PB", "CH", "ST", "ND", "RD", "TH", "QU", "NO", "SH", "WH", "IS",
    };
    for (const char* k : kList)
        if (m == k) return true;
    return false;
}

class Interpreter {
public:
    Interpreter(std::string_view text, const VectorReadOptions& options)
        : cur_{text}, opt_(options) {
        defaults(true);
    }

    Result<Drawing> run();

private:
    // ---- state ---------------------------------------------------------
    void defaults(bool full) {
        if (full) {
            p1_ = {0, 0};
            p2_ = {kHardX, kHardY};
            rotation_ = 0;
            pen_ = 1;
        }
        scaled_ = false;
        window_ = false;
        absolute_ = true;
        pen_down_ = false;
        symbol_ = 0;
        terminator_ = '\x03';
        chord_ = 5;
        label_dir_ = {1, 0};
        size_relative_ = true;
        size_ = {0.75, 1.5};
        slant_ = 0;
        label_origin_ = 1;
        extra_ = {0, 0};
        polygon_ = false;
    }

    // User units -> plotter units.
    Pt to_plotter(Pt u) const {
        if (!scaled_) return u;
        return {p1_.x + (u.x - sc_min_.x) * sc_factor_.x + sc_offset_.x,
                p1_.y + (u.y - sc_min_.y) * sc_factor_.y + sc_offset_.y};
    }
    Pt to_user(Pt p) const {
        if (!scaled_) return p;
        return {(p.x - p1_.x - sc_offset_.x) / sc_factor_.x + sc_min_.x,
                (p.y - p1_.y - sc_offset_.y) / sc_factor_.y + sc_min_.y};
    }
    // A size in user units along x / y -> plotter units.
    double user_dx(double d) const { return scaled_ ? d * sc_factor_.x : d; }
    double user_dy(double d) const { return scaled_ ? d * sc_factor_.y : d; }

    Pt char_size() const {  // width, cap height in plotter units
        if (!size_relative_) return {size_.x * kUnitsPerCm, size_.y * kUnitsPerCm};
        return {size_.x / 100 * std::abs(p2_.x - p1_.x), size_.y / 100 * std::abs(p2_.y - p1_.y)};
    }

    // ---- output --------------------------------------------------------
    Result<Point> to_steps(Pt p, std::size_t line, std::size_t column) const {
        for (int r = 0; r < rotation_; r += 90) p = {-p.y, p.x};
        Point out{};
        const double v[2] = {p.x, p.y};
        for (int a = 0; a < 2; ++a) {
            double s = v[a];
            if (opt_.step_size) s = s * 25e9 / static_cast<double>(opt_.step_size->mm_e12);
            s = std::round(s);  // halves away from zero
            if (!(std::abs(s) <= static_cast<double>(kMaxVectorCoord)))
                return make_error(Errc::limit, vec::place(opt_.source, line, column) +
                                                   ": coordinate beyond the limit of 2^30 steps");
            out[static_cast<std::size_t>(a)] = static_cast<std::int64_t>(s);
        }
        return out;
    }

    void lift() { open_ = false; }

    // A pen-down line in plotter units, clipped to the window, into the
    // drawing (or into the polygon buffer in polygon mode).
    Result<void> line(Pt a, Pt b) {
        if (polygon_) {
            if (poly_.empty() || poly_new_) {
                poly_.push_back({a});
                poly_new_ = false;
            }
            poly_.back().push_back(b);
            return {};
        }
        if (pen_ == 0) return {};  // no pen in the holder: nothing is drawn
        if (window_ && !clip(a, b)) {
            open_ = false;
            return {};
        }
        auto sa = to_steps(a, ins_line_, ins_col_);
        if (!sa) return std::move(sa).error();
        auto sb = to_steps(b, ins_line_, ins_col_);
        if (!sb) return std::move(sb).error();
        if (!open_ || last_ != *sa || drawing_.back().pen != pen_) {
            if (*sa == *sb) return {};
            drawing_.push_back(VectorPath{(*sa)[0], (*sa)[1], {}, pen_});
            open_ = true;
            last_ = *sa;
        }
        if (*sb == last_) return {};
        VectorMove mv;
        mv.x = (*sb)[0];
        mv.y = (*sb)[1];
        mv.line = static_cast<std::uint32_t>(ins_line_);
        mv.column = static_cast<std::uint32_t>(ins_col_);
        drawing_.back().moves.push_back(mv);
        last_ = *sb;
        // A clipped end leaves the window: the next line starts a new path.
        if (clipped_end_) open_ = false;
        return {};
    }

    // Liang-Barsky against the window; false when nothing is inside.
    bool clip(Pt& a, Pt& b) {
        double t0 = 0, t1 = 1;
        const double dx = b.x - a.x, dy = b.y - a.y;
        const double p[4] = {-dx, dx, -dy, dy};
        const double q[4] = {a.x - win_lo_.x, win_hi_.x - a.x, a.y - win_lo_.y, win_hi_.y - a.y};
        for (int i = 0; i < 4; ++i) {
            if (p[i] == 0) {
                if (q[i] < 0) return false;
                continue;
            }
            const double t = q[i] / p[i];
            if (p[i] < 0) t0 = std::max(t0, t);
            else t1 = std::min(t1, t);
        }
        if (t0 > t1) return false;
        const Pt a0 = a;
        if (t0 > 0) {
            a = {a0.x + t0 * dx, a0.y + t0 * dy};
            open_ = false;
        }
        clipped_end_ = t1 < 1;
        if (t1 < 1) b = {a0.x + t1 * dx, a0.y + t1 * dy};
        return true;
    }

    // Moves to `to` (plotter units) with the pen as it is.
    Result<void> move(Pt to) {
        clipped_end_ = false;
        if (pen_down_) {
            if (auto r = line(pos_, to); !r) return r;
        } else {
            lift();
            if (polygon_) poly_new_ = true;
        }
        pos_ = to;
        return {};
    }

    // A polyline drawn with the pen down whatever its state; the position
    // and pen state are left as they were.
    Result<void> stroke(const std::vector<Pt>& pts) {
        if (polygon_) poly_new_ = true;
        lift();
        for (std::size_t i = 1; i < pts.size(); ++i) {
            clipped_end_ = false;
            if (auto r = line(pts[i - 1], pts[i]); !r) return r;
        }
        lift();
        if (polygon_) poly_new_ = true;
        return {};
    }

    // Points of an arc about `c` (user units) from angle a0 through `sweep`
    // degrees at radius r, in plotter units, chords of at most chord_.
    std::vector<Pt> arc_points(Pt c, double r, double a0, double sweep) const {
        const double chord = std::clamp(std::abs(chord_), 0.5, 180.0);
        sweep = std::clamp(sweep, -3600.0, 3600.0);  // ten turns at most
        const int n = std::max(1, static_cast<int>(std::ceil(std::abs(sweep) / chord - 1e-9)));
        std::vector<Pt> pts;
        for (int i = 0; i <= n; ++i) {
            const double a = (a0 + sweep * i / n) * kPi / 180;
            pts.push_back(to_plotter({c.x + r * std::cos(a), c.y + r * std::sin(a)}));
        }
        return pts;
    }

    // ---- labels --------------------------------------------------------
    Result<void> draw_text(const std::string& text, bool centred_symbol);

    // ---- parsing -------------------------------------------------------
    Result<std::vector<Param>> numbers(const std::string& mnemonic);
    Result<void> skip_escape();
    Result<void> instruction(const std::string& m, std::vector<Param>& params);
    Result<void> encoded_polyline();
    Result<void> instruction_sc_again();

    Cursor cur_;
    const VectorReadOptions& opt_;
    Drawing drawing_;
    bool open_ = false, clipped_end_ = false;
    Point last_{};
    std::size_t ins_line_ = 1, ins_col_ = 1;

    Pt pos_;
    bool absolute_ = true, pen_down_ = false;
    int pen_ = 1, rotation_ = 0;
    Pt p1_, p2_;
    bool scaled_ = false;
    Pt sc_min_, sc_factor_{1, 1}, sc_offset_;
    bool window_ = false;
    Pt win_lo_, win_hi_;
    double chord_ = 5;
    bool polygon_ = false, poly_new_ = false;
    std::vector<std::vector<Pt>> poly_;
    // labels
    char symbol_ = 0, terminator_ = '\x03';
    Pt label_dir_{1, 0};
    bool size_relative_ = true;
    Pt size_{0.75, 1.5};
    double slant_ = 0;
    int label_origin_ = 1;
    Pt extra_;
    Pt label_start_;
    std::vector<Param> sc_params_;
};

Result<void> Interpreter::draw_text(const std::string& text, bool centred_symbol) {
    const Pt size = char_size();
    const double w = size.x, h = size.y;
    const double len = std::hypot(label_dir_.x, label_dir_.y);
    const Pt u = len > 0 ? Pt{label_dir_.x / len, label_dir_.y / len} : Pt{1, 0};
    const Pt v{-u.y, u.x};
    const double advance = 1.5 * w * (1 + extra_.x), line_feed = 2 * h * (1 + extra_.y);
    // Label origin: where the current point sits on the label's box.
    int lo = centred_symbol ? 5 : label_origin_;
    const bool offset = lo > 10;
    if (offset) lo -= 10;
    std::size_t first_line = text.find_first_of("\r\n");
    if (first_line == std::string::npos) first_line = text.size();
    const double width = static_cast<double>(first_line) * advance - (first_line ? 0.5 * w : 0);
    const int col = (lo - 1) / 3, row = (lo - 1) % 3;  // col: left/centre/right; row: bottom/middle/top
    double ox = col == 0 ? 0 : col == 1 ? -width / 2 : -width;
    double oy = row == 0 ? 0 : row == 1 ? -h / 2 : -h;
    if (offset) {
        ox += col == 0 ? w / 2 : col == 2 ? -w / 2 : 0;
        oy += row == 0 ? h / 2 : row == 2 ? -h / 2 : 0;
    }
    const Pt origin = centred_symbol ? pos_ : Pt{pos_.x + ox * u.x + oy * v.x, pos_.y + ox * u.y + oy * v.y};
    if (centred_symbol) {
        const Pt o{pos_.x + ox * u.x + oy * v.x, pos_.y + ox * u.y + oy * v.y};
        label_start_ = o;
    } else {
        label_start_ = origin;
    }
    Pt line_start = label_start_, at = label_start_;
    const bool was_down = pen_down_;
    for (const char ch : text) {
        if (ch == '\r') {
            at = line_start;
            continue;
        }
        if (ch == '\n') {
            line_start = {line_start.x - line_feed * v.x, line_start.y - line_feed * v.y};
            at = {at.x - line_feed * v.x, at.y - line_feed * v.y};
            continue;
        }
        if (ch == '\b') {
            at = {at.x - advance * u.x, at.y - advance * u.y};
            continue;
        }
        for (const vec::GlyphStroke& s : vec::glyph_strokes(static_cast<unsigned char>(ch))) {
            std::vector<Pt> pts;
            for (const vec::GlyphPoint& g : s) {
                const double gx = g.x / vec::kGlyphWidth * w + slant_ * g.y / vec::kGlyphHeight * h;
                const double gy = g.y / vec::kGlyphHeight * h;
                pts.push_back({at.x + gx * u.x + gy * v.x, at.y + gx * u.y + gy * v.y});
            }
            if (auto r = stroke(pts); !r) return r;
        }
        at = {at.x + advance * u.x, at.y + advance * u.y};
    }
    pen_down_ = was_down;
    if (!centred_symbol) pos_ = at;  // the pen ends after the label
    return {};
}

Result<std::vector<Param>> Interpreter::numbers(const std::string& mnemonic) {
    std::vector<Param> params;
    const std::string& src = opt_.source;
    bool want_number = false;  // after a comma
    while (true) {
        while (!cur_.done() && is_space(cur_.peek())) cur_.advance();
        if (cur_.done()) break;
        const char c = cur_.peek();
        if (c == ';' || is_alpha(c) || c == '\x1b') break;
        if (c == ',') {
            if (want_number || params.empty())
                return make_error(Errc::syntax, vec::place(src, cur_.line, cur_.column()) +
                                                    ": expected a number before ','");
            want_number = true;
            cur_.advance();
            continue;
        }
        if (!starts_number(c)) {
            if (c == ':' && params.empty()) {  // "PD:" as some drivers write: a stray separator
                cur_.advance();
                continue;
            }
            return make_error(Errc::syntax, vec::place(src, cur_.line, cur_.column()) +
                                                ": unexpected character " + vec::describe_char(c) +
                                                " in " + mnemonic);
        }
        Param p;
        p.line = cur_.line;
        p.column = cur_.column();
        std::size_t k = cur_.pos;
        i128 v = 0;
        const std::string why = vec::parse_decimal(cur_.text, k, v);
        if (!why.empty())
            return make_error(Errc::syntax, vec::place(src, p.line, p.column) + ": " + why);
        p.text = std::string(cur_.text.substr(cur_.pos, k - cur_.pos));
        p.value = static_cast<double>(v) / 1e12;
        while (cur_.pos < k) cur_.advance();
        params.push_back(std::move(p));
        want_number = false;
    }
    // A comma before the terminator ("PD1,2,;", as some drivers write) is
    // accepted, as plotters accept it.
    return params;
}

// Escape sequences: HP RS-232 device control (ESC . letter [params] [:]),
// PCL (ESC E, ESC % n A/B, ESC & / * / ( / ) group letter value... letter,
// with binary data after ESC * b n W and ESC ( s n W), all skipped.
Result<void> Interpreter::skip_escape() {
    const std::string at = vec::place(opt_.source, cur_.line, cur_.column());
    cur_.advance();
    if (cur_.done()) return make_error(Errc::syntax, at + ": ESC at the end of the input");
    const char c = cur_.peek();
    if (c == '.') {
        cur_.advance();
        if (cur_.done()) return make_error(Errc::syntax, at + ": incomplete device-control sequence");
        cur_.advance();  // the function letter
        std::size_t k = cur_.pos;
        while (k < cur_.text.size() && k - cur_.pos < 64 &&
               (std::isdigit(static_cast<unsigned char>(cur_.text[k])) || cur_.text[k] == ';'))
            ++k;
        if (k < cur_.text.size() && cur_.text[k] == ':')
            while (cur_.pos <= k) cur_.advance();
        return {};
    }
    if (c >= 0x21 && c <= 0x2f) {  // parameterized: ESC c [group] (value letter)+
        cur_.advance();
        if (c != '%' && !cur_.done() && cur_.peek() >= 0x60 && cur_.peek() <= 0x7e) cur_.advance();
        while (true) {
            std::string value;
            while (!cur_.done() && (starts_number(cur_.peek()))) {
                value += cur_.peek();
                cur_.advance();
            }
            if (cur_.done()) return make_error(Errc::syntax, at + ": incomplete escape sequence");
            const char t = cur_.peek();
            if (!((t >= 0x40 && t <= 0x5e) || (t >= 0x60 && t <= 0x7e)))
                return make_error(Errc::syntax, at + ": malformed escape sequence");
            cur_.advance();
            if (t == 'W' || t == 'w') {  // binary data follows
                const double n = value.empty() ? 0 : std::strtod(value.c_str(), nullptr);
                for (double i = 0; i < n && !cur_.done(); ++i) cur_.advance();
            }
            if (t >= 0x40 && t <= 0x5e) return {};  // upper case ends the sequence
        }
    }
    if (c >= 0x30 && c <= 0x7e) {  // two-character escape (ESC E reset ...)
        cur_.advance();
        return {};
    }
    return make_error(Errc::syntax, at + ": ESC followed by " + vec::describe_char(c));
}

// PE: encoded polyline (base 64 in 8-bit mode, base 32 after '7'): ':' pen
// number, '<' pen up for the next point, '>' fraction bits, '=' the next
// point is absolute; otherwise points are relative, in current units.
Result<void> Interpreter::encoded_polyline() {
    const std::string at = vec::place(opt_.source, ins_line_, ins_col_);
    bool seven = false;
    int fraction_bits = 0;
    auto read_number = [&](double& out) -> bool {
        std::int64_t value = 0, scale = 1;
        while (!cur_.done()) {
            const auto b = static_cast<unsigned char>(cur_.peek());
            std::int64_t digit;
            bool last;
            if (seven) {
                if (b >= 63 && b <= 94) { digit = b - 63; last = false; }
                else if (b >= 95 && b <= 126) { digit = b - 95; last = true; }
                else return false;
            } else {
                if (b >= 63 && b <= 126) { digit = b - 63; last = false; }
                else if (b >= 191 && b <= 254) { digit = b - 191; last = true; }
                else return false;
            }
            cur_.advance();
            value += digit * scale;
            scale *= seven ? 32 : 64;
            if (scale > (std::int64_t{1} << 50)) return false;
            if (last) {
                const std::int64_t mag = value >> 1;
                out = (value & 1) ? -static_cast<double>(mag) : static_cast<double>(mag);
                return true;
            }
        }
        return false;
    };
    bool up_next = false, abs_next = false;
    const bool was_down = pen_down_;
    while (!cur_.done() && cur_.peek() != ';') {
        const char c = cur_.peek();
        if (is_space(c)) { cur_.advance(); continue; }
        if (c == '7') { seven = true; cur_.advance(); continue; }
        if (c == ':' || c == '>') {
            cur_.advance();
            double v = 0;
            if (!read_number(v)) return make_error(Errc::syntax, at + ": malformed number in PE");
            if (c == ':') { lift(); pen_ = clamp_int(v, 0, 1000000); }
            else fraction_bits = clamp_int(v, 0, 60);
            continue;
        }
        if (c == '<') { up_next = true; cur_.advance(); continue; }
        if (c == '=') { abs_next = true; cur_.advance(); continue; }
        double x = 0, y = 0;
        if (!read_number(x) || !read_number(y))
            return make_error(Errc::syntax, at + ": malformed coordinate pair in PE");
        const double f = std::ldexp(1.0, -fraction_bits);
        x *= f;
        y *= f;
        const Pt target = abs_next ? to_plotter({x, y})
                                   : Pt{pos_.x + user_dx(x), pos_.y + user_dy(y)};
        pen_down_ = !up_next;
        if (auto r = move(target); !r) return r;
        up_next = abs_next = false;
    }
    pen_down_ = was_down;
    return {};
}

Result<void> Interpreter::instruction(const std::string& m, std::vector<Param>& params) {
    const std::string at = vec::place(opt_.source, ins_line_, ins_col_);
    auto num = [&](std::size_t i, double fallback) { return i < params.size() ? params[i].value : fallback; };
    const std::size_t n = params.size();

    if (m == "IN") {
        lift();
        defaults(true);
        pos_ = {0, 0};
        return {};
    }
    if (m == "DF") {
        lift();
        const Pt keep = pos_;
        const int pen = pen_, rot = rotation_;
        const Pt a = p1_, b = p2_;
        defaults(false);
        pos_ = keep;
        pen_ = pen;
        rotation_ = rot;
        p1_ = a;
        p2_ = b;
        return {};
    }
    if (m == "PU" || m == "PD" || m == "PA" || m == "PR") {
        if (n % 2 != 0)
            return make_error(Errc::syntax, at + ": odd number of coordinates (" +
                                                std::to_string(n) + ") in " + m);
        if (m == "PU") { pen_down_ = false; lift(); }
        if (m == "PD") pen_down_ = true;
        if (m == "PA") absolute_ = true;
        if (m == "PR") absolute_ = false;
        for (std::size_t k = 0; k < n; k += 2) {
            ins_line_ = params[k].line;
            ins_col_ = params[k].column;
            const Pt target = absolute_ ? to_plotter({params[k].value, params[k + 1].value})
                                        : Pt{pos_.x + user_dx(params[k].value),
                                             pos_.y + user_dy(params[k + 1].value)};
            if (auto r = move(target); !r) return r;
            if (symbol_ != 0)
                if (auto r = draw_text(std::string(1, symbol_), true); !r) return r;
        }
        return {};
    }
    if (m == "SP") {
        lift();
        pen_ = clamp_int(num(0, 0), 0, 1000000);
        return {};
    }
    if (m == "IP" || m == "IR") {
        const Pt old1 = p1_, old2 = p2_;
        if (n == 0) {
            p1_ = {0, 0};
            p2_ = {kHardX, kHardY};
        } else if (m == "IP") {
            p1_ = {num(0, 0), num(1, 0)};
            p2_ = n >= 4 ? Pt{num(2, 0), num(3, 0)} : Pt{p1_.x + old2.x - old1.x, p1_.y + old2.y - old1.y};
        } else {  // percentages of the hard-clip limits, here P1-P2 of IN
            p1_ = {num(0, 0) / 100 * kHardX, num(1, 0) / 100 * kHardY};
            p2_ = n >= 4 ? Pt{num(2, 0) / 100 * kHardX, num(3, 0) / 100 * kHardY}
                         : Pt{p1_.x + old2.x - old1.x, p1_.y + old2.y - old1.y};
        }
        if (scaled_) return instruction_sc_again();
        return {};
    }
    if (m == "SC") {
        if (n == 0) {
            scaled_ = false;
            return {};
        }
        if (n < 4) return make_error(Errc::syntax, at + ": SC wants 0 or 4 or more parameters");
        sc_params_.assign(params.begin(), params.end());
        return instruction_sc_again();
    }
    if (m == "IW") {
        if (n == 0) {
            window_ = false;
            return {};
        }
        if (n != 4) return make_error(Errc::syntax, at + ": IW wants 0 or 4 parameters");
        const Pt a = to_plotter({num(0, 0), num(1, 0)}), b = to_plotter({num(2, 0), num(3, 0)});
        win_lo_ = {std::min(a.x, b.x), std::min(a.y, b.y)};
        win_hi_ = {std::max(a.x, b.x), std::max(a.y, b.y)};
        window_ = true;
        lift();
        return {};
    }
    if (m == "RO") {
        const int r = clamp_int(num(0, 0), -3600, 3600);
        rotation_ = ((r % 360) + 360) % 360 / 90 * 90;
        lift();
        return {};
    }
    if (m == "CT") return {};
    if (m == "CI") {
        if (n < 1) return make_error(Errc::syntax, at + ": CI wants a radius");
        const double saved = chord_;
        if (n >= 2) chord_ = num(1, 5);
        const Pt c = to_user(pos_);
        auto r = stroke(arc_points(c, num(0, 0), 0, 360));
        chord_ = saved;
        return r;
    }
    if (m == "AA" || m == "AR") {
        if (n < 3) return make_error(Errc::syntax, at + ": " + m + " wants a centre and an angle");
        const Pt here = to_user(pos_);
        const Pt c = m == "AA" ? Pt{num(0, 0), num(1, 0)} : Pt{here.x + num(0, 0), here.y + num(1, 0)};
        const double saved = chord_;
        if (n >= 4) chord_ = num(3, 5);
        const double r = std::hypot(here.x - c.x, here.y - c.y);
        const double a0 = std::atan2(here.y - c.y, here.x - c.x) * 180 / kPi;
        auto pts = arc_points(c, r, a0, num(2, 0));
        chord_ = saved;
        for (std::size_t i = 1; i < pts.size(); ++i)
            if (auto e = move(pts[i]); !e) return e;
        return {};
    }
    if (m == "AT" || m == "RT") {
        if (n < 4) return make_error(Errc::syntax, at + ": " + m + " wants two points");
        const Pt a = to_user(pos_);
        Pt b{num(0, 0), num(1, 0)}, e{num(2, 0), num(3, 0)};
        if (m == "RT") {
            b = {a.x + b.x, a.y + b.y};
            e = {a.x + e.x, a.y + e.y};
        }
        // the circle through a, b, e
        const double d = 2 * (a.x * (b.y - e.y) + b.x * (e.y - a.y) + e.x * (a.y - b.y));
        if (std::abs(d) < 1e-12) return move(to_plotter(e));  // collinear: a line
        const double a2 = a.x * a.x + a.y * a.y, b2 = b.x * b.x + b.y * b.y, e2 = e.x * e.x + e.y * e.y;
        const Pt c{(a2 * (b.y - e.y) + b2 * (e.y - a.y) + e2 * (a.y - b.y)) / d,
                   (a2 * (e.x - b.x) + b2 * (a.x - e.x) + e2 * (b.x - a.x)) / d};
        auto ang = [&](Pt p) { return std::atan2(p.y - c.y, p.x - c.x) * 180 / kPi; };
        const double a0 = ang(a);
        auto norm = [](double x) { return std::fmod(std::fmod(x, 360) + 360, 360); };
        const double to_b = norm(ang(b) - a0), to_e = norm(ang(e) - a0);
        const double sweep = to_b < to_e ? to_e : to_e - 360;  // through b
        const double saved = chord_;
        if (n >= 5) chord_ = num(4, 5);
        auto pts = arc_points(c, std::hypot(a.x - c.x, a.y - c.y), a0, sweep);
        chord_ = saved;
        pts.back() = to_plotter(e);
        for (std::size_t i = 1; i < pts.size(); ++i)
            if (auto r = move(pts[i]); !r) return r;
        return {};
    }
    if (m == "EW" || m == "WG") {
        if (n < 3) return make_error(Errc::syntax, at + ": " + m + " wants a radius and two angles");
        const Pt c = to_user(pos_);
        const double saved = chord_;
        if (n >= 4) chord_ = num(3, 5);
        auto pts = arc_points(c, num(0, 0), num(1, 0), num(2, 0));
        chord_ = saved;
        pts.insert(pts.begin(), pos_);
        pts.push_back(pos_);
        return stroke(pts);
    }
    if (m == "EA" || m == "ER" || m == "RA" || m == "RR") {
        if (n < 2) return make_error(Errc::syntax, at + ": " + m + " wants a corner");
        const Pt a = to_user(pos_);
        const Pt b = (m == "EA" || m == "RA") ? Pt{num(0, 0), num(1, 0)}
                                              : Pt{a.x + num(0, 0), a.y + num(1, 0)};
        return stroke({to_plotter(a), to_plotter({b.x, a.y}), to_plotter(b), to_plotter({a.x, b.y}),
                       to_plotter(a)});
    }
    if (m == "BZ" || m == "BR") {
        if (n % 6 != 0) return make_error(Errc::syntax, at + ": " + m + " wants sets of three points");
        for (std::size_t k = 0; k < n; k += 6) {
            const Pt p0 = to_user(pos_);
            Pt c[3];
            for (int j = 0; j < 3; ++j) {
                c[j] = {params[k + 2 * j].value, params[k + 2 * j + 1].value};
                if (m == "BR") c[j] = {p0.x + c[j].x, p0.y + c[j].y};
            }
            for (int s = 1; s <= 16; ++s) {
                const double t = s / 16.0, u = 1 - t;
                const Pt q{u * u * u * p0.x + 3 * u * u * t * c[0].x + 3 * u * t * t * c[1].x + t * t * t * c[2].x,
                           u * u * u * p0.y + 3 * u * u * t * c[0].y + 3 * u * t * t * c[1].y + t * t * t * c[2].y};
                if (auto r = move(to_plotter(q)); !r) return r;
            }
        }
        return {};
    }
    if (m == "PM") {
        const int mode = clamp_int(num(0, 0), 0, 2);
        if (mode == 0) {
            lift();
            polygon_ = true;
            poly_.clear();
            poly_new_ = true;
        } else if (mode == 1) {
            poly_new_ = true;
        } else if (mode == 2) {
            polygon_ = false;
        }
        return {};
    }
    if (m == "EP" || m == "FP") {
        const bool was = polygon_;
        polygon_ = false;
        for (std::vector<Pt> s : poly_) {
            if (s.size() < 2) continue;
            if (s.front().x != s.back().x || s.front().y != s.back().y) s.push_back(s.front());
            if (auto r = stroke(s); !r) return r;
        }
        polygon_ = was;
        return {};
    }
    if (m == "CP") {
        const Pt size = char_size();
        const double len = std::hypot(label_dir_.x, label_dir_.y);
        const Pt u = len > 0 ? Pt{label_dir_.x / len, label_dir_.y / len} : Pt{1, 0};
        lift();
        if (n == 0) {  // carriage return and line feed
            pos_ = {label_start_.x - 2 * size.y * -u.y, label_start_.y - 2 * size.y * u.x};
            label_start_ = pos_;
            return {};
        }
        const double sx = num(0, 0) * 1.5 * size.x, ly = num(1, 0) * 2 * size.y;
        pos_ = {pos_.x + sx * u.x - ly * u.y, pos_.y + sx * u.y + ly * u.x};
        return {};
    }
    if (m == "DI" || m == "DR") {
        if (n < 2) {
            label_dir_ = {1, 0};
            return {};
        }
        label_dir_ = {num(0, 1), num(1, 0)};
        if (m == "DR") label_dir_ = {label_dir_.x * (p2_.x - p1_.x), label_dir_.y * (p2_.y - p1_.y)};
        return {};
    }
    if (m == "SI" || m == "SR") {
        size_relative_ = m == "SR";
        if (n < 2) size_ = size_relative_ ? Pt{0.75, 1.5} : Pt{0.19, 0.27};
        else size_ = {num(0, 0), num(1, 0)};
        return {};
    }
    if (m == "SL") {
        slant_ = num(0, 0);
        return {};
    }
    if (m == "ES") {
        extra_ = {num(0, 0), num(1, 0)};
        return {};
    }
    if (m == "LO") {
        label_origin_ = clamp_int(num(0, 1), 1, 19);
        if (label_origin_ < 1 || label_origin_ > 19 || label_origin_ == 10) label_origin_ = 1;
        return {};
    }
    if (no_effect(m)) return {};
    return make_error(Errc::unsupported, at + ": unsupported instruction '" + m + "'");
}

Result<void> Interpreter::instruction_sc_again() {
    const std::vector<Param>& p = sc_params_;
    auto v = [&](std::size_t i, double fallback) { return i < p.size() ? p[i].value : fallback; };
    const int type = clamp_int(v(4, 0), 0, 2);
    const double xmin = v(0, 0), ymin = v(2, 0);
    const double dx = p2_.x - p1_.x, dy = p2_.y - p1_.y;
    sc_min_ = {xmin, ymin};
    sc_offset_ = {0, 0};
    if (type == 2) {  // point factor: xmin, xfactor, ymin, yfactor
        sc_factor_ = {v(1, 1), v(3, 1)};
    } else {
        const double xmax = v(1, 1), ymax = v(3, 1);
        if (xmax == xmin || ymax == ymin)
            return make_error(Errc::syntax, vec::place(opt_.source, ins_line_, ins_col_) +
                                                ": SC with an empty range");
        sc_factor_ = {dx / (xmax - xmin), dy / (ymax - ymin)};
        if (type == 1) {  // isotropic, placed by left / bottom percentages
            const double f = std::min(std::abs(sc_factor_.x), std::abs(sc_factor_.y));
            const Pt iso{std::copysign(f, sc_factor_.x), std::copysign(f, sc_factor_.y)};
            const double left = v(5, 50) / 100, bottom = v(6, 50) / 100;
            sc_offset_ = {(dx - iso.x * (xmax - xmin)) * left, (dy - iso.y * (ymax - ymin)) * bottom};
            sc_factor_ = iso;
        }
    }
    scaled_ = true;
    return {};
}

Result<Drawing> Interpreter::run() {
    const std::string& src = opt_.source;
    while (true) {
        while (!cur_.done() && (is_space(cur_.peek()) || cur_.peek() == ';')) cur_.advance();
        if (cur_.done()) break;
        ins_line_ = cur_.line;
        ins_col_ = cur_.column();
        const std::string at = vec::place(src, ins_line_, ins_col_);
        const char a = cur_.peek();
        if (a == '\x1b') {
            if (auto r = skip_escape(); !r) return std::move(r).error();
            continue;
        }
        if (a == '\x03' || a == '\0') {  // stray terminators between instructions
            cur_.advance();
            continue;
        }
        if (!is_alpha(a))
            return make_error(Errc::syntax, at + ": unexpected character " + vec::describe_char(a));
        cur_.advance();
        if (cur_.done() || !is_alpha(cur_.peek()))
            return make_error(Errc::syntax, at + ": incomplete instruction '" + std::string(1, a) + "'");
        const std::string m{static_cast<char>(std::toupper(static_cast<unsigned char>(a))),
                            static_cast<char>(std::toupper(static_cast<unsigned char>(cur_.peek())))};
        cur_.advance();
        if (m == "LB" || m == "BL") {
            // Text up to the label terminator (DT; ETX by default).
            std::string text;
            while (!cur_.done() && cur_.peek() != terminator_) {
                text += cur_.peek();
                cur_.advance();
            }
            if (cur_.done())
                return make_error(Errc::syntax, at + ": label (" + m + ") not ended by " +
                                                    (terminator_ == '\x03' ? std::string("ETX (0x03)")
                                                                           : vec::describe_char(terminator_)));
            cur_.advance();
            if (m == "LB")
                if (auto r = draw_text(text, false); !r) return std::move(r).error();
            continue;
        }
        if (m == "CO") {  // comment: "quoted", or up to ';'
            while (!cur_.done() && is_space(cur_.peek())) cur_.advance();
            const char close = !cur_.done() && cur_.peek() == '"' ? '"' : ';';
            if (close == '"') cur_.advance();
            while (!cur_.done() && cur_.peek() != close) cur_.advance();
            if (cur_.done() && close == '"')
                return make_error(Errc::syntax, at + ": comment (CO) not ended by '\"'");
            if (!cur_.done()) cur_.advance();
            continue;
        }
        if (m == "DT") {  // DT t[,mode]: the label terminator
            if (!cur_.done() && cur_.peek() != ';') {
                terminator_ = cur_.peek();
                cur_.advance();
                while (!cur_.done() && cur_.peek() != ';' && !is_alpha(cur_.peek()) &&
                       cur_.peek() != '\x1b')
                    cur_.advance();  // ",mode"
            } else {
                terminator_ = '\x03';
            }
            continue;
        }
        if (m == "SM") {  // SM c: symbol mode; SM; or SM alone ends it
            symbol_ = 0;
            if (!cur_.done() && cur_.peek() != ';' && !is_space(cur_.peek())) {
                symbol_ = cur_.peek();
                cur_.advance();
            }
            continue;
        }
        if (m == "PE") {
            if (auto r = encoded_polyline(); !r) return std::move(r).error();
            continue;
        }
        auto params = numbers(m);
        if (!params) return std::move(params).error();
        if (auto r = instruction(m, *params); !r) return std::move(r).error();
    }
    return std::move(drawing_);
}

}  // namespace

Result<Drawing> read_hpgl(std::string_view text, const VectorReadOptions& options) {
    Interpreter it(text, options);
    return it.run();
}

}  // namespace stepzip
