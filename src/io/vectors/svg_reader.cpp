// stepzip — SVG reader: the stroked geometry of an SVG file as pen-down
// paths (docs/cli.md, "SVG input").
//
// A small strict XML tokenizer (elements, attributes, comments, CDATA,
// processing instructions, a DOCTYPE without internal subset, the five
// predefined entities and character references) feeds an interpreter that
// keeps a stack of transforms. Shapes are turned into path commands; each
// command is mapped to step space (the current transform, then the root's
// y flip and unit scale) before flattening, so the tolerance is in steps:
// Beziers are subdivided until their control points lie within it of the
// chord (the curve lies in their convex hull), elliptical arcs are cut into
// chords whose sagitta, scaled by the largest stretch of the transform,
// is within it. Vertices are then rounded to the nearest step.
// Complexity: O(bytes + flattened vertices).
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <numbers>
#include <optional>
#include <variant>
#include <string>
#include <vector>

#include "gcode_units.hpp"
#include "stepzip/vectors.hpp"

namespace stepzip {

namespace {

constexpr double kPi = std::numbers::pi;

struct Pt {
    double x = 0, y = 0;
};

// An affine map: x' = a x + c y + e, y' = b x + d y + f.
struct Affine {
    double a = 1, b = 0, c = 0, d = 1, e = 0, f = 0;
    Pt operator()(Pt p) const { return {a * p.x + c * p.y + e, b * p.x + d * p.y + f}; }
    // (*this) after `inner`: points go through `inner` first.
    Affine then(const Affine& inner) const {
        return {a * inner.a + c * inner.b, b * inner.a + d * inner.b,
                a * inner.c + c * inner.d, b * inner.c + d * inner.d,
                a * inner.e + c * inner.f + e, b * inner.e + d * inner.f + f};
    }
    // Largest singular value of the linear part.
    double stretch() const {
        const double s = a * a + b * b + c * c + d * d, det = a * d - b * c;
        return std::sqrt((s + std::sqrt(std::max(0.0, s * s - 4 * det * det))) / 2);
    }
};

struct Attr {
    std::string name, value;
    std::size_t offset = 0;  // of the value's first character in the text
};

struct Element {
    std::string name;
    std::vector<Attr> attrs;
    std::size_t offset = 0;  // of '<'
    bool self_closing = false;
    const Attr* find(std::string_view n) const {
        for (const Attr& a : attrs)
            if (a.name == n) return &a;
        return nullptr;
    }
};

// An error at a byte offset of the text.
struct Fail {
    Errc code;
    std::size_t offset;
    std::string what;
};

// A value or a Fail (errors are placed by offset, turned into line:column
// once, when reported).
template <class T>
class [[nodiscard]] Res {
public:
    Res(T v) : v_(std::move(v)) {}
    Res(Fail f) : v_(std::move(f)) {}
    explicit operator bool() const { return v_.index() == 0; }
    T& operator*() { return std::get<0>(v_); }
    Fail& error() & { return std::get<1>(v_); }
    Fail&& error() && { return std::get<1>(std::move(v_)); }

private:
    std::variant<T, Fail> v_;
};
template <>
class [[nodiscard]] Res<void> {
public:
    Res() = default;
    Res(Fail f) : f_(std::move(f)) {}
    explicit operator bool() const { return !f_; }
    Fail& error() & { return *f_; }
    Fail&& error() && { return std::move(*f_); }

private:
    std::optional<Fail> f_;
};

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
bool is_name_char(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == ':' || c == '-' ||
           c == '.' || static_cast<unsigned char>(c) >= 0x80;
}

// ---- numbers (SVG grammar: sign, digits, '.', digits, exponent) ----------
// Scans a number at s[i]; on success stores it and advances i.
bool scan_number(std::string_view s, std::size_t& i, double& out) {
    std::size_t j = i;
    if (j < s.size() && (s[j] == '+' || s[j] == '-')) ++j;
    const std::size_t digits0 = j;
    while (j < s.size() && std::isdigit(static_cast<unsigned char>(s[j]))) ++j;
    bool any = j > digits0;
    if (j < s.size() && s[j] == '.') {
        const std::size_t f0 = ++j;
        while (j < s.size() && std::isdigit(static_cast<unsigned char>(s[j]))) ++j;
        any = any || j > f0;
    }
    if (!any) return false;
    if (j < s.size() && (s[j] == 'e' || s[j] == 'E')) {
        std::size_t k = j + 1;
        if (k < s.size() && (s[k] == '+' || s[k] == '-')) ++k;
        const std::size_t e0 = k;
        while (k < s.size() && std::isdigit(static_cast<unsigned char>(s[k]))) ++k;
        if (k > e0) j = k;
    }
    const char* b = s.data() + i + (s[i] == '+' ? 1 : 0);
    auto [p, ec] = std::from_chars(b, s.data() + j, out);
    if (ec != std::errc() || !std::isfinite(out)) return false;
    (void)p;
    i = j;
    return true;
}

void skip_sep(std::string_view s, std::size_t& i) {
    while (i < s.size() && is_space(s[i])) ++i;
    if (i < s.size() && s[i] == ',') {
        ++i;
        while (i < s.size() && is_space(s[i])) ++i;
    }
}

// A list of numbers separated by white space and/or commas.
bool number_list(std::string_view s, std::vector<double>& out, std::size_t& bad) {
    std::size_t i = 0;
    while (i < s.size() && is_space(s[i])) ++i;
    while (i < s.size()) {
        double v;
        if (!scan_number(s, i, v)) {
            bad = i;
            return false;
        }
        out.push_back(v);
        skip_sep(s, i);
    }
    return true;
}

// A length: a number and an optional absolute unit, in user units (px).
bool length(std::string_view s, double& out) {
    std::size_t i = 0;
    while (i < s.size() && is_space(s[i])) ++i;
    if (!scan_number(s, i, out)) return false;
    std::string_view unit = s.substr(i);
    while (!unit.empty() && is_space(unit.back())) unit.remove_suffix(1);
    static constexpr struct { const char* name; double px; } kUnits[] = {
        {"", 1}, {"px", 1}, {"mm", 96 / 25.4}, {"cm", 96 / 2.54}, {"in", 96}, {"pt", 96.0 / 72},
        {"pc", 16}};
    for (const auto& u : kUnits)
        if (unit == u.name) {
            out *= u.px;
            return true;
        }
    return false;
}

// ---- XML -----------------------------------------------------------------
class Tokenizer {
public:
    explicit Tokenizer(std::string_view t) : t_(t) {}

