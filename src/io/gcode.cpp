// stepzip — G-code reader and writer (SPEC §5, §6 `interpolate` / `segment`).
//
// Reader: one pass over the lines; each line is split into words (a letter
// and an exact decimal), then applied in the order a controller would:
// units and distance mode first, then the motion. Complexity: O(bytes).
#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <string>
#include <vector>

#include "gcode_units.hpp"
#include "stepzip/vectors.hpp"

namespace stepzip {

namespace {

using vec::i128;

struct Word {
    char letter = 0;  // upper case
    i128 value = 0;   // 10^-12 units
    std::string text;  // the number as written
    std::size_t column = 0;
};

// Splits one line into words. Comments and '%' are skipped.
Result<std::vector<Word>> split_words(std::string_view line, const std::string& source,
                                      std::size_t line_no) {
    std::vector<Word> words;
    std::size_t i = 0;
    while (i < line.size()) {
        const char c = line[i];
        if (c == ' ' || c == '\t' || c == '\r') {
            ++i;
        } else if (c == ';') {
            break;
        } else if (c == '(') {
            const auto close = line.find(')', i);
            if (close == std::string_view::npos)
                return make_error(Errc::syntax, vec::place(source, line_no, i + 1) +
                                                    ": comment '(' is not closed on its line");
            i = close + 1;
        } else if (c == '%' && words.empty()) {
            // program start/end marker: nothing else may follow but a comment
            std::size_t k = i + 1;
            while (k < line.size() && (line[k] == ' ' || line[k] == '\t' || line[k] == '\r')) ++k;
            if (k < line.size() && line[k] != ';' && line[k] != '(')
                return make_error(Errc::syntax, vec::place(source, line_no, k + 1) +
                                                    ": text after '%'");
            i = k;
        } else if (std::isalpha(static_cast<unsigned char>(c))) {
            Word w;
            w.letter = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
            w.column = i + 1;
            std::size_t k = i + 1;
            while (k < line.size() && (line[k] == ' ' || line[k] == '\t')) ++k;
            const std::size_t start = k;
            const std::string why = vec::parse_decimal(line, k, w.value);
            if (!why.empty())
                return make_error(Errc::syntax, vec::place(source, line_no, start + 1) + ": " +
                                                    why + " after '" + w.letter + "'");
            w.text = std::string(line.substr(start, k - start));
            words.push_back(std::move(w));
            i = k;
        } else {
            return make_error(Errc::syntax, vec::place(source, line_no, i + 1) +
                                                ": unexpected character " + vec::describe_char(c));
        }
    }
    return words;
}

struct GcodeState {
    bool absolute = true;
    bool ij_absolute = false;  // G90.1; default G91.1 (I J relative to the arc start)
    i128 unit = vec::kPerMm;   // 10^-15 mm per 10^-12 file unit
    int motion = -1;           // last of G0..G3, -1 before any
    i128 px = 0, py = 0;       // exact position, 10^-15 mm
    std::int64_t sx = 0, sy = 0;  // position in steps
    bool path_open = false;
};

}  // namespace

Result<Drawing> read_gcode(std::string_view text, const VectorReadOptions& options) {
    const std::string& src = options.source;
    Drawing drawing;
    GcodeState st;
    auto close_path = [&] {
        if (st.path_open && drawing.back().moves.empty()) drawing.pop_back();
        st.path_open = false;
    };

    std::size_t line_no = 0, begin = 0;
    while (begin < text.size()) {
        ++line_no;
        std::size_t end = text.find('\n', begin);
        if (end == std::string_view::npos) end = text.size();
        const std::string_view line = text.substr(begin, end - begin);
        begin = end + 1;

        auto words = split_words(line, src, line_no);
        if (!words) return std::move(words).error();
        if (words->empty()) continue;

        int motion = -1;
        std::size_t motion_col = 0;
        bool dwell = false;
        std::array<const Word*, 26> seen{};
        for (const Word& w : *words) {
            const std::string at = vec::place(src, line_no, w.column);
            if (w.letter == 'G') {
                const i128 g = w.value;
                const i128 one = vec::pow10(12), tenth = vec::pow10(11);
                if (g == 0 || g == one || g == 2 * one || g == 3 * one) {
                    if (motion >= 0)
                        return make_error(Errc::syntax, at + ": two motion words on one line");
                    motion = static_cast<int>(g / one);
                    motion_col = w.column;
                } else if (g == 90 * one) {
                    st.absolute = true;
                } else if (g == 91 * one) {
                    st.absolute = false;
                } else if (g == 90 * one + tenth) {
                    st.ij_absolute = true;
                } else if (g == 91 * one + tenth) {
                    st.ij_absolute = false;
                } else if (g == 20 * one) {
                    st.unit = vec::kPerInch;
                } else if (g == 21 * one) {
                    st.unit = vec::kPerMm;
                } else if (g == 4 * one) {
                    dwell = true;
                } else if (g == 17 * one || g == 94 * one) {
                    // XY plane, feed per minute: what this reader assumes anyway
                } else {
                    return make_error(Errc::unsupported,
                                      at + ": unsupported word 'G" + w.text + "'");
                }
                continue;
            }
            if (w.letter == 'M' || w.letter == 'N' || w.letter == 'F' || w.letter == 'S' ||
                w.letter == 'T')
                continue;  // machine words that do not move: ignored (documented)
            if (w.letter == 'X' || w.letter == 'Y' || w.letter == 'I' || w.letter == 'J' ||
                w.letter == 'P') {
                const Word*& slot = seen[static_cast<std::size_t>(w.letter - 'A')];
                if (slot)
                    return make_error(Errc::syntax,
                                      at + ": word '" + std::string(1, w.letter) + "' repeated");
                slot = &w;
                continue;
            }
            if (w.letter == 'Z')
                return make_error(Errc::unsupported,
                                  at + ": unsupported word 'Z" + w.text +
                                      "' (G-code is read as two-axis X Y paths)");
            if (w.letter == 'R')
                return make_error(Errc::unsupported,
                                  at + ": unsupported word 'R" + w.text +
                                      "' (give an arc's centre with I and J)");
            return make_error(Errc::unsupported, at + ": unsupported word '" +
                                                     std::string(1, w.letter) + w.text + "'");
        }
        const Word* wx = seen['X' - 'A'];
        const Word* wy = seen['Y' - 'A'];
        const Word* wi = seen['I' - 'A'];
        const Word* wj = seen['J' - 'A'];
        const Word* wp = seen['P' - 'A'];
        if (wp && !dwell)
            return make_error(Errc::unsupported, vec::place(src, line_no, wp->column) +
                                                     ": unsupported word 'P" + wp->text +
                                                     "' (P is read only with G4)");

        if (motion >= 0) st.motion = motion;
        if (motion == 0) close_path();  // any G0 lifts the pen
        const bool has_xy = wx || wy;
        if (!has_xy && !(wi || wj) && motion < 0) continue;  // no motion on this line
        const Word* first = wx ? wx : wy ? wy : wi ? wi : wj;
        const std::size_t col = motion >= 0 ? motion_col : first->column;
        if (st.motion < 0)
            return make_error(Errc::syntax, vec::place(src, line_no, col) +
                                                ": coordinates before any G0, G1, G2 or G3");
        const bool arc = st.motion == 2 || st.motion == 3;
        if ((wi || wj) && !arc)
            return make_error(Errc::syntax, vec::place(src, line_no, (wi ? wi : wj)->column) +
                                                ": I or J outside an arc (G2 or G3)");
        if (arc && !(wi || wj)) {
            if (!has_xy && motion >= 0) continue;  // "G2" alone only sets the mode
            return make_error(Errc::unsupported,
                              vec::place(src, line_no, col) +
                                  ": arc without I or J (give the centre with I and J)");
        }
        if (!has_xy && !arc) continue;  // "G1" alone only sets the mode

        // The target, exactly, then in steps.
        const i128 start_x = st.px, start_y = st.py;
        i128 nx = st.px, ny = st.py;
        if (wx) nx = st.absolute ? wx->value * st.unit : st.px + wx->value * st.unit;
        if (wy) ny = st.absolute ? wy->value * st.unit : st.py + wy->value * st.unit;
        std::int64_t tx = st.sx, ty = st.sy;
        if (wx) {
            auto r = vec::to_steps(nx, options.step_size, vec::place(src, line_no, wx->column),
                                   wx->text);
            if (!r) return std::move(r).error();
            tx = *r;
        }
        if (wy) {
            auto r = vec::to_steps(ny, options.step_size, vec::place(src, line_no, wy->column),
                                   wy->text);
            if (!r) return std::move(r).error();
            ty = *r;
        }
        VectorMove mv;
        mv.x = tx;
        mv.y = ty;
        mv.line = static_cast<std::uint32_t>(line_no);
        mv.column = static_cast<std::uint32_t>(col);
        if (arc) {
            mv.kind = st.motion == 2 ? MoveKind::arc_cw : MoveKind::arc_ccw;
            const i128 ci = wi ? wi->value * st.unit : 0;
            const i128 cj = wj ? wj->value * st.unit : 0;
            const i128 cxe = st.ij_absolute ? ci : start_x + ci;
            const i128 cye = st.ij_absolute ? cj : start_y + cj;
            const Word* wc = wi ? wi : wj;
            auto rx = vec::to_steps(cxe, options.step_size,
                                    vec::place(src, line_no, (wi ? wi : wc)->column),
                                    wi ? wi->text : "0");
            if (!rx) return std::move(rx).error();
            auto ry = vec::to_steps(cye, options.step_size,
                                    vec::place(src, line_no, (wj ? wj : wc)->column),
                                    wj ? wj->text : "0");
            if (!ry) return std::move(ry).error();
            mv.cx = *rx;
            mv.cy = *ry;
            if (mv.cx == st.sx && mv.cy == st.sy)
                return make_error(Errc::syntax, vec::place(src, line_no, wc->column) +
                                                    ": arc of radius zero (centre on its start)");
        }
        st.px = nx;
        st.py = ny;
        const bool moves = arc || tx != st.sx || ty != st.sy;
        if (st.motion != 0 && moves) {
            if (!st.path_open) {
                drawing.push_back(VectorPath{st.sx, st.sy, {}});
                st.path_open = true;
            }
            drawing.back().moves.push_back(mv);
        }
        st.sx = tx;
        st.sy = ty;
    }
    close_path();
    return drawing;
}

namespace {

std::string coord_text(std::int64_t steps, const std::optional<StepSize>& step) {
    if (!step) return std::to_string(steps);
    return vec::format_e12(i128{steps} * step->mm_e12);
}


// A feed in units per minute with three decimals, trailing zeros dropped.
std::string feed_text(double f) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3f", f);
    std::string t = buf;
    while (!t.empty() && t.back() == '0') t.pop_back();
    if (!t.empty() && t.back() == '.') t.pop_back();
    return t;
}

}  // namespace

