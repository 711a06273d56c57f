// stepzip — a drawing as plain SVG paths, for plotter programs.
#include <algorithm>
#include <string>

#include "stepzip/vectors.hpp"

namespace stepzip {

Result<std::string> write_svg_paths(const Drawing& drawing, std::string_view comment) {
    std::int64_t min_x = 0, max_x = 0, min_y = 0, max_y = 0;
    bool any = false;
    auto grow = [&](std::int64_t x, std::int64_t y) {
        if (!any) {
            min_x = max_x = x;
            min_y = max_y = y;
            any = true;
        }
        min_x = std::min(min_x, x);
        max_x = std::max(max_x, x);
        min_y = std::min(min_y, y);
        max_y = std::max(max_y, y);
    };
    for (std::size_t p = 0; p < drawing.size(); ++p) {
        grow(drawing[p].x0, drawing[p].y0);
        for (const VectorMove& m : drawing[p].moves) {
            if (m.kind != MoveKind::line)
                return make_error(Errc::unsupported, "path " + std::to_string(p + 1) +
                                                         ": SVG path output carries lines only");
            grow(m.x, m.y);
        }
    }
    const std::int64_t margin = 2;
    // After scale(1,-1) a point (x, y) lands at (x, -y): the box is
    // [min_x, max_x] x [-max_y, -min_y].
    const std::string w = std::to_string(max_x - min_x + 2 * margin);
    const std::string h = std::to_string(max_y - min_y + 2 * margin);
    std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    out += "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"" +
           std::to_string(min_x - margin) + " " + std::to_string(-max_y - margin) + " " + w +
           " " + h + "\" width=\"" + w + "\" height=\"" + h + "\">\n";
    if (!comment.empty()) {
        std::string c(comment);
        for (std::size_t k; (k = c.find("--")) != std::string::npos;) c.replace(k, 2, "- -");
        out += "<!-- " + c + " -->\n";
    }
    out += "<g transform=\"scale(1,-1)\" fill=\"none\" stroke=\"#000\" stroke-width=\"1\" "
           "stroke-linecap=\"round\" stroke-linejoin=\"round\">\n";
    for (const VectorPath& path : drawing) {
        out += "<path d=\"M" + std::to_string(path.x0) + " " + std::to_string(path.y0);
        for (const VectorMove& m : path.moves)
            out += " L" + std::to_string(m.x) + " " + std::to_string(m.y);
        out += "\"/>\n";
    }
    out += "</g>\n</svg>\n";
    return out;
}

}  // namespace stepzip
