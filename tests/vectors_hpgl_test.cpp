// HP-GL as a plotter reads it: arcs and circles, scaling, clipping, pens,
// encoded polylines, polygons, labels, escapes; pens through G-code and
// HP-GL output. (tests/tools/hpgl.sh runs hp2xx's own test files.)
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "stepzip/vectors.hpp"

using namespace stepzip;

namespace {

Drawing hpgl(const std::string& text) {
    VectorReadOptions o;
    o.source = "t.plt";
    auto r = read_hpgl(text, o);
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
    return r.ok() ? *r : Drawing{};
}

std::vector<std::pair<std::int64_t, std::int64_t>> points(const VectorPath& p) {
    std::vector<std::pair<std::int64_t, std::int64_t>> v{{p.x0, p.y0}};
    for (const VectorMove& m : p.moves) v.emplace_back(m.x, m.y);
    return v;
}

using Pts = std::vector<std::pair<std::int64_t, std::int64_t>>;

}  // namespace

TEST(HpglPlotter, CircleAboutThePenInChordsOfFiveDegrees) {
    const Drawing d = hpgl("PA1000,1000;CI500;PD1100,1000;");
    ASSERT_EQ(d.size(), 2u);
    const auto c = points(d[0]);
    EXPECT_EQ(c.size(), 73u);  // 360 / 5 chords, closed
    for (const auto& [x, y] : c) EXPECT_NEAR(std::hypot(x - 1000.0, y - 1000.0), 500, 0.75);
    EXPECT_EQ(c.front(), c.back());
    // the pen is back at the centre, up: the next line starts there
    EXPECT_EQ(points(d[1]), (Pts{{1000, 1000}, {1100, 1000}}));
}

TEST(HpglPlotter, ArcsAbsoluteRelativeAndThroughThreePoints) {
    Drawing d = hpgl("PU100,0;PD;AA0,0,90,30;");
    ASSERT_EQ(d.size(), 1u);
    EXPECT_EQ(points(d[0]), (Pts{{100, 0}, {87, 50}, {50, 87}, {0, 100}}));
    d = hpgl("PU100,0;PD;AR-100,0,-180,90;");
    EXPECT_EQ(points(d[0]), (Pts{{100, 0}, {0, -100}, {-100, 0}}));
    d = hpgl("PU0,0;PD;AT100,100,200,0,90;");  // through (100, 100): centre (100, 0)
    EXPECT_EQ(points(d[0]), (Pts{{0, 0}, {100, 100}, {200, 0}}));
}

TEST(HpglPlotter, UserScalingAnisotropicIsotropicAndPointFactor) {
    EXPECT_EQ(points(hpgl("IP0,0,1000,2000;SC0,10,0,10;PU1,1;PD2,3;")[0]),
              (Pts{{100, 200}, {200, 600}}));
    // isotropic: the smaller factor (100) on both axes, centred (left and
    // bottom 50 %): y gets (2000 - 1000) / 2 more
    EXPECT_EQ(points(hpgl("IP0,0,1000,2000;SC0,10,0,10,1;PU0,0;PD10,10;")[0]),
              (Pts{{0, 500}, {1000, 1500}}));
    EXPECT_EQ(points(hpgl("IP0,0,1000,2000;SC0,10,0,10,1,0,0;PU0,0;PD10,10;")[0]),
              (Pts{{0, 0}, {1000, 1000}}));
    EXPECT_EQ(points(hpgl("IP500,500;SC0,4,0,5,2;PU1,1;PD2,2;")[0]),
              (Pts{{504, 505}, {508, 510}}));
    // SC alone turns scaling off; relative moves scale too
    EXPECT_EQ(points(hpgl("IP0,0,100,100;SC0,10,0,10;PU1,1;PR;PD1,0;SC;PD1,0;")[0]),
              (Pts{{10, 10}, {20, 10}, {21, 10}}));
}

TEST(HpglPlotter, WindowClipsAndBreaksPaths) {
    const Drawing d = hpgl("IW0,0,100,100;PU-50,50;PD150,50,150,80,50,80;");
    ASSERT_EQ(d.size(), 2u);
    EXPECT_EQ(points(d[0]), (Pts{{0, 50}, {100, 50}}));
    EXPECT_EQ(points(d[1]), (Pts{{100, 80}, {50, 80}}));  // enters on x = 100
    EXPECT_TRUE(hpgl("IW0,0,10,10;PU20,20;PD30,30;").empty());
}

