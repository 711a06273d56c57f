// stepzip — HP-GL reader and writer (SPEC §5: PU / PD / PA / PR).
//
// Reader: one pass; an instruction is a two-letter mnemonic and a list of
// exact decimal parameters. Complexity: O(bytes).
#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

#include "gcode_units.hpp"
#include "stepzip/vectors.hpp"

namespace stepzip {

namespace {

using vec::i128;

struct Param {
    i128 value = 0;
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
bool starts_number(char c) {
    return std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.';
}

}  // namespace

Result<Drawing> read_hpgl(std::string_view text, const VectorReadOptions& options) {
    const std::string& src = options.source;
    Drawing drawing;
    Cursor cur{text};
    bool absolute = true, pen_down = false, path_open = false;
    i128 px = 0, py = 0;  // exact position, 10^-15 mm (plotter units x 25)
    std::int64_t sx = 0, sy = 0;
    const i128 unit = options.step_size ? vec::kPerPlotterUnit : vec::kPerMm;

    auto close_path = [&] {
        if (path_open && drawing.back().moves.empty()) drawing.pop_back();
        path_open = false;
    };

    while (true) {
        while (!cur.done() && (is_space(cur.peek()) || cur.peek() == ';')) cur.advance();
        if (cur.done()) break;
        const std::size_t m_line = cur.line, m_col = cur.column();
        const std::string at = vec::place(src, m_line, m_col);
        const char a = cur.peek();
        if (a == '\x1b') {
            // HP device-control sequence (ESC . letter [parameters] [:]) sent to
            // the plotter's serial interface, not to the HP-GL interpreter.
            cur.advance();
            if (cur.done() || cur.peek() != '.')
                return make_error(Errc::syntax, at + ": ESC not followed by '.'");
            cur.advance();
            if (cur.done())
                return make_error(Errc::syntax, at + ": incomplete device-control sequence");
            cur.advance();  // the function letter
            std::size_t k = cur.pos;
            while (k < text.size() && k - cur.pos < 64 &&
                   (std::isdigit(static_cast<unsigned char>(text[k])) || text[k] == ';'))
                ++k;
            if (k < text.size() && text[k] == ':') {
                while (cur.pos <= k) cur.advance();
            }
            continue;
        }
        if (!std::isalpha(static_cast<unsigned char>(a)))
            return make_error(Errc::syntax,
                              at + ": unexpected character " + vec::describe_char(a));
        cur.advance();
        if (cur.done() || !std::isalpha(static_cast<unsigned char>(cur.peek())))
            return make_error(Errc::syntax, at + ": incomplete instruction '" +
                                                std::string(1, a) + "'");
        std::string mnemonic{static_cast<char>(std::toupper(static_cast<unsigned char>(a))),
                             static_cast<char>(std::toupper(static_cast<unsigned char>(cur.peek())))};
        cur.advance();
        if (mnemonic == "LB") {
            // A label: text for the plotter's character generator, ended by
            // ETX. Labels are not strokes of the drawing; they are skipped.
            while (!cur.done() && cur.peek() != '\x03') cur.advance();
            if (cur.done())
                return make_error(Errc::syntax, at + ": label (LB) not ended by ETX (0x03)");
            cur.advance();
            continue;
        }
        if (mnemonic == "CO") {
            // A comment (HP-GL/2): CO "text"; skipped.
            while (!cur.done() && is_space(cur.peek())) cur.advance();
            if (!cur.done() && cur.peek() == '"') {
                cur.advance();
                while (!cur.done() && cur.peek() != '"') cur.advance();
                if (cur.done())
                    return make_error(Errc::syntax, at + ": comment (CO) not ended by '\"'");
                cur.advance();
            }
            continue;
        }

        // Parameters: numbers separated by commas or spaces, up to ';', a
        // letter or the end.
        std::vector<Param> params;
        bool want_number = false;  // after a comma
        while (true) {
            while (!cur.done() && is_space(cur.peek())) cur.advance();
            if (cur.done()) break;
            const char c = cur.peek();
            if (c == ';' || std::isalpha(static_cast<unsigned char>(c))) break;
            if (c == ',') {
                if (want_number || params.empty())
                    return make_error(Errc::syntax, vec::place(src, cur.line, cur.column()) +
                                                        ": expected a number before ','");
                want_number = true;
                cur.advance();
                continue;
            }
            if (!starts_number(c))
                return make_error(Errc::syntax, vec::place(src, cur.line, cur.column()) +
                                                    ": unexpected character " +
                                                    vec::describe_char(c) + " in " + mnemonic);
            Param p;
            p.line = cur.line;
            p.column = cur.column();
            std::size_t k = cur.pos;
            const std::string why = vec::parse_decimal(text, k, p.value);
            if (!why.empty())
                return make_error(Errc::syntax, vec::place(src, p.line, p.column) + ": " + why);
            p.text = std::string(text.substr(cur.pos, k - cur.pos));
            while (cur.pos < k) cur.advance();
            params.push_back(std::move(p));
            want_number = false;
        }
        if (want_number)
            return make_error(Errc::syntax, vec::place(src, cur.line, cur.column()) +
                                                ": expected a number after ','");

        if (mnemonic == "IN") {
            close_path();
            pen_down = false;
            absolute = true;
            continue;
        }
        if (mnemonic == "DF" || mnemonic == "SP" || mnemonic == "VS" || mnemonic == "LT" ||
            mnemonic == "PW" || mnemonic == "PG" || mnemonic == "DI" || mnemonic == "DR" ||
            mnemonic == "SR" || mnemonic == "SI" || mnemonic == "SL" || mnemonic == "CS")
            continue;  // pen, speed, line style, page, label style: no effect on the path
        if (mnemonic == "SC" || mnemonic == "IP")
            continue;  // scaling: coordinates are taken as steps in user units (docs/cli.md)
        if (mnemonic != "PU" && mnemonic != "PD" && mnemonic != "PA" && mnemonic != "PR")
            return make_error(Errc::unsupported, at + ": unsupported instruction '" + mnemonic + "'");
        if (params.size() % 2 != 0)
            return make_error(Errc::syntax, at + ": odd number of coordinates (" +
                                                std::to_string(params.size()) + ") in " + mnemonic);

        if (mnemonic == "PU") {
            close_path();
            pen_down = false;
        } else if (mnemonic == "PD") {
            pen_down = true;
        } else if (mnemonic == "PA") {
            absolute = true;
        } else {
            absolute = false;
        }
        if (pen_down && !path_open) {
            drawing.push_back(VectorPath{sx, sy, {}});
            path_open = true;
        }
        for (std::size_t k = 0; k < params.size(); k += 2) {
            const Param& ex = params[k];
            const Param& ey = params[k + 1];
            const i128 nx = absolute ? ex.value * unit : px + ex.value * unit;
            const i128 ny = absolute ? ey.value * unit : py + ey.value * unit;
            auto rx = vec::to_steps(nx, options.step_size, vec::place(src, ex.line, ex.column),
                                    ex.text);
            if (!rx) return std::move(rx).error();
            auto ry = vec::to_steps(ny, options.step_size, vec::place(src, ey.line, ey.column),
                                    ey.text);
            if (!ry) return std::move(ry).error();
            px = nx;
            py = ny;
            if (pen_down && (*rx != sx || *ry != sy)) {
                VectorMove mv;
                mv.x = *rx;
                mv.y = *ry;
                mv.line = static_cast<std::uint32_t>(ex.line);
                mv.column = static_cast<std::uint32_t>(ex.column);
                drawing.back().moves.push_back(mv);
            }
            sx = *rx;
            sy = *ry;
        }
    }
    close_path();
    return drawing;
}

Result<std::string> write_hpgl(const Drawing& drawing, std::string_view comment) {
    std::string out = "IN;";
    if (!comment.empty()) {
        std::string c(comment);
        std::replace(c.begin(), c.end(), '"', '\'');
        out += "CO\"" + c + "\";";
    }
    out += "SP1;\n";
    for (std::size_t p = 0; p < drawing.size(); ++p) {
        const VectorPath& path = drawing[p];
        out += "PU" + std::to_string(path.x0) + "," + std::to_string(path.y0) + ";\n";
        std::size_t in_line = 0;
        for (const VectorMove& m : path.moves) {
            if (m.kind != MoveKind::line)
                return make_error(Errc::unsupported,
                                  "path " + std::to_string(p + 1) +
                                      ": HP-GL output cannot carry arcs exactly");
            out += in_line == 0 ? "PD" : ",";
            out += std::to_string(m.x) + "," + std::to_string(m.y);
            if (++in_line == 8) {
                out += ";\n";
                in_line = 0;
            }
        }
        if (in_line != 0) out += ";\n";
    }
    out += "PU;SP0;\n";
    return out;
}

}  // namespace stepzip