    enum class Kind { start, end, eof };
    // The next element start or end tag; text, comments, CDATA, processing
    // instructions and the DOCTYPE are skipped.
    Res<Kind> next(Element& el) {
        for (;;) {
            const std::size_t lt = t_.find('<', pos_);
            if (lt == std::string_view::npos) {
                pos_ = t_.size();
                return Kind::eof;
            }
            if (auto r = check_text(pos_, lt); !r) return std::move(r).error();
            pos_ = lt;
            std::string_view rest = t_.substr(pos_);
            if (rest.starts_with("<!--")) {
                if (auto r = skip_to("-->", "unterminated comment"); !r) return std::move(r).error();
            } else if (rest.starts_with("<![CDATA[")) {
                if (auto r = skip_to("]]>", "unterminated CDATA section"); !r)
                    return std::move(r).error();
            } else if (rest.starts_with("<?")) {
                if (auto r = skip_to("?>", "unterminated processing instruction"); !r)
                    return std::move(r).error();
            } else if (rest.starts_with("<!DOCTYPE")) {
                const std::size_t gt = t_.find('>', pos_);
                const std::size_t br = t_.find('[', pos_);
                if (br != std::string_view::npos && (gt == std::string_view::npos || br < gt))
                    return Fail{Errc::unsupported, br, "DOCTYPE with an internal subset"};
                if (gt == std::string_view::npos)
                    return Fail{Errc::syntax, pos_, "unterminated DOCTYPE"};
                pos_ = gt + 1;
            } else if (rest.starts_with("</")) {
                el = {};
                el.offset = pos_;
                pos_ += 2;
                el.name = name();
                if (el.name.empty()) return Fail{Errc::syntax, pos_, "expected an element name"};
                skip_space();
                if (pos_ >= t_.size() || t_[pos_] != '>')
                    return Fail{Errc::syntax, pos_, "expected '>'"};
                ++pos_;
                return Kind::end;
            } else {
                return start_tag(el);
            }
        }
    }
    std::size_t pos() const { return pos_; }

private:
    // Character data: only '&' needs to be well formed ('<' cannot occur).
    Res<void> check_text(std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i)
            if (t_[i] == '&') {
                std::string tmp;
                std::size_t j = i;
                if (auto r = entity(j, tmp); !r) return std::move(r).error();
                i = j - 1;
            }
        return {};
    }
    Res<void> skip_to(std::string_view end, const char* what) {
        const std::size_t k = t_.find(end, pos_ + 2);
        if (k == std::string_view::npos) return Fail{Errc::syntax, pos_, what};
        pos_ = k + end.size();
        return {};
    }
    void skip_space() {
        while (pos_ < t_.size() && is_space(t_[pos_])) ++pos_;
    }
    std::string name() {
        const std::size_t b = pos_;
        while (pos_ < t_.size() && is_name_char(t_[pos_])) ++pos_;
        return std::string(t_.substr(b, pos_ - b));
    }
    // An entity or character reference at t_[i] == '&'; appends its text.
    Res<void> entity(std::size_t& i, std::string& out) {
        const std::size_t semi = t_.find(';', i);
        if (semi == std::string_view::npos || semi - i > 12)
            return Fail{Errc::syntax, i, "'&' that starts no entity"};
        const std::string_view ref = t_.substr(i + 1, semi - i - 1);
        static constexpr struct { const char* name; char c; } kEnt[] = {
            {"amp", '&'}, {"lt", '<'}, {"gt", '>'}, {"quot", '"'}, {"apos", '\''}};
        for (const auto& e : kEnt)
            if (ref == e.name) {
                out += e.c;
                i = semi + 1;
                return {};
            }
        if (ref.size() >= 2 && ref[0] == '#') {
            unsigned long code = 0;
            const bool hex = ref[1] == 'x';
            const std::string_view digits = ref.substr(hex ? 2 : 1);
            auto [p, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), code,
                                           hex ? 16 : 10);
            if (ec == std::errc() && p == digits.data() + digits.size() && !digits.empty() &&
                code > 0 && code <= 0x10FFFF) {
                // Only ASCII matters to the geometry; others become '?'.
                out += code < 0x80 ? static_cast<char>(code) : '?';
                i = semi + 1;
                return {};
            }
        }
        return Fail{Errc::syntax, i, "unknown entity '&" + std::string(ref) + ";'"};
    }
    Res<Kind> start_tag(Element& el) {
        el = {};
        el.offset = pos_;
        ++pos_;
        el.name = name();
        if (el.name.empty()) return Fail{Errc::syntax, pos_, "expected an element name"};
        for (;;) {
            const std::size_t before = pos_;
            skip_space();
            if (pos_ >= t_.size()) return Fail{Errc::syntax, el.offset, "unterminated tag"};
            if (t_[pos_] == '>') {
                ++pos_;
                return Kind::start;
            }
            if (t_.substr(pos_).starts_with("/>")) {
                pos_ += 2;
                el.self_closing = true;
                return Kind::start;
            }
            if (pos_ == before) return Fail{Errc::syntax, pos_, "expected white space"};
            Attr a;
            const std::size_t name_at = pos_;
            a.name = name();
            if (a.name.empty())
                return Fail{Errc::syntax, pos_, std::string("unexpected '") + t_[pos_] + "' in a tag"};
            skip_space();
            if (pos_ >= t_.size() || t_[pos_] != '=')
                return Fail{Errc::syntax, pos_, "expected '=' after attribute '" + a.name + "'"};
            ++pos_;
            skip_space();
            if (pos_ >= t_.size() || (t_[pos_] != '"' && t_[pos_] != '\''))
                return Fail{Errc::syntax, pos_, "expected a quoted attribute value"};
            const char q = t_[pos_++];
            a.offset = pos_;
            for (;;) {
                if (pos_ >= t_.size())
                    return Fail{Errc::syntax, a.offset - 1, "unterminated attribute value"};
                const char c = t_[pos_];
                if (c == q) break;
                if (c == '<') return Fail{Errc::syntax, pos_, "'<' in an attribute value"};
                if (c == '&') {
                    if (auto r = entity(pos_, a.value); !r) return std::move(r).error();
                    continue;
                }
                a.value += is_space(c) ? ' ' : c;
                ++pos_;
            }
            ++pos_;
            if (el.find(a.name))
                return Fail{Errc::syntax, name_at, "repeated attribute '" + a.name + "'"};
            el.attrs.push_back(std::move(a));
        }
    }

