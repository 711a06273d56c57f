// stepzip — HP-GL writer (SPEC §5); the reader is vectors/hpgl_reader.cpp.
#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

#include "gcode_units.hpp"
#include "stepzip/vectors.hpp"

namespace stepzip {

Result<std::string> write_hpgl(const Drawing& drawing, std::string_view comment) {
    std::string out = "IN;";
    if (!comment.empty()) {
        std::string c(comment);
        std::replace(c.begin(), c.end(), '"', '\'');
        out += "CO\"" + c + "\";";
    }
    int pen = drawing.empty() ? 1 : drawing.front().pen;
    out += "SP" + std::to_string(pen) + ";\n";
    for (std::size_t p = 0; p < drawing.size(); ++p) {
        const VectorPath& path = drawing[p];
        if (path.pen != pen) {
            pen = path.pen;
            out += "SP" + std::to_string(pen) + ";\n";
        }
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
