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
    bool bare = false;  // a letter without a number ("G28 X Y"), kept when allowed
};

// Splits one line into words. Comments and '%' are skipped.
Result<std::vector<Word>> split_words(std::string_view line, const std::string& source,
                                      std::size_t line_no, bool allow_bare) {
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
            if (!why.empty() && allow_bare && why == "expected a number" &&
                (k == line.size() || !(line[k] == '+' || line[k] == '-' || line[k] == '.'))) {
                w.bare = true;
                k = start;
            } else if (!why.empty())
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

// Options of the one G-code reader behind read_gcode() and
// read_gcode_job().
struct CoreOptions {
    std::string source;
    std::string letters = "XY";  // the axes, upper case
    std::array<vec::AxisScale, kMaxAxes> scale{};
    // read_gcode(): two-axis drawings; a word it does not know is an error
    // (G28, G92, Z, E, ...) instead of being skipped and counted.
    bool strict = false;
};

enum class EMode { follow, absolute, relative };

struct CoreState {
    bool absolute = true;
    bool ij_absolute = false;  // G90.1; default G91.1 (I J relative to the arc start)
    EMode e_mode = EMode::follow;
    int plane = 17;
    i128 unit = vec::kPerMm;   // 10^-15 mm per 10^-12 file unit
    int motion = -1;           // last of G0..G3, -1 before any
    double feed = 0;
    int pen = 1;                           // T in drawings
    std::array<i128, kMaxAxes> machine{};  // exact machine position, 10^-15 mm
    std::array<i128, kMaxAxes> offset{};   // G92: logical = machine + offset
    Point steps{};                         // machine position in steps
};

// G-codes of the motion group other than G0-G3: moves this reader cannot
// plan (splines, threading, probing, canned cycles).
bool other_motion(i128 g) {
    const i128 one = vec::pow10(12), tenth = vec::pow10(11);
    const i128 whole = g / one, frac = g % one;
    if (frac != 0 && frac % tenth != 0) return false;
    switch (static_cast<int>(whole)) {
        case 5: case 33: case 38: case 73: case 76:
        case 81: case 82: case 83: case 84: case 85: case 86: case 87: case 88: case 89:
            return true;
        default: return false;
    }
}

Result<MachineJob> read_core(std::string_view text, const CoreOptions& opt) {
    const std::string& src = opt.source;
    MachineJob job;
    job.letters = opt.letters;
    job.axes = static_cast<int>(opt.letters.size());
    job.runs.emplace_back();
    CoreState st;
    const int n_axes = job.axes;
    auto axis_of = [&](char letter) -> int {
        const auto k = opt.letters.find(letter);
        return k == std::string::npos ? -1 : static_cast<int>(k);
    };
    const int ix = axis_of('X'), iy = axis_of('Y'), ie = axis_of('E');

    std::size_t line_no = 0, begin = 0;
    while (begin < text.size()) {
        ++line_no;
        std::size_t end = text.find('\n', begin);
        if (end == std::string_view::npos) end = text.size();
        const std::string_view line = text.substr(begin, end - begin);
        begin = end + 1;

        auto words = split_words(line, src, line_no, !opt.strict);
        if (!words) return std::move(words).error();
        if (words->empty()) continue;

        int motion = -1;
        std::size_t motion_col = 0;
        bool dwell = false, set_position = false, home = false;
        std::array<const Word*, 26> seen{};
        std::array<const Word*, kMaxAxes> axis_word{};
        for (const Word& w : *words) {
            const std::string at = vec::place(src, line_no, w.column);
            auto unsupported = [&](const std::string& why = {}) {
                return make_error(Errc::unsupported, at + ": unsupported word '" +
                                                         std::string(1, w.letter) + w.text + "'" +
                                                         why);
            };
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
                    st.plane = g == 17 * one ? 17 : st.plane;
                } else if (opt.strict) {
                    return unsupported();
                } else if (other_motion(g)) {
                    return make_error(Errc::unsupported,
                                      at + ": unsupported motion word 'G" + w.text +
                                          "' (only G0, G1, G2 and G3 are planned)");
                } else if (g == 18 * one || g == 19 * one) {
                    st.plane = static_cast<int>(g / one);
                } else if (g == 92 * one) {
                    set_position = true;
                } else if (g == 28 * one) {
                    home = true;
                } else if (g != 80 * one) {
                    ++job.skipped_words;
                }
                continue;
            }
            if (w.letter == 'M') {
                const i128 one = vec::pow10(12);
                if (!opt.strict && w.value == 82 * one) {
                    st.e_mode = EMode::absolute;
                } else if (!opt.strict && w.value == 83 * one) {
                    st.e_mode = EMode::relative;
                } else {
                    ++job.skipped_words;  // machine functions: no motion
                }
                continue;
            }
            if (w.letter == 'N') continue;
            if (w.letter == 'F') {
                st.feed = static_cast<double>(w.value) / 1e12;
                continue;
            }
            if (w.letter == 'T' && opt.strict) {
                // a tool: the pen of the paths that follow (pen plotters)
                const i128 one = vec::pow10(12);
                if (w.value < 0 || w.value % one != 0 || w.value / one > 1000000)
                    return make_error(Errc::syntax, at + ": tool number " + w.text +
                                                        " is not a whole number in 0..1000000");
                st.pen = static_cast<int>(w.value / one);
                continue;
            }
            if (w.letter == 'S' || w.letter == 'T') {
                ++job.skipped_words;
                continue;
            }
            const int axis = axis_of(w.letter);
            if (axis >= 0 || w.letter == 'I' || w.letter == 'J' || w.letter == 'P') {
                const Word*& slot = seen[static_cast<std::size_t>(w.letter - 'A')];
                if (slot)
                    return make_error(Errc::syntax,
                                      at + ": word '" + std::string(1, w.letter) + "' repeated");
                slot = &w;
                if (axis >= 0) axis_word[static_cast<std::size_t>(axis)] = &w;
                continue;
            }
            if (opt.strict && w.letter == 'Z')
                return unsupported(" (G-code is read as two-axis X Y paths)");
            if (w.letter == 'R' && (opt.strict || motion == 2 || motion == 3 ||
                                    (motion < 0 && (st.motion == 2 || st.motion == 3))))
                return unsupported(" (give an arc's centre with I and J)");
            if (opt.strict) return unsupported();
            ++job.skipped_words;  // an axis the job does not have, or an unknown letter
        }
        for (const Word& w : *words)
            if (w.bare && !home)
                return make_error(Errc::syntax, vec::place(src, line_no, w.column + 1) +
                                                    ": expected a number after '" +
                                                    std::string(1, w.letter) + "'");
        const Word* wi = seen['I' - 'A'];
        const Word* wj = seen['J' - 'A'];
        const Word* wp = seen['P' - 'A'];
        if (wp && !dwell) {
            if (opt.strict)
                return make_error(Errc::unsupported, vec::place(src, line_no, wp->column) +
                                                         ": unsupported word 'P" + wp->text +
                                                         "' (P is read only with G4)");
            ++job.skipped_words;
        }
        bool has_axes = false;
        for (int a = 0; a < n_axes; ++a) has_axes = has_axes || axis_word[static_cast<std::size_t>(a)];

        // The exact value of an axis word in 10^-15 mm, and its steps.
        auto word_e15 = [&](const Word& w) {
            const bool rotary = w.letter == 'A' || w.letter == 'B' || w.letter == 'C';
            return w.value * (rotary ? vec::kPerMm : st.unit);
        };
        auto to_steps = [&](int a, i128 machine_pos, const Word& w) {
            return vec::to_steps(machine_pos, opt.scale[static_cast<std::size_t>(a)],
                                 vec::place(src, line_no, w.column), w.text);
        };

        if (home || set_position) {
            if (motion >= 0)
                return make_error(Errc::syntax, vec::place(src, line_no, motion_col) +
                                                    ": a motion word on a G28 or G92 line");
            for (int a = 0; a < n_axes; ++a) {
                const auto k = static_cast<std::size_t>(a);
                const Word* w = axis_word[k];
                if (has_axes && !w) continue;
                if (home) {
                    st.machine[k] = 0;
                    st.offset[k] = 0;
                } else {
                    st.offset[k] = (w ? word_e15(*w) : 0) - st.machine[k];
                }
            }
            if (home) {
                Point now{};
                for (int a = 0; a < n_axes; ++a) {
                    const auto k = static_cast<std::size_t>(a);
                    now[k] = has_axes && !axis_word[k] ? st.steps[k] : 0;
                }
                if (now != st.steps) {
                    st.steps = now;
                    if (!job.runs.back().moves.empty()) job.runs.emplace_back();
                    job.runs.back().start = now;
                }
            }
            continue;
        }

        if (motion >= 0) st.motion = motion;
        const bool rapid_word = motion == 0;
        if (!has_axes && !(wi || wj) && motion < 0) continue;  // no motion on this line
        const Word* first = nullptr;
        for (int a = 0; a < n_axes && !first; ++a) first = axis_word[static_cast<std::size_t>(a)];
        if (!first) first = wi ? wi : wj;
        const std::size_t col = motion >= 0 ? motion_col : first->column;
        if (st.motion < 0)
            return make_error(Errc::syntax, vec::place(src, line_no, col) +
                                                ": coordinates before any G0, G1, G2 or G3");
        const bool arc = st.motion == 2 || st.motion == 3;
        if ((wi || wj) && !arc)
            return make_error(Errc::syntax, vec::place(src, line_no, (wi ? wi : wj)->column) +
                                                ": I or J outside an arc (G2 or G3)");
        if (arc && !(wi || wj)) {
            if (!has_axes && motion >= 0) continue;  // "G2" alone only sets the mode
            return make_error(Errc::unsupported,
                              vec::place(src, line_no, col) +
                                  ": arc without I or J (give the centre with I and J)");
        }
        if (arc && (ix < 0 || iy < 0))
            return make_error(Errc::unsupported, vec::place(src, line_no, col) +
                                                     ": an arc needs the X and Y axes");
        if (arc && st.plane != 17)
            return make_error(Errc::unsupported,
                              vec::place(src, line_no, col) + ": arc in the G" +
                                  std::to_string(st.plane) + " plane (only G17, X Y, is read)");
        if (!has_axes && !arc) {
            // "G1" alone only sets the mode; "G0" alone lifts the pen
            if (rapid_word && opt.strict) {
                MachineMove mv;
                mv.rapid = true;
                mv.to = st.steps;
                job.runs.back().moves.push_back(mv);
            }
            continue;
        }

        // The targets, exactly, then in steps.
        const std::array<i128, kMaxAxes> start = st.machine;
        MachineMove mv;
        mv.rapid = st.motion == 0;
        mv.to = st.steps;
        mv.feed = st.feed;
        mv.pen = st.pen;
        mv.line = static_cast<std::uint32_t>(line_no);
        mv.column = static_cast<std::uint32_t>(col);
        for (int a = 0; a < n_axes; ++a) {
            const auto k = static_cast<std::size_t>(a);
            const Word* w = axis_word[k];
            if (!w) continue;
            const bool relative = a == ie && st.e_mode != EMode::follow
                                      ? st.e_mode == EMode::relative
                                      : !st.absolute;
            st.machine[k] = relative ? st.machine[k] + word_e15(*w) : word_e15(*w) - st.offset[k];
            auto r = to_steps(a, st.machine[k], *w);
            if (!r) return std::move(r).error();
            mv.to[k] = *r;
        }
        if (arc) {
            mv.kind = st.motion == 2 ? MoveKind::arc_cw : MoveKind::arc_ccw;
            const auto kx = static_cast<std::size_t>(ix), ky = static_cast<std::size_t>(iy);
            const i128 ci = wi ? wi->value * st.unit : 0;
            const i128 cj = wj ? wj->value * st.unit : 0;
            const i128 cxe = st.ij_absolute ? ci - st.offset[kx] : start[kx] + ci;
            const i128 cye = st.ij_absolute ? cj - st.offset[ky] : start[ky] + cj;
            const Word* wc = wi ? wi : wj;
            Word zero;
            zero.text = "0";
            zero.column = wc->column;
            auto rx = to_steps(ix, cxe, wi ? *wi : zero);
            if (!rx) return std::move(rx).error();
            auto ry = to_steps(iy, cye, wj ? *wj : zero);
            if (!ry) return std::move(ry).error();
            mv.cx = *rx;
            mv.cy = *ry;
            if (mv.cx == st.steps[kx] && mv.cy == st.steps[ky])
                return make_error(Errc::syntax, vec::place(src, line_no, wc->column) +
                                                    ": arc of radius zero (centre on its start)");
        }
        if (arc || mv.to != st.steps || (rapid_word && opt.strict))
            job.runs.back().moves.push_back(mv);
        st.steps = mv.to;
    }
    return job;
}

}  // namespace