    std::string_view t_;
    std::size_t pos_ = 0;
};

// ---- geometry --------------------------------------------------------------
class Reader {
public:
    Reader(std::string_view text, const VectorReadOptions& options) : text_(text), opt_(options) {}
    Result<Drawing> run();

private:
    struct Frame {
        Affine ctm;
        bool skip = false;  // inside an element whose content is not drawn
        int pen = 1;
        std::string name;
    };

    std::string where(std::size_t offset) const {
        std::size_t line = 1, ls = 0;
        for (std::size_t i = 0; i < offset && i < text_.size(); ++i)
            if (text_[i] == '\n') {
                ++line;
                ls = i + 1;
            }
        return vec::place(opt_.source, line, offset - ls + 1);
    }
    Error fail(const Fail& f) const { return make_error(f.code, where(f.offset) + ": " + f.what); }

    Res<void> root(const Element& el);
    Res<void> shape(const Element& el, const Affine& ctm, int pen);
    Res<void> path_data(const Attr& d);
    Res<Affine> transform(const Attr& t) const;

    // ---- output in step space ---------------------------------------------
    Res<void> emit(Pt p) {  // p in step space
        std::int64_t v[2];
        const double s[2] = {std::round(p.x), std::round(p.y)};
        for (int a = 0; a < 2; ++a) {
            if (!(std::abs(s[a]) <= static_cast<double>(kMaxVectorCoord)))
                return Fail{Errc::limit, at_, "coordinate beyond the limit of 2^30 steps"};
            v[a] = static_cast<std::int64_t>(s[a]);
        }
        if (!open_) {
            cur_path_ = VectorPath{v[0], v[1], {}, pen_};
            open_ = true;
            return {};
        }
        const std::int64_t lx = cur_path_.moves.empty() ? cur_path_.x0 : cur_path_.moves.back().x;
        const std::int64_t ly = cur_path_.moves.empty() ? cur_path_.y0 : cur_path_.moves.back().y;
        if (v[0] == lx && v[1] == ly) return {};
        VectorMove mv;
        mv.x = v[0];
        mv.y = v[1];
        // Line and column of the element or command (offsets mostly grow).
        if (at_ < lc_off_) lc_off_ = lc_line_ = lc_ls_ = 0;
        if (lc_line_ == 0) lc_line_ = 1;
        for (; lc_off_ < at_ && lc_off_ < text_.size(); ++lc_off_)
            if (text_[lc_off_] == '\n') {
                ++lc_line_;
                lc_ls_ = lc_off_ + 1;
            }
        const std::size_t line = lc_line_, ls = lc_ls_;
        mv.line = static_cast<std::uint32_t>(line);
        mv.column = static_cast<std::uint32_t>(at_ - ls + 1);
        cur_path_.moves.push_back(mv);
        return {};
    }
    void end_chain() {
        if (open_ && !cur_path_.moves.empty()) drawing_.push_back(std::move(cur_path_));
        open_ = false;
    }
    // Pen-down segments from the current point (user space).
    Res<void> start_if_needed() {
        if (!open_) return emit(map_(cur_));
        return {};
    }
    Res<void> line_to(Pt p) {
        if (auto r = start_if_needed(); !r) return r;
        cur_ = p;
        return emit(map_(p));
    }
    Res<void> cubic_to(Pt c1, Pt c2, Pt p) {
        if (auto r = start_if_needed(); !r) return r;
        const Pt q[4] = {map_(cur_), map_(c1), map_(c2), map_(p)};
        cur_ = p;
        if (auto r = flatten_cubic(q, 0); !r) return r;
        return emit(q[3]);
    }
    // Emits the interior vertices of a Bezier (step space); the end is the caller's.
    Res<void> flatten_cubic(const Pt q[4], int depth) {
        if (depth >= 24 || (dist_to_segment(q[1], q[0], q[3]) <= opt_.tolerance &&
                            dist_to_segment(q[2], q[0], q[3]) <= opt_.tolerance))
            return {};
        auto mid = [](Pt a, Pt b) { return Pt{(a.x + b.x) / 2, (a.y + b.y) / 2}; };
        const Pt ab = mid(q[0], q[1]), bc = mid(q[1], q[2]), cd = mid(q[2], q[3]);
        const Pt abc = mid(ab, bc), bcd = mid(bc, cd), m = mid(abc, bcd);
        const Pt left[4] = {q[0], ab, abc, m}, right[4] = {m, bcd, cd, q[3]};
        if (auto r = flatten_cubic(left, depth + 1); !r) return r;
        if (auto r = emit(m); !r) return r;
        return flatten_cubic(right, depth + 1);
    }
    static double dist_to_segment(Pt p, Pt a, Pt b) {
        const double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
        double t = l2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / l2 : 0;
        t = std::clamp(t, 0.0, 1.0);
        return std::hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy));
    }
    Res<void> arc_to(double rx, double ry, double phi_deg, bool large, bool sweep, Pt p);

    std::string_view text_;
    const VectorReadOptions& opt_;
    Drawing drawing_;
    VectorPath cur_path_;
    bool open_ = false;
    int pen_ = 1;
    Affine map_;          // user space of the element -> step space
    Pt cur_{}, start_{};  // current point and subpath start, user space
    std::size_t at_ = 0;  // offset of what is being drawn, for messages
    std::size_t lc_off_ = 0, lc_line_ = 0, lc_ls_ = 0;  // line/column cache of emit()
    Affine root_map_;     // root user space -> step space
};

