// Vector exchange: the JSON and SVG writers on segmented chains, and the
// segmenters' output drawn as G-code reproducing the SPEC's Fig. 5 example.
#include <gtest/gtest.h>

#include <string>

#include "stepzip/segmenter.hpp"
#include "stepzip/vectors.hpp"

using namespace stepzip;

namespace {

SegmentedChain fig5() {
    SegmentedChain sc;
    sc.chain = *from_freeman(0, 0, "02002002000");
    return sc;
}

std::size_t count(const std::string& s, const std::string& what) {
    std::size_t n = 0;
    for (auto p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
    return n;
}

}  // namespace

TEST(JsonWrite, Golden) {
    SegmentedChain a = fig5();
    a.segments = {Segment{{7, 3}, {0}}, Segment{{1, 0}, {0}}};
    SegmentedChain b;
    b.chain.axes = 3;
    b.chain.start = {1, -2, 3};
    b.chain.steps = {make_step(std::array<int, 3>{1, 1, 0}.data(), 3)};
    b.segments = {Segment{{1, 1, 0}, {0, 0}}};
    CutInfo info;
    info.profile = Profile::eval4;
    EXPECT_EQ(write_json({a}, info),
              "{\"profile\":\"eval4\",\"segmenter\":\"greedy\",\"exact\":true,\"chains\":[\n"
              "{\"start\":[0,0],\"steps\":11,\"segments\":[{\"delta\":[7,3],\"phase\":[0]},"
              "{\"delta\":[1,0],\"phase\":[0]}]}\n]}\n");
    info.profile = Profile::eval8;
    EXPECT_EQ(write_json({b}, info),
              "{\"profile\":\"eval8\",\"segmenter\":\"greedy\",\"exact\":true,\"chains\":[\n"
              "{\"start\":[1,-2,3],\"steps\":1,\"segments\":[{\"delta\":[1,1,0],\"phase\":[0,0]}]}"
              "\n]}\n");
}

TEST(JsonWrite, PatentModeCarriesItsDeviation) {
    SegmentedChain a = fig5();
    std::vector<Point> ends;
    ASSERT_TRUE(patent_approximate(a.chain.steps, ends).ok());
    ASSERT_EQ(ends.size(), 1u);
    for (const Point& e : ends) a.segments.push_back(default_segment(Profile::patent, e, 2));
    CutInfo info;
    info.profile = Profile::patent;
    info.segmenter = SegmenterKind::patent;
    info.exact = false;
    info.stats = SegmentStats{1, 0, 1};
    const std::string j = write_json({a}, info);
    EXPECT_NE(j.find("\"exact\":false,\"stats\":{\"patent_segments\":1,\"patent_exact\":0,"
                     "\"patent_max_deviation\":1}"),
              std::string::npos)
        << j;
    EXPECT_NE(j.find("{\"delta\":[8,3],\"phase\":[-5]}"), std::string::npos) << j;
}

TEST(GcodeWrite, Fig5UnderThePatentModeEndsItsFirstMoveAtX8Y3) {
    SegmentedChain a = fig5();
    std::vector<Point> ends;
    ASSERT_TRUE(patent_approximate(a.chain.steps, ends).ok());
    for (const Point& e : ends) a.segments.push_back(default_segment(Profile::patent, e, 2));
    auto d = segments_to_drawing({a});
    ASSERT_TRUE(d.ok());
    const std::string g = write_gcode(*d);
    EXPECT_NE(g.find("G0 X0 Y0\nG1 X8 Y3\n"), std::string::npos) << g;
}

TEST(SvgWrite, DrawsStepsSegmentsAndEndPoints) {
    SegmentedChain a = fig5();
    a.segments = {Segment{{7, 3}, {0}}, Segment{{1, 0}, {0}}};
    SegmentedChain b;
    b.chain = *from_freeman(-5, 4, "1111");
    b.segments = {Segment{{4, 4}, {}}};
    CutInfo info;
    info.profile = Profile::eval4;
    auto svg = write_svg({a, b}, info);
    ASSERT_TRUE(svg.ok());
    const std::string& s = *svg;
    EXPECT_EQ(s.rfind("<?xml", 0), 0u);
    EXPECT_EQ(count(s, "<polyline"), 2u);  // one per chain
    EXPECT_EQ(count(s, "<line "), 3u);     // one per segment
    EXPECT_EQ(count(s, "<circle"), 5u);    // segment ends + chain starts
    EXPECT_EQ(count(s, "#d1301f"), 1u);    // (7, 3): a general slope
    EXPECT_EQ(count(s, "#1f6fd1"), 1u);    // (1, 0): a run
    EXPECT_EQ(count(s, "#1e9e3a"), 1u);    // (4, 4): a diagonal
    EXPECT_EQ(count(s, "stroke-dasharray"), 0u);
    // bounding box x in [-5, 8], y in [0, 8], 2 units of margin
    EXPECT_NE(s.find("viewBox=\"0 0 17 12\""), std::string::npos);
    // y grows upwards: the first chain starts at (0, 0) -> picture (7, 10)
    EXPECT_NE(s.find("points=\"7,10 "), std::string::npos);
    EXPECT_EQ(s.substr(s.size() - 7), "</svg>\n");
    info.exact = false;
    EXPECT_EQ(count(*write_svg({a}, info), "stroke-dasharray"), 2u);
    SegmentedChain three;
    three.chain.axes = 3;
    EXPECT_EQ(write_svg({three}, info).error().code, Errc::unsupported);
}
