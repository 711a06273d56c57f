// SVG in: path commands and number syntax, shapes, transforms, units, pens,
// the flattening tolerance, errors with line:column, and the round trip
// through the plain SVG writer. (tests/tools/svg_in.sh compares with
// rsvg-convert's raster.)
#include <gtest/gtest.h>

#include <algorithm>
#include <utility>
#include <cmath>
#include <functional>
#include <string>

#include "stepzip/vectors.hpp"

using namespace stepzip;

namespace {

using Pts = std::vector<std::pair<std::int64_t, std::int64_t>>;

Drawing svg(const std::string& body, double tolerance = 0.5, const std::string& root_attrs = "") {
    VectorReadOptions o;
    o.source = "t.svg";
    o.tolerance = tolerance;
    auto r = read_svg("<svg xmlns=\"http://www.w3.org/2000/svg\"" + root_attrs + ">" + body +
                          "</svg>",
                      o);
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
    return r.ok() ? *r : Drawing{};
}

Pts points(const VectorPath& p) {
    Pts v{{p.x0, p.y0}};
    for (const VectorMove& m : p.moves) v.emplace_back(m.x, m.y);
    return v;
}

std::string error_of(const std::string& text) {
    VectorReadOptions o;
    o.source = "t.svg";
    auto r = read_svg(text, o);
    return r.ok() ? std::string("(accepted)") : r.error().message;
}

double dist_to_segment(double px, double py, double ax, double ay, double bx, double by) {
    const double dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
    const double t = l2 > 0 ? std::clamp(((px - ax) * dx + (py - ay) * dy) / l2, 0.0, 1.0) : 0;
    return std::hypot(px - ax - t * dx, py - ay - t * dy);
}

// Largest distance between the polyline and the curve (sampled), both ways.
double deviation(const Pts& poly, const std::function<std::pair<double, double>(double)>& curve) {
    std::vector<std::pair<double, double>> samples;
    for (int k = 0; k <= 4000; ++k) samples.push_back(curve(k / 4000.0));
    double worst = 0;
    for (const auto& [x, y] : samples) {  // curve -> polyline
        double best = 1e300;
        for (std::size_t i = 1; i < poly.size(); ++i)
            best = std::min(best, dist_to_segment(x, y, double(poly[i - 1].first), double(poly[i - 1].second),
                                                  double(poly[i].first), double(poly[i].second)));
        worst = std::max(worst, best);
    }
    for (std::size_t i = 1; i < poly.size(); ++i)  // polyline (5 points per chord) -> curve
        for (int s = 0; s <= 4; ++s) {
            const double t = s / 4.0;
            const double x = double(poly[i - 1].first) + t * double(poly[i].first - poly[i - 1].first);
            const double y = double(poly[i - 1].second) + t * double(poly[i].second - poly[i - 1].second);
            double best = 1e300;
            for (std::size_t k = 1; k < samples.size(); ++k)
                best = std::min(best, dist_to_segment(x, y, samples[k - 1].first, samples[k - 1].second,
                                                      samples[k].first, samples[k].second));
            worst = std::max(worst, best);
        }
    return worst;
}

// Rounding each vertex to the nearest step moves it by at most this.
const double kRound = std::sqrt(0.5);

}  // namespace

TEST(SvgIn, LinesAbsoluteRelativeImplicitAndClose) {
    // y is negated: SVG's y grows downwards, steps' upwards.
    const Drawing d = svg("<path d='M10,10h10v10h-10z m30 0 l5-5 5 5'/>");
    ASSERT_EQ(d.size(), 2u);
    EXPECT_EQ(points(d[0]), (Pts{{10, -10}, {20, -10}, {20, -20}, {10, -20}, {10, -10}}));
    // after z the current point is the subpath's start (10,10): m30 0 -> (40,10)
    EXPECT_EQ(points(d[1]), (Pts{{40, -10}, {45, -5}, {50, -10}}));
}

TEST(SvgIn, EveryNumberSyntax) {
    // exponents, a leading point, signs and points as separators
    const Drawing d = svg("<path d='M1e1-2L.5e1.5E1-1e0-1+2 +3V-.4e+1H 7.'/>");
    ASSERT_EQ(d.size(), 1u);
    EXPECT_EQ(points(d[0]), (Pts{{10, 2}, {5, -5}, {-1, 1}, {2, -3}, {2, 4}, {7, 4}}));
}