Res<Affine> Reader::transform(const Attr& t) const {
    Affine m;
    const std::string_view s = t.value;
    std::size_t i = 0;
    auto bad = [&](std::size_t k, std::string what) {
        return Fail{Errc::syntax, t.offset + k, std::move(what)};
    };
    for (;;) {
        while (i < s.size() && (is_space(s[i]) || s[i] == ',')) ++i;
        if (i >= s.size()) return m;
        const std::size_t n0 = i;
        while (i < s.size() && std::isalpha(static_cast<unsigned char>(s[i]))) ++i;
        const std::string_view fn = s.substr(n0, i - n0);
        while (i < s.size() && is_space(s[i])) ++i;
        if (i >= s.size() || s[i] != '(') return bad(i, "expected '(' in transform");
        ++i;
        std::vector<double> v;
        while (i < s.size() && is_space(s[i])) ++i;
        while (i < s.size() && s[i] != ')') {
            double x;
            if (!scan_number(s, i, x)) return bad(i, "malformed number in transform");
            v.push_back(x);
            skip_sep(s, i);
        }
        if (i >= s.size()) return bad(n0, "unterminated transform function");
        ++i;
        const std::size_t k = v.size();
        Affine f;
        auto arity = [&](std::size_t lo, std::size_t hi) { return k >= lo && k <= hi; };
        if (fn == "matrix" && k == 6) {
            f = {v[0], v[1], v[2], v[3], v[4], v[5]};
        } else if (fn == "translate" && arity(1, 2)) {
            f.e = v[0];
            f.f = k == 2 ? v[1] : 0;
        } else if (fn == "scale" && arity(1, 2)) {
            f.a = v[0];
            f.d = k == 2 ? v[1] : v[0];
        } else if (fn == "rotate" && (k == 1 || k == 3)) {
            const double r = v[0] * kPi / 180, cs = std::cos(r), sn = std::sin(r);
            f = {cs, sn, -sn, cs, 0, 0};
            if (k == 3) {  // about (cx, cy)
                const Affine to{1, 0, 0, 1, v[1], v[2]}, back{1, 0, 0, 1, -v[1], -v[2]};
                f = to.then(f).then(back);
            }
        } else if (fn == "skewX" && k == 1) {
            f.c = std::tan(v[0] * kPi / 180);
        } else if (fn == "skewY" && k == 1) {
            f.b = std::tan(v[0] * kPi / 180);
        } else {
            return bad(n0, "unknown transform '" + std::string(fn) + "' with " +
                               std::to_string(k) + " argument(s)");
        }
        m = m.then(f);
    }
}