TEST(HpglPlotter, PensKeptAndPenZeroDrawsNothing) {
    const Drawing d = hpgl("SP1;PU0,0;PD10,0;SP2;PD10,10;SP0;PD0,10;SP3;PD0,0;");
    ASSERT_EQ(d.size(), 3u);
    EXPECT_EQ(d[0].pen, 1);
    EXPECT_EQ(d[1].pen, 2);
    EXPECT_EQ(points(d[1]), (Pts{{10, 0}, {10, 10}}));
    EXPECT_EQ(d[2].pen, 3);
    EXPECT_EQ(points(d[2]), (Pts{{0, 10}, {0, 0}}));
    // written back as HP-GL and as G-code (T words), the pens survive
    auto text = write_hpgl(d);
    ASSERT_TRUE(text.ok());
    EXPECT_NE(text->find("SP2;"), std::string::npos);
    EXPECT_EQ(hpgl(*text), d);
    const std::string g = write_gcode(d);
    EXPECT_NE(g.find("T2\n"), std::string::npos);
    auto back = read_gcode(g);
    ASSERT_TRUE(back.ok());
    EXPECT_EQ(*back, d);
}

TEST(HpglPlotter, EncodedPolyline) {
    // base 64: n -> 2|n| + sign; a last digit is 191 + d, others 63 + d.
    // (10, 0) and (0, 10) relative with the pen down, then '<': (10, 0) up,
    // then '=': absolute (0, 0) down, and (65, 0): 130 = 2 + 2 * 64 -> 65, 193.
    const std::string pe = std::string("PU0,0;PE") + "\xd3\xbf" + "\xbf\xd3" + "<" + "\xd3\xbf" +
                           "=" + "\xbf\xbf" + "\x41\xc1\xbf" + ";";
    const Drawing d = hpgl(pe);
    ASSERT_EQ(d.size(), 2u);
    EXPECT_EQ(points(d[0]), (Pts{{0, 0}, {10, 0}, {10, 10}}));
    EXPECT_EQ(points(d[1]), (Pts{{20, 10}, {0, 0}, {65, 0}}));
}

TEST(HpglPlotter, PolygonEdgesAndFilledShapesAsOutlines) {
    EXPECT_EQ(points(hpgl("PU0,0;PM0;PD10,0,10,10;PM2;EP;")[0]),
              (Pts{{0, 0}, {10, 0}, {10, 10}, {0, 0}}));
    EXPECT_EQ(points(hpgl("PU5,5;RR10,20;")[0]), (Pts{{5, 5}, {15, 5}, {15, 25}, {5, 25}, {5, 5}}));
    EXPECT_EQ(points(hpgl("PU5,5;EA0,0;")[0]), (Pts{{5, 5}, {0, 5}, {0, 0}, {5, 0}, {5, 5}}));
    const Drawing w = hpgl("PU0,0;WG100,0,90,45;");
    EXPECT_EQ(points(w[0]), (Pts{{0, 0}, {100, 0}, {71, 71}, {0, 100}, {0, 0}}));
    const Drawing b = hpgl("PU0,0;PD;BZ0,100,100,100,100,0;");
    EXPECT_EQ(points(b[0]).size(), 17u);
    EXPECT_EQ(points(b[0]).back(), (std::pair<std::int64_t, std::int64_t>{100, 0}));
}

TEST(HpglPlotter, LabelsInTheStrokeFont) {
    // SI 0.1 cm: 40 plotter units wide, 40 high; 'H' is three strokes
    const Drawing d = hpgl("SI0.1,0.1;PU100,100;LBH\x03PD200,100;");
    ASSERT_EQ(d.size(), 4u);
    EXPECT_EQ(points(d[0]), (Pts{{100, 100}, {100, 140}}));
    EXPECT_EQ(points(d[1]), (Pts{{140, 100}, {140, 140}}));
    EXPECT_EQ(points(d[2]), (Pts{{100, 120}, {140, 120}}));
    // the pen ends one character (1.5 widths) further, and stays up
    EXPECT_EQ(points(d[3]), (Pts{{160, 100}, {200, 100}}));
    // DT changes the terminator; symbol mode draws at every point
    EXPECT_EQ(hpgl("DT#;SI0.1,0.1;LB-#").size(), 1u);
    EXPECT_EQ(hpgl("SI0.1,0.1;SM-;PU0,0,100,0,200,0;").size(), 3u);
}

TEST(HpglPlotter, EscapesCommentsAndLenientSeparators) {
    const Drawing d = hpgl("\x1b%-1B\x1b" "E\x1b&l1O\x1b*b3W\x01\x02\x03" "CO\"a;b\";CO plain;IN;PD:10,10,;\x1b%0A");
    ASSERT_EQ(d.size(), 1u);
    EXPECT_EQ(points(d[0]), (Pts{{0, 0}, {10, 10}}));
    EXPECT_EQ(points(hpgl("RO90;PD10,0;")[0]), (Pts{{0, 0}, {0, 10}}));
    EXPECT_EQ(points(hpgl("PD10.5,-10.5;")[0]), (Pts{{0, 0}, {11, -11}}));  // rounded
    EXPECT_EQ(detect_vector_format("\x03IN;"), VectorFormat::hpgl);
    EXPECT_EQ(detect_vector_format("CO hello;"), VectorFormat::hpgl);
    EXPECT_EQ(detect_vector_format("\x1b%-1BIN;"), VectorFormat::hpgl);
    EXPECT_EQ(detect_vector_format("hello"), std::nullopt);
}