TEST(SvgIn, ArcFlagsWithoutSeparatorsAndTheSweepSide) {
    // large-arc 1, sweep 0 written "10": a half circle of radius 10 about
    // (10, 0) through (10, 10) in SVG, (10, -10) in steps
    const Drawing d = svg("<path d='M0 0a10 10 0 1020 0'/>");
    ASSERT_EQ(d.size(), 1u);
    const Pts p = points(d[0]);
    EXPECT_EQ(p.front(), (std::pair<std::int64_t, std::int64_t>{0, 0}));
    EXPECT_EQ(p.back(), (std::pair<std::int64_t, std::int64_t>{20, 0}));
    for (const auto& [x, y] : p) {
        EXPECT_LE(y, 0);
        EXPECT_NEAR(std::hypot(x - 10.0, double(y)), 10, 0.5 + kRound);
    }
    // it reaches (10, -10) within the tolerance and the rounding
    EXPECT_LE(std::min_element(p.begin(), p.end(), [](auto a, auto b) { return a.second < b.second; })->second, -9);
    // sweep 1 takes the other side
    for (const auto& [x, y] : points(svg("<path d='M0 0A10 10 0 0 1 20 0'/>")[0])) EXPECT_GE(y, 0);
    // radii too small are scaled up (here to 10); a zero radius is a line
    EXPECT_EQ(points(svg("<path d='M0 0A1 1 0 0 1 20 0'/>")[0]),
              points(svg("<path d='M0 0A10 10 0 0 1 20 0'/>")[0]));
    EXPECT_EQ(points(svg("<path d='M0 0A0 5 0 0 1 20 0'/>")[0]), (Pts{{0, 0}, {20, 0}}));
}

TEST(SvgIn, SmoothCurvesReflectTheLastControlPoint) {
    EXPECT_EQ(svg("<path d='M0 0C0 10 10 10 10 0S20 -10 20 0'/>"),
              svg("<path d='M0 0C0 10 10 10 10 0C10 -10 20 -10 20 0'/>"));
    EXPECT_EQ(svg("<path d='m0 0c0 10 10 10 10 0s10-10 10 0'/>"),
              svg("<path d='M0 0C0 10 10 10 10 0S20 -10 20 0'/>"));
    EXPECT_EQ(svg("<path d='M0 0Q5 10 10 0T20 0'/>"), svg("<path d='M0 0Q5 10 10 0Q15 -10 20 0'/>"));
    EXPECT_EQ(svg("<path d='M0 0q5 10 10 0t10 0'/>"), svg("<path d='M0 0Q5 10 10 0T20 0'/>"));
    // S after a line: the first control point is the current point
    EXPECT_EQ(svg("<path d='M0 0L5 0S10 10 15 0'/>"), svg("<path d='M0 0L5 0C5 0 10 10 15 0'/>"));
    // a straight cubic is one chord
    EXPECT_EQ(points(svg("<path d='M0 0C10 0 20 0 30 0'/>")[0]), (Pts{{0, 0}, {30, 0}}));
}