Res<void> Reader::arc_to(double rx, double ry, double phi_deg, bool large, bool sweep,
                                  Pt p) {
    const Pt p0 = cur_;
    if (p0.x == p.x && p0.y == p.y) return {};
    rx = std::abs(rx);
    ry = std::abs(ry);
    if (rx == 0 || ry == 0) return line_to(p);
    // Endpoint to centre parameterization (SVG 1.1, appendix F.6.5).
    const double phi = std::fmod(phi_deg, 360) * kPi / 180, cs = std::cos(phi), sn = std::sin(phi);
    const double hx = (p0.x - p.x) / 2, hy = (p0.y - p.y) / 2;
    const double x1 = cs * hx + sn * hy, y1 = -sn * hx + cs * hy;
    const double lambda = x1 * x1 / (rx * rx) + y1 * y1 / (ry * ry);
    if (lambda > 1) {
        rx *= std::sqrt(lambda);
        ry *= std::sqrt(lambda);
    }
    const double num = rx * rx * ry * ry - rx * rx * y1 * y1 - ry * ry * x1 * x1;
    const double den = rx * rx * y1 * y1 + ry * ry * x1 * x1;
    double coef = den > 0 ? std::sqrt(std::max(0.0, num / den)) : 0;
    if (large == sweep) coef = -coef;
    const double cxp = coef * rx * y1 / ry, cyp = -coef * ry * x1 / rx;
    const double cx = cs * cxp - sn * cyp + (p0.x + p.x) / 2;
    const double cy = sn * cxp + cs * cyp + (p0.y + p.y) / 2;
    const double t1 = std::atan2((y1 - cyp) / ry, (x1 - cxp) / rx);
    double dt = std::atan2((-y1 - cyp) / ry, (-x1 - cxp) / rx) - t1;
    if (sweep && dt < 0) dt += 2 * kPi;
    if (!sweep && dt > 0) dt -= 2 * kPi;
    // Chords: on the unit circle a chord of angle h has sagitta 1 - cos(h/2);
    // the arc is the image of that circle under `unit`, so its chords are
    // within stretch() times that.
    const Affine unit = map_.then(Affine{cs * rx, sn * rx, -sn * ry, cs * ry, cx, cy});
    const double ratio = opt_.tolerance / std::max(unit.stretch(), 1e-300);
    const double h = ratio >= 1 ? kPi / 2 : std::min(kPi / 2, 2 * std::acos(1 - ratio));
    const double n = std::min(1e6, std::max(1.0, std::ceil(std::abs(dt) / h)));
    if (auto r = start_if_needed(); !r) return r;
    const auto count = static_cast<long>(n);
    for (long k = 1; k < count; ++k) {
        const double t = t1 + dt * static_cast<double>(k) / n;
        if (auto r = emit(unit(Pt{std::cos(t), std::sin(t)})); !r) return r;
    }
    cur_ = p;
    return emit(map_(p));
}

