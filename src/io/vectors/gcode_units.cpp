// stepzip — exact decimals and unit conversion for the vector formats.
#include "gcode_units.hpp"

#include <cctype>
#include <cstdio>

namespace stepzip::vec {

i128 pow10(int n) noexcept {
    i128 r = 1;
    for (int i = 0; i < n; ++i) r *= 10;
    return r;
}

std::string parse_decimal(std::string_view text, std::size_t& pos, i128& value_e12) {
    std::size_t i = pos;
    bool negative = false;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) {
        negative = text[i] == '-';
        ++i;
    }
    i128 int_part = 0, frac_part = 0;
    int int_digits = 0, frac_digits = 0;  // significant integer digits, fraction digits
    bool had_int = false;
    while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) {
        had_int = true;
        if ((int_part != 0 || text[i] != '0') && ++int_digits > 15) return "number too large";
        int_part = int_part * 10 + (text[i] - '0');
        ++i;
    }
    bool had_frac = false;
    if (i < text.size() && text[i] == '.') {
        ++i;
        while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) {
            had_frac = true;
            if (++frac_digits > 12) return "more than 12 fraction digits";
            frac_part = frac_part * 10 + (text[i] - '0');
            ++i;
        }
    }
    if (!had_int && !had_frac) return "expected a number";
    i128 v = int_part * pow10(12) + frac_part * pow10(12 - frac_digits);
    value_e12 = negative ? -v : v;
    pos = i;
    return {};
}

std::string format_e12(i128 value_e12) {
    const bool negative = value_e12 < 0;
    i128 v = negative ? -value_e12 : value_e12;
    const i128 scale = pow10(12);
    i128 whole = v / scale, frac = v % scale;
    std::string digits;
    do {
        digits.insert(digits.begin(), static_cast<char>('0' + static_cast<int>(whole % 10)));
        whole /= 10;
    } while (whole != 0);
    std::string out = negative ? "-" + digits : digits;
    if (frac != 0) {
        std::string f(12, '0');
        for (int k = 11; k >= 0; --k) {
            f[static_cast<std::size_t>(k)] = static_cast<char>('0' + static_cast<int>(frac % 10));
            frac /= 10;
        }
        while (!f.empty() && f.back() == '0') f.pop_back();
        out += "." + f;
    }
    return out;
}

AxisScale AxisScale::of(const std::optional<StepSize>& step) noexcept {
    AxisScale s;
    if (step) {
        s.den = i128{step->mm_e12} * 1000;
        s.rounds = true;
    }
    return s;
}

AxisScale AxisScale::per_mm(i128 steps_per_mm_e12) noexcept {
    AxisScale s;
    s.num = steps_per_mm_e12;
    s.den = pow10(27);
    s.rounds = true;
    return s;
}

Result<std::int64_t> to_steps(i128 pos_e15, const AxisScale& scale, const std::string& where,
                              std::string_view text) {
    i128 scaled = 0;
    if (__builtin_mul_overflow(pos_e15, scale.num, &scaled))
        return make_error(Errc::limit, where + ": coordinate " + std::string(text) +
                                           " is beyond the limit of 2^30 steps");
    i128 q = scaled / scale.den;
    const i128 r = scaled % scale.den;
    if (r != 0) {
        if (!scale.rounds)
            return make_error(Errc::syntax, where + ": coordinate " + std::string(text) +
                                                " is not a whole number of steps (set a step "
                                                "size to read millimetres)");
        const i128 twice = (r < 0 ? -r : r) * 2;
        if (twice >= scale.den) q += scaled < 0 ? -1 : 1;  // halves away from zero
    }
    if (q > kMaxVectorCoord || q < -kMaxVectorCoord)
        return make_error(Errc::limit, where + ": coordinate " + std::string(text) +
                                           " is beyond the limit of 2^30 steps");
    return static_cast<std::int64_t>(q);
}

Result<std::int64_t> to_steps(i128 pos_e15, const std::optional<StepSize>& step,
                              const std::string& where, std::string_view text) {
    return to_steps(pos_e15, AxisScale::of(step), where, text);
}

std::string place(const std::string& source, std::size_t line, std::size_t column) {
    return source + ":" + std::to_string(line) + ":" + std::to_string(column);
}