TEST(SvgIn, BasicShapes) {
    EXPECT_EQ(points(svg("<line x1='1' y1='2' x2='8' y2='-3'/>")[0]), (Pts{{1, -2}, {8, 3}}));
    EXPECT_EQ(points(svg("<polyline points='0,0 5,0,5 5'/>")[0]), (Pts{{0, 0}, {5, 0}, {5, -5}}));
    EXPECT_EQ(points(svg("<polygon points='0 0 5 0 5 5'/>")[0]),
              (Pts{{0, 0}, {5, 0}, {5, -5}, {0, 0}}));
    EXPECT_EQ(points(svg("<rect x='1' y='2' width='4' height='3'/>")[0]),
              (Pts{{1, -2}, {5, -2}, {5, -5}, {1, -5}, {1, -2}}));
    EXPECT_TRUE(svg("<rect width='0' height='3'/><circle r='0'/>").empty());  // not rendered
    // rounded corners: ry follows rx, every vertex inside the box and the
    // corners cut off
    const Pts r = points(svg("<rect width='40' height='20' rx='10'/>")[0]);
    EXPECT_GT(r.size(), 9u);
    for (const auto& [x, y] : r) {
        EXPECT_TRUE(x >= 0 && x <= 40 && y <= 0 && y >= -20);
        EXPECT_FALSE(x < 3 && y > -3);
    }
    const Pts c = points(svg("<circle cx='50' cy='-50' r='20'/>")[0]);
    EXPECT_EQ(c.front(), c.back());
    EXPECT_EQ(c.front(), (std::pair<std::int64_t, std::int64_t>{70, 50}));
    for (const auto& [x, y] : c) EXPECT_NEAR(std::hypot(x - 50.0, y - 50.0), 20, 0.5 + kRound);
    const Pts e = points(svg("<ellipse cx='0' cy='0' rx='30' ry='10'/>")[0]);
    for (const auto& [x, y] : e) EXPECT_NEAR(double(x * x) / 900 + double(y * y) / 100, 1, 0.15);
    EXPECT_EQ(*std::max_element(e.begin(), e.end()), (std::pair<std::int64_t, std::int64_t>{30, 0}));
}

TEST(SvgIn, TransformsNestAndCompose) {
    auto line = [](const std::string& t, const std::string& inner = "") {
        return points(svg("<g transform='" + t + "'>" + (inner.empty() ? "" : "<g transform='" + inner + "'>") +
                          "<line x1='0' y1='0' x2='10' y2='0'/><line x1='0' y1='0' x2='0' y2='10'/>" +
                          (inner.empty() ? "" : "</g>") + "</g>")[0]);
    };
    EXPECT_EQ(line("translate(100,0) rotate(90)"), (Pts{{100, 0}, {100, -10}}));
    EXPECT_EQ(line("translate(100)", "rotate(90)"), (Pts{{100, 0}, {100, -10}}));
    EXPECT_EQ(line("rotate(90 10 0)"), (Pts{{10, 10}, {10, 0}}));
    EXPECT_EQ(line("matrix(1 0 0 1 5 6)"), (Pts{{5, -6}, {15, -6}}));
    EXPECT_EQ(line("scale(2,3)"), (Pts{{0, 0}, {20, 0}}));
    EXPECT_EQ(line("scale(3)"), (Pts{{0, 0}, {30, 0}}));
    EXPECT_EQ(line("skewY(45)"), (Pts{{0, 0}, {10, -10}}));
    const Drawing sk = svg("<g transform='skewX(45)'><line x1='0' y1='0' x2='0' y2='10'/></g>");
    EXPECT_EQ(points(sk[0]), (Pts{{0, 0}, {10, -10}}));
    // translate then scale: the scale applies first
    EXPECT_EQ(line("translate(1,1),scale(2)"), (Pts{{1, -1}, {21, -1}}));
    // the transform of a shape itself counts too
    EXPECT_EQ(points(svg("<g transform='translate(5 0)'><line transform='scale(2)' x2='3'/></g>")[0]),
              (Pts{{5, 0}, {11, 0}}));
}

TEST(SvgIn, UnitsViewBoxAndStepSize) {
    VectorReadOptions o;
    o.step_size = parse_step_size("0.5").value();
    // 100 mm over a viewBox 100 wide: a user unit is 1 mm, 2 steps; the
    // viewBox's origin does not move the drawing
    auto d = read_svg("<svg width='100mm' height='50mm' viewBox='-10 -10 100 50'>"
                      "<line x1='0' y1='0' x2='10' y2='5'/></svg>", o);
    ASSERT_TRUE(d.ok()) << d.error().message;
    EXPECT_EQ(points((*d)[0]), (Pts{{0, 0}, {20, -10}}));
    // without a viewBox a user unit is a CSS pixel (1/96 in): 96 px = 25.4 mm
    d = read_svg("<svg><line x2='96'/><line x1='0' x2='1in'/></svg>", o);
    ASSERT_TRUE(d.ok()) << d.error().message;
    EXPECT_EQ(points((*d)[0]), (Pts{{0, 0}, {51, 0}}));  // 50.8 steps, rounded
    EXPECT_EQ(points((*d)[1]), (Pts{{0, 0}, {51, 0}}));
    // without a step size a user unit is a step; units on shapes still count
    EXPECT_EQ(points(svg("<line x2='1in'/>")[0]), (Pts{{0, 0}, {96, 0}}));
}