Res<void> Reader::path_data(const Attr& d) {
    const std::string_view s = d.value;
    std::size_t i = 0;
    char cmd = 0;
    Pt last_ctrl{};       // reflected by S / T
    char last_kind = 0;   // 'C' after C/S, 'Q' after Q/T, else 0
    auto bad = [&](std::size_t k, std::string what) {
        return Fail{Errc::syntax, d.offset + k, std::move(what)};
    };
    auto skip_ws = [&] {
        while (i < s.size() && is_space(s[i])) ++i;
    };
    auto num = [&](double& v) -> bool {
        if (!scan_number(s, i, v)) return false;
        skip_sep(s, i);
        return true;
    };
    auto flag = [&](bool& v) -> bool {
        if (i >= s.size() || (s[i] != '0' && s[i] != '1')) return false;
        v = s[i++] == '1';
        skip_sep(s, i);
        return true;
    };
    skip_ws();
    bool first = true;
    while (i < s.size()) {
        const std::size_t cmd_at = i;
        if (std::isalpha(static_cast<unsigned char>(s[i]))) {
            cmd = s[i++];
            skip_ws();
            if (std::string_view("MmLlHhVvCcSsQqTtAaZz").find(cmd) == std::string_view::npos)
                return bad(cmd_at, std::string("unknown path command '") + cmd + "'");
        } else if (cmd == 0 || cmd == 'Z' || cmd == 'z') {
            return bad(i, "expected a path command");
        }
        if (first && cmd != 'M' && cmd != 'm') return bad(cmd_at, "path data must start with M");
        first = false;
        at_ = d.offset + cmd_at;
        const bool rel = std::islower(static_cast<unsigned char>(cmd)) != 0;
        const Pt o = rel ? cur_ : Pt{};
        const char up = static_cast<char>(std::toupper(static_cast<unsigned char>(cmd)));
        const std::size_t args_at = i;
        auto missing = [&] { return bad(args_at, std::string("missing or malformed arguments of '") + cmd + "'"); };
        char kind = 0;
        switch (up) {
        case 'M': {
            double x, y;
            if (!num(x) || !num(y)) return missing();
            end_chain();
            cur_ = start_ = {o.x + x, o.y + y};
            cmd = rel ? 'l' : 'L';  // further pairs are line-tos
            break;
        }
        case 'Z':
            if (open_) {
                if (auto r = line_to(start_); !r) return r;
            }
            end_chain();
            cur_ = start_;
            break;
        case 'L': {
            double x, y;
            if (!num(x) || !num(y)) return missing();
            if (auto r = line_to({o.x + x, o.y + y}); !r) return r;
            break;
        }
        case 'H': {
            double x;
            if (!num(x)) return missing();
            if (auto r = line_to({o.x + x, cur_.y}); !r) return r;
            break;
        }
        case 'V': {
            double y;
            if (!num(y)) return missing();
            if (auto r = line_to({cur_.x, o.y + y}); !r) return r;
            break;
        }
        case 'C':
        case 'S': {
            double v[6];
            Pt c1;
            int k0 = 0;
            if (up == 'S') {
                c1 = last_kind == 'C' ? Pt{2 * cur_.x - last_ctrl.x, 2 * cur_.y - last_ctrl.y} : cur_;
                k0 = 2;
            }
            for (int k = k0; k < 6; ++k)
                if (!num(v[k])) return missing();
            if (up == 'C') c1 = {o.x + v[0], o.y + v[1]};
            const Pt c2{o.x + v[2], o.y + v[3]}, p{o.x + v[4], o.y + v[5]};
            if (auto r = cubic_to(c1, c2, p); !r) return r;
            last_ctrl = c2;
            kind = 'C';
            break;
        }
        case 'Q':
        case 'T': {
            Pt c;
            double x, y;
            if (up == 'Q') {
                double cx, cy;
                if (!num(cx) || !num(cy)) return missing();
                c = {o.x + cx, o.y + cy};
            } else {
                c = last_kind == 'Q' ? Pt{2 * cur_.x - last_ctrl.x, 2 * cur_.y - last_ctrl.y} : cur_;
            }
            if (!num(x) || !num(y)) return missing();
            const Pt p0 = cur_, p{o.x + x, o.y + y};
            // The quadratic as a cubic (degree elevation, exact).
            const Pt c1{p0.x + 2 * (c.x - p0.x) / 3, p0.y + 2 * (c.y - p0.y) / 3};
            const Pt c2{p.x + 2 * (c.x - p.x) / 3, p.y + 2 * (c.y - p.y) / 3};
            if (auto r = cubic_to(c1, c2, p); !r) return r;
            last_ctrl = c;
            kind = 'Q';
            break;
        }
        case 'A': {
            double rx, ry, rot, x, y;
            bool large, sweep;
            if (!num(rx) || !num(ry) || !num(rot) || !flag(large) || !flag(sweep) || !num(x) ||
                !num(y))
                return missing();
            if (auto r = arc_to(rx, ry, rot, large, sweep, {o.x + x, o.y + y}); !r) return r;
            break;
        }
        default:
            return bad(cmd_at, "unknown path command");
        }
        last_kind = kind;
        skip_ws();
    }
    end_chain();
    return {};
}