Result<Drawing> read_gcode(std::string_view text, const VectorReadOptions& options) {
    CoreOptions opt;
    opt.source = options.source;
    opt.strict = true;
    opt.scale.fill(vec::AxisScale::of(options.step_size));
    auto job = read_core(text, opt);
    if (!job) return std::move(job).error();
    // Paths: a rapid move lifts the pen; a drawing move starts a path where
    // the pen is if none is open. Dots (paths without moves) are dropped.
    Drawing drawing;
    bool open = false;
    std::int64_t x = 0, y = 0;
    for (const MachineMove& m : job->runs.front().moves) {
        if (m.rapid) {
            open = false;
        } else {
            if (!open || drawing.back().pen != m.pen) drawing.push_back(VectorPath{x, y, {}, m.pen});
            open = true;
            VectorMove v;
            v.kind = m.kind;
            v.x = m.to[0];
            v.y = m.to[1];
            v.cx = m.cx;
            v.cy = m.cy;
            v.line = m.line;
            v.column = m.column;
            drawing.back().moves.push_back(v);
        }
        x = m.to[0];
        y = m.to[1];
    }
    return drawing;
}

Result<MachineJob> read_gcode_job(std::string_view text, const MachineReadOptions& options) {
    CoreOptions opt;
    opt.source = options.source;
    opt.letters.clear();
    for (const char c : options.axes) {
        const char u = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
        if (std::string_view("XYZABCE").find(u) == std::string_view::npos)
            return make_error(Errc::invalid_argument,
                              "axes '" + options.axes + "': '" + std::string(1, c) +
                                  "' is not one of X Y Z A B C E");
        if (opt.letters.find(u) != std::string::npos)
            return make_error(Errc::invalid_argument,
                              "axes '" + options.axes + "': '" + std::string(1, u) + "' twice");
        opt.letters += u;
    }
    if (opt.letters.size() < 2 || opt.letters.size() > static_cast<std::size_t>(kMaxAxes))
        return make_error(Errc::invalid_argument,
                          "axes '" + options.axes + "': give two to six axes");
    const std::size_t n = opt.letters.size();
    const auto& spm = options.steps_per_mm;
    if (!spm.empty() && spm.size() != 1 && spm.size() != n)
        return make_error(Errc::invalid_argument,
                          "steps per mm: " + std::to_string(spm.size()) + " values for " +
                              std::to_string(n) + " axes (give one, or one per axis)");
    for (std::size_t a = 0; a < n && !spm.empty(); ++a) {
        const std::string& t = spm[spm.size() == 1 ? 0 : a];
        std::size_t pos = 0;
        i128 v = 0;
        const std::string why = vec::parse_decimal(t, pos, v);
        if (!why.empty() || pos != t.size() || v <= 0)
            return make_error(Errc::invalid_argument,
                              "steps per mm '" + t + "': " +
                                  (why.empty() ? std::string("not a positive decimal number") : why));
        opt.scale[a] = vec::AxisScale::per_mm(v);
    }
    return read_core(text, opt);
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
    int pen = 1;
    for (const VectorPath& path : drawing) {
        if (path.pen != pen) {
            pen = path.pen;
            out += "T" + std::to_string(pen) + "\n";
        }
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
