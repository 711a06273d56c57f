// stepzip — segmented chains as an SVG picture.
#include <algorithm>
#include <cstdio>
#include <string>

#include "stepzip/vectors.hpp"

namespace stepzip {

namespace {

const char* shape_colour(SegmentShape s) {
    switch (s) {
        case SegmentShape::run: return "#1f6fd1";
        case SegmentShape::diagonal: return "#1e9e3a";
        case SegmentShape::slope: return "#d1301f";
    }
    return "#000";
}

}  // namespace

Result<std::string> write_svg(const std::vector<SegmentedChain>& chains, const CutInfo& info) {
    std::int64_t min_x = 0, max_x = 0, min_y = 0, max_y = 0;
    bool any = false;
    for (std::size_t c = 0; c < chains.size(); ++c) {
        const Chain& ch = chains[c].chain;
        if (ch.axes != 2)
            return make_error(Errc::unsupported,
                              "chain " + std::to_string(c + 1) + " has " +
                                  std::to_string(ch.axes) + " axes; SVG needs two-axis chains");
        Point p = ch.start;
        auto grow = [&](const Point& q) {
            if (!any) {
                min_x = max_x = q[0];
                min_y = max_y = q[1];
                any = true;
            }
            min_x = std::min(min_x, q[0]);
            max_x = std::max(max_x, q[0]);
            min_y = std::min(min_y, q[1]);
            max_y = std::max(max_y, q[1]);
        };
        grow(p);
        for (Step s : ch.steps) {
            apply_step(p, s, 2);
            grow(p);
        }
    }
    const std::int64_t margin = 2;
    const std::int64_t width = max_x - min_x + 2 * margin;
    const std::int64_t height = max_y - min_y + 2 * margin;
    // Picture coordinates: x - min_x + margin, and y flipped so it grows upwards.
    auto px = [&](std::int64_t x) { return std::to_string(x - min_x + margin); };
    auto py = [&](std::int64_t y) { return std::to_string(max_y - y + margin); };
    const double extent = static_cast<double>(std::max(width, height));
    const double scale = std::clamp(800.0 / extent, 0.01, 40.0);
    char buf[256];

    std::string out;
    out += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    std::snprintf(buf, sizeof buf,
                  "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 %lld %lld\" "
                  "width=\"%.0f\" height=\"%.0f\">\n",
                  static_cast<long long>(width), static_cast<long long>(height),
                  static_cast<double>(width) * scale, static_cast<double>(height) * scale);
    out += buf;
    out += "<title>stepzip segments: profile " + std::string(profile_name(info.profile)) +
           ", segmenter " + std::string(segmenter_name(info.segmenter)) +
           (info.exact ? "" : " (end points only, not step exact)") + "</title>\n";
    out += "<desc>grey: unit steps; blue: axis-parallel runs; green: diagonals; red: other "
           "slopes; dots: segment end points; circle: chain start</desc>\n";
    out += "<g fill=\"none\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n";
    // Sizes in picture units that come out as fixed pixel sizes at the
    // default width (no vector-effect: not every renderer supports it).
    const double px_unit = 1.0 / scale;
    const double r_end = 2.0 * px_unit;
    for (const SegmentedChain& sc : chains) {
        const Chain& ch = sc.chain;
        // the chain, step by step
        std::snprintf(buf, sizeof buf, "<polyline stroke=\"#b0b0b0\" stroke-width=\"%.4g\" points=\"",
                      3.0 * px_unit);
        out += buf;
        Point p = ch.start;
        out += px(p[0]) + "," + py(p[1]);
        for (Step s : ch.steps) {
            apply_step(p, s, 2);
            out += " " + px(p[0]) + "," + py(p[1]);
        }
        out += "\"/>\n";
        // the segments over it
        std::int64_t x = ch.start[0], y = ch.start[1];
        for (const Segment& s : sc.segments) {
            const std::int64_t nx = x + s.delta[0], ny = y + s.delta[1];
            std::snprintf(buf, sizeof buf, "\" stroke-width=\"%.4g\"", 1.5 * px_unit);
            out += "<line x1=\"" + px(x) + "\" y1=\"" + py(y) + "\" x2=\"" + px(nx) +
                   "\" y2=\"" + py(ny) + "\" stroke=\"" + shape_colour(segment_shape(s)) + buf;
            if (!info.exact) {
                std::snprintf(buf, sizeof buf, " stroke-dasharray=\"%.4g %.4g\"", 6 * px_unit,
                              3 * px_unit);
                out += buf;
            }
            out += "/>\n";
            x = nx;
            y = ny;
            std::snprintf(buf, sizeof buf, "<circle cx=\"%s\" cy=\"%s\" r=\"%.4g\" fill=\"#000\"/>\n",
                          px(x).c_str(), py(y).c_str(), r_end);
            out += buf;
        }
        std::snprintf(buf, sizeof buf,
                      "<circle cx=\"%s\" cy=\"%s\" r=\"%.4g\" fill=\"none\" stroke=\"#000\" "
                      "stroke-width=\"%.4g\"/>\n",
                      px(ch.start[0]).c_str(), py(ch.start[1]).c_str(), 2.5 * r_end, px_unit);
        out += buf;
    }
    out += "</g>\n</svg>\n";
    return out;
}

}  // namespace stepzip