Res<void> Reader::shape(const Element& el, const Affine& ctm, int pen) {
    map_ = ctm;
    pen_ = pen;
    at_ = el.offset;
    auto len = [&](const char* name, double def, double& out) -> Res<void> {
        const Attr* a = el.find(name);
        if (!a) {
            out = def;
            return {};
        }
        if (!length(a->value, out))
            return Fail{Errc::unsupported, a->offset,
                        std::string("attribute '") + name + "': expected a number with an "
                        "optional unit px mm cm in pt pc (percentages are not read)"};
        return {};
    };
#define SVG_LEN(name, def, var) \
    double var;                 \
    if (auto r = len(name, def, var); !r) return r
    const std::string& n = el.name;
    if (n == "path") {
        const Attr* d = el.find("d");
        if (!d) return {};
        return path_data(*d);
    }
    if (n == "line") {
        SVG_LEN("x1", 0, x1);
        SVG_LEN("y1", 0, y1);
        SVG_LEN("x2", 0, x2);
        SVG_LEN("y2", 0, y2);
        cur_ = {x1, y1};
        if (auto r = line_to({x2, y2}); !r) return r;
        end_chain();
        return {};
    }
    if (n == "polyline" || n == "polygon") {
        const Attr* a = el.find("points");
        if (!a) return {};
        std::vector<double> v;
        std::size_t badpos = 0;
        if (!number_list(a->value, v, badpos))
            return Fail{Errc::syntax, a->offset + badpos, "malformed number in points"};
        if (v.size() % 2 != 0) return Fail{Errc::syntax, a->offset, "odd number of coordinates"};
        if (v.empty()) return {};
        cur_ = start_ = {v[0], v[1]};
        for (std::size_t k = 2; k < v.size(); k += 2)
            if (auto r = line_to({v[k], v[k + 1]}); !r) return r;
        if (n == "polygon" && open_)
            if (auto r = line_to(start_); !r) return r;
        end_chain();
        return {};
    }
    if (n == "rect") {
        SVG_LEN("x", 0, x);
        SVG_LEN("y", 0, y);
        SVG_LEN("width", 0, w);
        SVG_LEN("height", 0, h);
        if (w <= 0 || h <= 0) return {};  // not rendered
        SVG_LEN("rx", -1, rx);
        SVG_LEN("ry", -1, ry);
        if (rx < 0) rx = ry;
        if (ry < 0) ry = rx;
        rx = std::clamp(rx, 0.0, w / 2);
        ry = std::clamp(ry, 0.0, h / 2);
        cur_ = {x + rx, y};
        const bool round = rx > 0 && ry > 0;
        auto corner = [&](Pt p) { return round ? arc_to(rx, ry, 0, false, true, p) : Res<void>{}; };
        if (auto r = line_to({x + w - rx, y}); !r) return r;
        if (auto r = corner({x + w, y + ry}); !r) return r;
        if (auto r = line_to({x + w, y + h - ry}); !r) return r;
        if (auto r = corner({x + w - rx, y + h}); !r) return r;
        if (auto r = line_to({x + rx, y + h}); !r) return r;
        if (auto r = corner({x, y + h - ry}); !r) return r;
        if (auto r = line_to({x, y + ry}); !r) return r;
        if (auto r = corner({x + rx, y}); !r) return r;
        end_chain();
        return {};
    }
    if (n == "circle" || n == "ellipse") {
        SVG_LEN("cx", 0, cx);
        SVG_LEN("cy", 0, cy);
        double rx, ry;
        if (n == "circle") {
            SVG_LEN("r", 0, radius);
            rx = ry = radius;
        } else {
            if (auto r = len("rx", 0, rx); !r) return r;
            if (auto r = len("ry", 0, ry); !r) return r;
        }
        if (rx <= 0 || ry <= 0) return {};  // not rendered
        cur_ = {cx + rx, cy};
        if (auto r = arc_to(rx, ry, 0, false, true, {cx - rx, cy}); !r) return r;
        if (auto r = arc_to(rx, ry, 0, false, true, {cx + rx, cy}); !r) return r;
        end_chain();
        return {};
    }
#undef SVG_LEN
    return {};
}