std::string write_gcode(const Drawing& drawing, const GcodeWriteOptions& options) {
    bool feeds = false;
    for (const VectorPath& path : drawing)
        for (const VectorMove& m : path.moves) feeds = feeds || m.feed > 0;
    std::string out;
    out += "; stepzip vectors: " + std::to_string(drawing.size()) + " path(s), coordinates in ";
    out += options.step_size ? "mm" : "steps";
    if (feeds) out += options.step_size ? ", feed in mm/min" : ", feed in steps/min";
    out += "\n";
    if (!options.comment.empty()) {
        std::string c = options.comment;
        std::replace(c.begin(), c.end(), '\n', ' ');
        out += "; " + c + "\n";
    }
    out += options.relative ? "G91\n" : "G90\n";
    if (options.step_size) out += "G21\n";
    if (feeds) out += "G94\n";
    std::string last_feed;
    std::int64_t cx = 0, cy = 0;  // current position in steps
    auto xy = [&](std::int64_t x, std::int64_t y) {
        const std::int64_t ox = options.relative ? x - cx : x;
        const std::int64_t oy = options.relative ? y - cy : y;
        return " X" + coord_text(ox, options.step_size) + " Y" + coord_text(oy, options.step_size);
    };
    for (const VectorPath& path : drawing) {
        out += "G0" + xy(path.x0, path.y0) + "\n";
        cx = path.x0;
        cy = path.y0;
        for (const VectorMove& m : path.moves) {
            switch (m.kind) {
                case MoveKind::line: out += "G1"; break;
                case MoveKind::arc_cw: out += "G2"; break;
                case MoveKind::arc_ccw: out += "G3"; break;
            }
            out += xy(m.x, m.y);
            if (m.kind != MoveKind::line)
                out += " I" + coord_text(m.cx - cx, options.step_size) + " J" +
                       coord_text(m.cy - cy, options.step_size);
            if (m.feed > 0) {
                std::string f = feed_text(m.feed);
                if (f != last_feed) out += " F" + f;
                last_feed = std::move(f);
            }
            out += "\n";
            cx = m.x;
            cy = m.y;
        }
    }
    return out;
}

}  // namespace stepzip