TEST(SvgIn, LayersArePensAndUndrawnContentIsSkipped) {
    const Drawing d = svg(
        "<?xml-stylesheet href='x'?><title>t</title><style>path{stroke:red}</style>"
        "<line x2='1'/>"
        "<g inkscape:groupmode='layer' xmlns:inkscape='http://www.inkscape.org/namespaces/inkscape'>"
        "<g><line x2='2'/></g></g>"
        "<g id='second'><line x2='3'/><![CDATA[ <line x2='99'/> ]]></g>"
        "<defs><line x2='98'/></defs><text>a &amp; b</text>"
        "<line x2='97' display='none'/><g style='x'><line x2='4'/></g>");
    ASSERT_EQ(d.size(), 4u);
    EXPECT_EQ(d[0].moves[0].x, 1);
    EXPECT_EQ(d[0].pen, 1);
    EXPECT_EQ(d[1].moves[0].x, 2);
    EXPECT_EQ(d[1].pen, 1);
    EXPECT_EQ(d[2].moves[0].x, 3);
    EXPECT_EQ(d[2].pen, 2);
    EXPECT_EQ(d[3].moves[0].x, 4);
    EXPECT_EQ(d[3].pen, 1);
}

TEST(SvgIn, FlattenedCurvesStayWithinTheTolerance) {
    for (double tol : {0.25, 0.5, 2.0}) {
        SCOPED_TRACE(tol);
        // a cubic under a non-uniform scale and a skew
        const Pts cubic = points(svg("<g transform='skewX(20) scale(3 1)'>"
                                     "<path d='M0 0C0 300 300 300 300 -100'/></g>", tol)[0]);
        auto cubic_at = [](double t) {
            const double u = 1 - t;
            const double x = 3 * u * u * t * 0 + 3 * u * t * t * 300 + t * t * t * 300;
            const double y = 3 * u * u * t * 300 + 3 * u * t * t * 300 + t * t * t * -100;
            const double sx = 3 * x + std::tan(20 * std::acos(-1.0) / 180) * y;
            return std::pair<double, double>{sx, -y};
        };
        EXPECT_LE(deviation(cubic, cubic_at), tol + kRound);
        // a rotated elliptical arc, large and swept
        const Pts arc = points(svg("<path d='M0 0A400 150 30 1 1 200 100'/>", tol)[0]);
        // its centre form, worked out as SVG 1.1 F.6.5 gives it
        const double phi = 30 * std::acos(-1.0) / 180, cs = std::cos(phi), sn = std::sin(phi);
        const double hx = -100, hy = -50;
        const double x1 = cs * hx + sn * hy, y1 = -sn * hx + cs * hy;
        const double rx = 400, ry = 150;
        const double coef = std::sqrt((rx * rx * ry * ry - rx * rx * y1 * y1 - ry * ry * x1 * x1) /
                                      (rx * rx * y1 * y1 + ry * ry * x1 * x1));
        const double cxp = -coef * rx * y1 / ry, cyp = coef * ry * x1 / rx;  // large == sweep: minus
        const double cx = cs * cxp - sn * cyp + 100, cy = sn * cxp + cs * cyp + 50;
        const double t1 = std::atan2((y1 - cyp) / ry, (x1 - cxp) / rx);
        double dt = std::atan2((-y1 - cyp) / ry, (-x1 - cxp) / rx) - t1;
        if (dt < 0) dt += 2 * std::acos(-1.0);
        EXPECT_GT(dt, std::acos(-1.0));  // the large arc
        auto arc_at = [&](double t) {
            const double a = t1 + dt * t;
            const double x = cx + cs * rx * std::cos(a) - sn * ry * std::sin(a);
            const double y = cy + sn * rx * std::cos(a) + cs * ry * std::sin(a);
            return std::pair<double, double>{x, -y};
        };
        EXPECT_LE(deviation(arc, arc_at), tol + kRound);
    }
    // the tolerance decides the number of chords
    const auto count = [](double tol) { return svg("<circle r='1000'/>", tol)[0].moves.size(); };
    EXPECT_GT(count(0.25), count(2.0) + 40);
    EXPECT_LT(count(2.0), 200u);
}