// The root's units: with a step size, user units become millimetres by the
// root's width / height (absolute units) over its viewBox, or as CSS pixels
// (1/96 in) without them; without a step size a user unit is a step.
Res<void> Reader::root(const Element& el) {
    double sx = 1, sy = 1;
    if (opt_.step_size) {
        double mm_x = 25.4 / 96, mm_y = 25.4 / 96;  // per user unit
        const Attr* vb = el.find("viewBox");
        if (vb) {
            std::vector<double> v;
            std::size_t badpos = 0;
            if (!number_list(vb->value, v, badpos) || v.size() != 4 || v[2] <= 0 || v[3] <= 0)
                return Fail{Errc::syntax, vb->offset, "viewBox: expected four numbers, width and height positive"};
            double w = v[2], h = v[3];
            if (const Attr* a = el.find("width"); a && !length(a->value, w))
                return Fail{Errc::unsupported, a->offset, "width: expected a number with an optional unit px mm cm in pt pc"};
            if (const Attr* a = el.find("height"); a && !length(a->value, h))
                return Fail{Errc::unsupported, a->offset, "height: expected a number with an optional unit px mm cm in pt pc"};
            mm_x = w / v[2] * 25.4 / 96;
            mm_y = h / v[3] * 25.4 / 96;
        }
        const double step_mm = static_cast<double>(opt_.step_size->mm_e12) * 1e-12;
        sx = mm_x / step_mm;
        sy = mm_y / step_mm;
    }
    root_map_ = Affine{sx, 0, 0, -sy, 0, 0};
    return {};
}

Result<Drawing> Reader::run() {
    Tokenizer tok(text_);
    std::vector<Frame> stack;
    int layers = 0;
    bool seen_root = false;
    static constexpr const char* kContainers[] = {"g", "a", "switch"};
    static constexpr const char* kShapes[] = {"path", "line", "polyline", "polygon",
                                              "rect", "circle", "ellipse"};
    for (;;) {
        Element el;
        auto kind = tok.next(el);
        if (!kind) return fail(kind.error());
        if (*kind == Tokenizer::Kind::eof) break;
        if (*kind == Tokenizer::Kind::end) {
            if (stack.empty() || stack.back().name != el.name)
                return fail({Errc::syntax, el.offset,
                             stack.empty() ? "end tag '" + el.name + "' without a start tag"
                                           : "end tag '" + el.name + "' does not close '" +
                                                 stack.back().name + "'"});
            stack.pop_back();
            continue;
        }
        if (!seen_root) {
            if (el.name != "svg" && !el.name.ends_with(":svg"))
                return fail({Errc::syntax, el.offset, "the root element is '" + el.name + "', not 'svg'"});
            seen_root = true;
            if (auto r = root(el); !r) return fail(r.error());
            if (!el.self_closing) stack.push_back(Frame{root_map_, false, 1, el.name});
            continue;
        }
        if (stack.empty())
            return fail({Errc::syntax, el.offset, "content after the root element"});
        Frame f = stack.back();
        f.name = el.name;
        const bool container = std::find(std::begin(kContainers), std::end(kContainers),
                                         el.name) != std::end(kContainers) ||
                               el.name == "svg";
        const bool shape_el = std::find(std::begin(kShapes), std::end(kShapes), el.name) !=
                              std::end(kShapes);
        const Attr* display = el.find("display");
        if (!f.skip && (!(container || shape_el) || (display && display->value == "none")))
            f.skip = true;  // defs, style, text, symbol, use, metadata ... : not drawn
        if (!f.skip) {
            if (const Attr* t = el.find("transform")) {
                auto m = transform(*t);
                if (!m) return fail(m.error());
                f.ctm = f.ctm.then(*m);
            }
            // A top-level group that is an Inkscape layer or has an id: a pen.
            if (el.name == "g" && stack.size() == 1 &&
                (el.find("id") || (el.find("inkscape:groupmode") &&
                                   el.find("inkscape:groupmode")->value == "layer")))
                f.pen = ++layers;
            if (shape_el)
                if (auto r = shape(el, f.ctm, f.pen); !r) return fail(r.error());
        }
        if (!el.self_closing) stack.push_back(std::move(f));
    }
    if (!seen_root) return fail({Errc::syntax, tok.pos(), "no <svg> root element"});
    if (!stack.empty())
        return fail({Errc::syntax, tok.pos(), "element '" + stack.back().name + "' is not closed"});
    return std::move(drawing_);
}

}  // namespace

Result<Drawing> read_svg(std::string_view text, const VectorReadOptions& options) {
    if (!(options.tolerance > 0) || !std::isfinite(options.tolerance))
        return make_error(Errc::invalid_argument, "tolerance must be a positive number of steps");
    Reader reader(text, options);
    return reader.run();
}

bool looks_like_svg(std::string_view head) noexcept {
    std::size_t i = 0;
    if (head.starts_with("\xEF\xBB\xBF")) i = 3;
    while (i < head.size() && is_space(head[i])) ++i;
    if (i >= head.size() || head[i] != '<') return false;
    for (std::size_t k = head.find("<svg", i); k != std::string_view::npos;
         k = head.find("<svg", k + 1))
        if (k + 4 < head.size() && (is_space(head[k + 4]) || head[k + 4] == '>' || head[k + 4] == '/'))
            return true;
    return false;
}

}  // namespace stepzip