std::string describe_char(char c) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x21 && u < 0x7f) return std::string("'") + c + "'";
    char buf[16];
    std::snprintf(buf, sizeof buf, "byte 0x%02x", u);
    return buf;
}

}  // namespace stepzip::vec

namespace stepzip {

Result<StepSize> parse_step_size(std::string_view text) {
    std::size_t pos = 0;
    vec::i128 v = 0;
    const std::string why = vec::parse_decimal(text, pos, v);
    if (!why.empty() || pos != text.size())
        return make_error(Errc::invalid_argument,
                          "step size '" + std::string(text) + "': " +
                              (why.empty() ? std::string("not a decimal number") : why));
    if (v <= 0)
        return make_error(Errc::invalid_argument,
                          "step size '" + std::string(text) + "' must be positive");
    if (v > vec::pow10(18))
        return make_error(Errc::invalid_argument,
                          "step size '" + std::string(text) + "' is larger than 10^6 mm");
    return StepSize{static_cast<std::int64_t>(v)};
}

std::string_view vector_format_name(VectorFormat f) noexcept {
    return f == VectorFormat::gcode ? "gcode" : f == VectorFormat::hpgl ? "hpgl" : "svg";
}

std::optional<VectorFormat> parse_vector_format(std::string_view name) noexcept {
    if (name == "gcode") return VectorFormat::gcode;
    if (name == "hpgl") return VectorFormat::hpgl;
    if (name == "svg") return VectorFormat::svg;
    return std::nullopt;
}

std::optional<VectorFormat> detect_vector_format(std::string_view head) noexcept {
    if (looks_like_svg(head)) return VectorFormat::svg;
    std::size_t i = 0;
    auto skip_space = [&] {  // and ETX, which some drivers send before a plot
        while (i < head.size() && (std::isspace(static_cast<unsigned char>(head[i])) || head[i] == '\x03'))
            ++i;
    };
    skip_space();
    if (i >= head.size()) return std::nullopt;
    const char c0 = head[i];
    if (c0 == ';' || c0 == '(' || c0 == '%') return VectorFormat::gcode;
    if (c0 == '\x1b')
        return VectorFormat::hpgl;  // a device-control or PCL escape opens the plot
    if (!std::isalpha(static_cast<unsigned char>(c0))) return std::nullopt;
    if (i + 1 < head.size() && std::isalpha(static_cast<unsigned char>(head[i + 1]))) {
        // Two letters: an HP-GL mnemonic (a G-code word is one letter and
        // a number), followed by a parameter, a separator or another one.
        // Another letter must follow a common opening mnemonic ("INPU"),
        // so that a word of text is not taken for HP-GL.
        const char n = i + 2 < head.size() ? head[i + 2] : ';';
        if (std::isalpha(static_cast<unsigned char>(n))) {
            const std::string m{static_cast<char>(std::toupper(static_cast<unsigned char>(c0))),
                                static_cast<char>(std::toupper(static_cast<unsigned char>(head[i + 1])))};
            for (const char* k : {"IN", "DF", "BP", "PS", "PU", "PD", "PA", "PR", "SP", "CO"})
                if (m == k) return VectorFormat::hpgl;
            return std::nullopt;
        }
        if (std::isdigit(static_cast<unsigned char>(n)) || std::isspace(static_cast<unsigned char>(n)) ||
            n == ';' || n == ',' || n == '-' || n == '+' || n == '.' || n == '"' || n == ':')
            return VectorFormat::hpgl;
        return std::nullopt;
    }
    ++i;
    while (i < head.size() && (head[i] == ' ' || head[i] == '\t')) ++i;
    if (i < head.size() && (std::isdigit(static_cast<unsigned char>(head[i])) || head[i] == '-' ||
                            head[i] == '+' || head[i] == '.'))
        return VectorFormat::gcode;
    return std::nullopt;
}

Result<Drawing> read_vectors(VectorFormat format, std::string_view text,
                             const VectorReadOptions& options) {
    switch (format) {
    case VectorFormat::gcode: return read_gcode(text, options);
    case VectorFormat::hpgl: return read_hpgl(text, options);
    case VectorFormat::svg: break;
    }
    return read_svg(text, options);
}

}  // namespace stepzip