TEST(SvgIn, PlainSvgOutputReadsBackToTheSameDrawing) {
    Drawing d;
    d.push_back(VectorPath{-5, 7, {}, 1});
    for (auto [x, y] : Pts{{10, 7}, {10, -20}, {3, 4}}) {
        VectorMove m;
        m.x = x;
        m.y = y;
        d[0].moves.push_back(m);
    }
    d.push_back(VectorPath{100, 100, {}, 1});
    VectorMove m;
    m.x = 101;
    m.y = 250;
    d[1].moves.push_back(m);
    auto text = write_svg_paths(d, "a -- comment");
    ASSERT_TRUE(text.ok());
    auto back = read_svg(*text);
    ASSERT_TRUE(back.ok()) << back.error().message;
    EXPECT_EQ(*back, d);
    EXPECT_EQ(detect_vector_format(*text), VectorFormat::svg);
}

TEST(SvgIn, ErrorsNameLineAndColumn) {
    EXPECT_EQ(error_of("<svg>\n <path d=\"M0 0 L 1 x\"/>\n</svg>"),
              "t.svg:2:18: missing or malformed arguments of 'L'");
    EXPECT_EQ(error_of("<svg>\n <path d=\"L0 0\"/></svg>"), "t.svg:2:11: path data must start with M");
    EXPECT_EQ(error_of("<svg>\n <path d=\"M0 0 X1\"/></svg>"), "t.svg:2:16: unknown path command 'X'");
    EXPECT_EQ(error_of("<svg>\n <g>\n</svg>"), "t.svg:3:1: end tag 'svg' does not close 'g'");
    EXPECT_EQ(error_of("<svg><g transform='spin(3)'/></svg>"),
              "t.svg:1:20: unknown transform 'spin' with 1 argument(s)");
    EXPECT_EQ(error_of("<svg><line x2='5%'/></svg>").substr(0, 27), "t.svg:1:16: attribute 'x2':");
    EXPECT_EQ(error_of("<svg>&nbsp;</svg>"), "t.svg:1:6: unknown entity '&nbsp;'");
    EXPECT_EQ(error_of("<svg a='1' a='2'/>"), "t.svg:1:12: repeated attribute 'a'");
    EXPECT_EQ(error_of("<svg></svg><g/>"), "t.svg:1:12: content after the root element");
    EXPECT_EQ(error_of("<svg/>\n<!-- ok --><g/>"), "t.svg:2:12: content after the root element");
    EXPECT_EQ(error_of("<html/>"), "t.svg:1:1: the root element is 'html', not 'svg'");
    EXPECT_EQ(error_of("<svg><!-- x </svg>"), "t.svg:1:6: unterminated comment");
    EXPECT_EQ(error_of("<svg><polygon points='1 2 3'/></svg>"), "t.svg:1:23: odd number of coordinates");
    EXPECT_EQ(error_of("<svg><line x2='1e12'/></svg>"), "t.svg:1:6: coordinate beyond the limit of 2^30 steps");
    VectorReadOptions o;
    o.tolerance = 0;
    EXPECT_FALSE(read_svg("<svg/>", o).ok());
}

TEST(SvgIn, DetectedFromContent) {
    EXPECT_EQ(detect_vector_format("\xEF\xBB\xBF<?xml version='1.0'?>\n<svg width='1'>"), VectorFormat::svg);
    EXPECT_EQ(detect_vector_format("<!-- a -->\n<svg>"), VectorFormat::svg);
    EXPECT_NE(detect_vector_format("<svgx>"), VectorFormat::svg);
    EXPECT_EQ(detect_vector_format("G1 X1 Y1\n"), VectorFormat::gcode);
    EXPECT_EQ(parse_vector_format("svg"), VectorFormat::svg);
    EXPECT_EQ(vector_format_name(VectorFormat::svg), "svg");
}
