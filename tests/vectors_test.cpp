// Vector exchange: the G-code and HP-GL readers (every error with its
// line:column), step-size rounding, and writer -> reader round trips.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "stepzip/vectors.hpp"

using namespace stepzip;

namespace {

VectorMove line_to(std::int64_t x, std::int64_t y) {
    VectorMove m;
    m.x = x;
    m.y = y;
    return m;
}

VectorMove arc_to(MoveKind k, std::int64_t x, std::int64_t y, std::int64_t cx, std::int64_t cy) {
    VectorMove m;
    m.kind = k;
    m.x = x;
    m.y = y;
    m.cx = cx;
    m.cy = cy;
    return m;
}

Drawing gcode(const std::string& text, const char* step = nullptr) {
    VectorReadOptions o;
    o.source = "t.gcode";
    if (step) o.step_size = *parse_step_size(step);
    auto r = read_gcode(text, o);
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
    return r.ok() ? *r : Drawing{};
}

Drawing hpgl(const std::string& text, const char* step = nullptr) {
    VectorReadOptions o;
    o.source = "t.plt";
    if (step) o.step_size = *parse_step_size(step);
    auto r = read_hpgl(text, o);
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
    return r.ok() ? *r : Drawing{};
}

}  // namespace

TEST(GcodeRead, SpecExampleOneLine) {
    const Drawing d = gcode("G0 X0 Y0\nG1 X7 Y3\n");
    ASSERT_EQ(d.size(), 1u);
    EXPECT_EQ(d[0], (VectorPath{0, 0, {line_to(7, 3)}}));
    EXPECT_EQ(d[0].moves[0].line, 2u);
    EXPECT_EQ(d[0].moves[0].column, 1u);
}

TEST(GcodeRead, RapidMovesStartNewPathsAndDotsAreDropped) {
    const Drawing d = gcode(
        "G0 X1 Y1\nG1 X4 Y1\nY5\nG0 X10 Y10\nG0 X20 Y0\nG1 X20 Y0\nG1 X21\nG0 X0 Y0\n");
    ASSERT_EQ(d.size(), 2u);
    EXPECT_EQ(d[0], (VectorPath{1, 1, {line_to(4, 1), line_to(4, 5)}}));
    EXPECT_EQ(d[1], (VectorPath{20, 0, {line_to(21, 0)}}));
}

TEST(GcodeRead, FirstDrawingMoveWithoutRapidStartsAtOrigin) {
    const Drawing d = gcode("G1 X3 Y-2\n");
    EXPECT_EQ(d, (Drawing{VectorPath{0, 0, {line_to(3, -2)}}}));
}

TEST(GcodeRead, RelativeAndAbsoluteModes) {
    const Drawing d = gcode("G0 X5 Y5\nG91\nG1 X2 Y0\nX0 Y3\nG90 G1 X0 Y0\nG91 G0 X1 Y1\nG1 X-1\n");
    ASSERT_EQ(d.size(), 2u);
    EXPECT_EQ(d[0], (VectorPath{5, 5, {line_to(7, 5), line_to(7, 8), line_to(0, 0)}}));
    EXPECT_EQ(d[1], (VectorPath{1, 1, {line_to(0, 1)}}));
}

TEST(GcodeRead, CommentsLineNumbersMachineWordsAndCrlf) {
    const Drawing d = gcode(
        "%\r\n; a plot\r\n(header comment)\r\n\r\nN10 G21 G90 G17 G94 ( set up )\r\n"
        "N20 M3 S1000 T1\r\nN30 G0 X0 Y0 F3000\r\nn40 g1 x 7 y 3 ; lower case, spaces\r\n"
        "G4 P0.5\r\nM5\r\nM2\r\n%\r\n");
    EXPECT_EQ(d, (Drawing{VectorPath{0, 0, {line_to(7, 3)}}}));
}

TEST(GcodeRead, ArcsWithCentreOffsets) {
    const Drawing d = gcode("G0 X10 Y0\nG3 X0 Y10 I-10 J0\nG2 X10 Y0 I0 J-10\nG3 I-10\n");
    ASSERT_EQ(d.size(), 1u);
    EXPECT_EQ(d[0], (VectorPath{10, 0,
                                {arc_to(MoveKind::arc_ccw, 0, 10, 0, 0),
                                 arc_to(MoveKind::arc_cw, 10, 0, 0, 0),
                                 arc_to(MoveKind::arc_ccw, 10, 0, 0, 0)}}));
}

TEST(GcodeRead, ArcCentreAbsoluteModeAndRelativeEnd) {
    const Drawing d = gcode("G0 X10 Y0\nG90.1 G91 G3 X-10 Y10 I0 J0\nG91.1 G2 X10 Y-10 I0 J-10\n");
    ASSERT_EQ(d.size(), 1u);
    EXPECT_EQ(d[0], (VectorPath{10, 0,
                                {arc_to(MoveKind::arc_ccw, 0, 10, 0, 0),
                                 arc_to(MoveKind::arc_cw, 10, 0, 0, 0)}}));
}

TEST(GcodeRead, WholeStepsWithoutStepSize) {
    EXPECT_EQ(gcode("G1 X7.000 Y+3.\n"), (Drawing{VectorPath{0, 0, {line_to(7, 3)}}}));
}

TEST(GcodeRead, StepSizeRoundsHalvesAwayFromZero) {
    // 0.1 mm per step: 1.25 mm = 12.5 steps -> 13; -1.25 -> -13; 1.24 -> 12; 1.26 -> 13
    EXPECT_EQ(gcode("G1 X1.25 Y-1.25\n", "0.1"), (Drawing{VectorPath{0, 0, {line_to(13, -13)}}}));
    EXPECT_EQ(gcode("G1 X1.24 Y1.26\n", "0.1"), (Drawing{VectorPath{0, 0, {line_to(12, 13)}}}));
    // exact decimals: 0.3 / 0.1 is exactly 3 (no binary floating point)
    EXPECT_EQ(gcode("G1 X0.3 Y0.7\n", "0.1"), (Drawing{VectorPath{0, 0, {line_to(3, 7)}}}));
}

TEST(GcodeRead, StepSizeInchesAndNoDriftInRelativeMode) {
    // 1 inch = 25.4 mm = 1000 steps of 0.0254 mm
    EXPECT_EQ(gcode("G20 G1 X1 Y-0.5\n", "0.0254"),
              (Drawing{VectorPath{0, 0, {line_to(1000, -500)}}}));
    // ten relative moves of half a step end exactly five steps away
    std::string text = "G91\n";
    for (int i = 0; i < 10; ++i) text += "G1 X0.05\n";
    const Drawing d = gcode(text, "0.1");
    ASSERT_EQ(d.size(), 1u);
    ASSERT_FALSE(d[0].moves.empty());
    EXPECT_EQ(d[0].moves.back().x, 5);
    // positions 0.05 0.10 ... 0.50 mm round to 1 1 2 2 3 3 4 4 5 5: five distinct moves
    EXPECT_EQ(d[0].moves.size(), 5u);
}

struct ErrorCase {
    const char* text;
    Errc code;
    const char* message;
};

TEST(GcodeRead, EveryErrorNamesLineAndColumn) {
    const ErrorCase cases[] = {
        {"G28\n", Errc::unsupported, "t.gcode:1:1: unsupported word 'G28'"},
        {"G1 X1\nG1 Z5\n", Errc::unsupported, "t.gcode:2:4: unsupported word 'Z5'"},
        {"G1 X1 Q2\n", Errc::unsupported, "t.gcode:1:7: unsupported word 'Q2'"},
        {"G1 X1 X2\n", Errc::syntax, "t.gcode:1:7: word 'X' repeated"},
        {"G0 G1 X1\n", Errc::syntax, "t.gcode:1:4: two motion words on one line"},
        {"G1 X1 *12\n", Errc::syntax, "t.gcode:1:7: unexpected character '*'"},
        {"\n\nG1 X1 (oops\n", Errc::syntax, "t.gcode:3:7: comment '(' is not closed"},
        {"G1 X\n", Errc::syntax, "t.gcode:1:5: expected a number after 'X'"},
        {"G1 X1.1234567890123\n", Errc::syntax, "t.gcode:1:5: more than 12 fraction digits"},
        {"X5 Y1\n", Errc::syntax, "t.gcode:1:1: coordinates before any G0, G1, G2 or G3"},
        {"G1 X1 I1\n", Errc::syntax, "t.gcode:1:7: I or J outside an arc"},
        {"G2 X1 Y1\n", Errc::unsupported, "t.gcode:1:1: arc without I or J"},
        {"G2 X1 Y1 R1\n", Errc::unsupported, "t.gcode:1:10: unsupported word 'R1'"},
        {"G1 X1 P5\n", Errc::unsupported, "t.gcode:1:7: unsupported word 'P5'"},
        {"G0 X3\nG2 X0 Y0 I0 J0\n", Errc::syntax, "t.gcode:2:10: arc of radius zero"},
        {"G1 X2000000000\n", Errc::limit, "t.gcode:1:4: coordinate 2000000000 is beyond"},
        {"G1 X7.5\n", Errc::syntax, "t.gcode:1:4: coordinate 7.5 is not a whole number of steps"},
        {"% x\n", Errc::syntax, "t.gcode:1:3: text after '%'"},
    };
    for (const ErrorCase& c : cases) {
        VectorReadOptions o;
        o.source = "t.gcode";
        auto r = read_gcode(c.text, o);
        ASSERT_FALSE(r.ok()) << c.text;
        EXPECT_EQ(r.error().code, c.code) << c.text << " -> " << r.error().message;
        EXPECT_EQ(r.error().message.rfind(c.message, 0), 0u)
            << c.text << " -> " << r.error().message;
    }
}

TEST(HpglRead, PenUpPenDownAbsolute) {
    const Drawing d = hpgl("IN;SP1;PU0,0;PD7,3;PU;SP0;");
    EXPECT_EQ(d, (Drawing{VectorPath{0, 0, {line_to(7, 3)}}}));
    EXPECT_EQ(d[0].moves[0].column, 16u);
}

TEST(HpglRead, RelativeModeSeparatorsAndBackToBack) {
    const Drawing d = hpgl("IN;\nPU 10 10;PD20,10,20,20\nPR;PD-5,0 -5 -5;PU;PA;PU0,0PD0,1PUPD;\n");
    ASSERT_EQ(d.size(), 2u);
    EXPECT_EQ(d[0], (VectorPath{10, 10, {line_to(20, 10), line_to(20, 20), line_to(15, 20),
                                         line_to(10, 15)}}));
    EXPECT_EQ(d[1], (VectorPath{0, 0, {line_to(0, 1)}}));
}

TEST(HpglRead, PlotterUnitsWithStepSize) {
    // a plotter unit is 0.025 mm: at 0.1 mm per step 10 units = 2.5 steps -> 3
    EXPECT_EQ(hpgl("PD10,-10,40,0;", "0.1"),
              (Drawing{VectorPath{0, 0, {line_to(3, -3), line_to(10, 0)}}}));
    EXPECT_EQ(hpgl("PD40,80;", "0.025"), (Drawing{VectorPath{0, 0, {line_to(40, 80)}}}));
}

// What gnuplot's hpgl terminal writes: device-control escapes, scaling,
// label instructions and labels; none of them adds or moves a stroke.
TEST(HpglRead, AcceptsPlotterPreambleScalingAndLabels) {
    const std::string text =
        "\x1b.Y\n\x1b.I81;;17:\x1b.N;19:\x1b.M500:\nIN;\nSC0,10000,0,7500;\nSR0.2,0.4;\nDI0,1;\n"
        "SP1;\nPU;PA195,120;\nPD;PA309,120;\nPU;PA105,105;\nLB-1\x03\nPU;PA10,20;PD;PA10,30;\n";
    VectorReadOptions opt;
    opt.source = "t.plt";
    auto d = read_hpgl(text, opt);
    ASSERT_TRUE(d) << d.error().message;
    // SC0,10000,0,7500 maps user units onto P1 = (0, 0), P2 = (33600, 47520)
    // (hp2xx's default): x times 3.36, y times 6.336, rounded. The label
    // "-1" is drawn with the stroke font between the two lines: '-' one
    // stroke, '1' two, upwards (DI0,1), starting at (105, 105) user units.
    ASSERT_EQ(d->size(), 5u);
    EXPECT_EQ(d->front(), (VectorPath{655, 760, {line_to(1038, 760)}}));
    EXPECT_EQ(d->back(), (VectorPath{34, 127, {line_to(34, 190)}}));
    for (std::size_t k = 1; k < 4; ++k) {
        EXPECT_NEAR((*d)[k].x0, 353, 150);
        EXPECT_GE((*d)[k].y0, 665);
    }
    EXPECT_EQ(detect_vector_format(text), VectorFormat::hpgl);
}

TEST(HpglRead, EveryErrorNamesLineAndColumn) {
    const ErrorCase cases[] = {
        {"IN;ZZ5;", Errc::unsupported, "t.plt:1:4: unsupported instruction 'ZZ'"},
        {"IN;\nAA0,100;", Errc::syntax, "t.plt:2:1: AA wants a centre and an angle"},
        {"IN;LBtext", Errc::syntax, "t.plt:1:4: label (LB) not ended by ETX (0x03)"},
        {"\x1b" "\x01", Errc::syntax, "t.plt:1:1: ESC followed by byte 0x01"},
        {"PD1,2,3;", Errc::syntax, "t.plt:1:1: odd number of coordinates (3) in PD"},
        {"PD1,,2;", Errc::syntax, "t.plt:1:5: expected a number before ','"},
        {"IN;\nSP1;\n  1,2;", Errc::syntax, "t.plt:3:3: unexpected character '1'"},
        {"P", Errc::syntax, "t.plt:1:1: incomplete instruction 'P'"},
        {"PD2000000000,0;", Errc::limit, "t.plt:1:3: coordinate beyond the limit"},
        {"PD1,2*;", Errc::syntax, "t.plt:1:6: unexpected character '*' in PD"},
        {"PD--1,2;", Errc::syntax, "t.plt:1:3: expected a number"},
    };
    for (const ErrorCase& c : cases) {
        VectorReadOptions o;
        o.source = "t.plt";
        auto r = read_hpgl(c.text, o);
        ASSERT_FALSE(r.ok()) << c.text;
        EXPECT_EQ(r.error().code, c.code) << c.text << " -> " << r.error().message;
        EXPECT_EQ(r.error().message.rfind(c.message, 0), 0u)
            << c.text << " -> " << r.error().message;
    }
}

TEST(VectorFormat, DetectFromContent) {
    EXPECT_EQ(detect_vector_format("G0 X0 Y0\n"), VectorFormat::gcode);
    EXPECT_EQ(detect_vector_format("  ; comment\nG1 X1"), VectorFormat::gcode);
    EXPECT_EQ(detect_vector_format("%\n"), VectorFormat::gcode);
    EXPECT_EQ(detect_vector_format("N10 G1 X1"), VectorFormat::gcode);
    EXPECT_EQ(detect_vector_format("IN;SP1;"), VectorFormat::hpgl);
    EXPECT_EQ(detect_vector_format("pu0,0;pd1,1;"), VectorFormat::hpgl);
    EXPECT_EQ(detect_vector_format("0 0 0020020020\n"), std::nullopt);
    EXPECT_EQ(detect_vector_format(""), std::nullopt);
    EXPECT_EQ(detect_vector_format("hello"), std::nullopt);
}

TEST(StepSizeParse, AcceptsDecimalsAndRejectsTheRest) {
    EXPECT_EQ(parse_step_size("0.0125")->mm_e12, 12'500'000'000);
    EXPECT_EQ(parse_step_size("1")->mm_e12, 1'000'000'000'000);
    for (const char* bad : {"", "0", "-0.1", "abc", "0.1x", "0.0000000000001", "2000000"})
        EXPECT_FALSE(parse_step_size(bad).ok()) << bad;
}

TEST(GcodeWrite, GoldenAbsoluteAndRelative) {
    const Drawing d{VectorPath{0, 0, {line_to(8, 3), line_to(9, 3)}},
                    VectorPath{-2, 5, {arc_to(MoveKind::arc_ccw, -2, 5, -2, 0)}}};
    EXPECT_EQ(write_gcode(d),
              "; stepzip vectors: 2 path(s), coordinates in steps\nG90\n"
              "G0 X0 Y0\nG1 X8 Y3\nG1 X9 Y3\nG0 X-2 Y5\nG3 X-2 Y5 I0 J-5\n");
    GcodeWriteOptions rel;
    rel.relative = true;
    EXPECT_EQ(write_gcode(d, rel),
              "; stepzip vectors: 2 path(s), coordinates in steps\nG91\n"
              "G0 X0 Y0\nG1 X8 Y3\nG1 X1 Y0\nG0 X-11 Y2\nG3 X0 Y0 I0 J-5\n");
    GcodeWriteOptions mm;
    mm.step_size = *parse_step_size("0.025");
    EXPECT_EQ(write_gcode(Drawing{VectorPath{0, 0, {line_to(8, -3)}}}, mm),
              "; stepzip vectors: 1 path(s), coordinates in mm\nG90\nG21\n"
              "G0 X0 Y0\nG1 X0.2 Y-0.075\n");
}

TEST(HpglWrite, GoldenAndArcsRefused) {
    const Drawing d{VectorPath{0, 0, {line_to(8, 3), line_to(9, 3)}}};
    EXPECT_EQ(*write_hpgl(d), "IN;SP1;\nPU0,0;\nPD8,3,9,3;\nPU;SP0;\n");
    auto r = write_hpgl(Drawing{VectorPath{1, 0, {arc_to(MoveKind::arc_cw, -1, 0, 0, 0)}}});
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, Errc::unsupported);
}

namespace {

// A random drawing of lines (and arcs when `arcs`) with coordinates in [-r, r].
Drawing random_drawing(std::mt19937_64& rng, bool arcs, std::int64_t r) {
    std::uniform_int_distribution<std::int64_t> coord(-r, r);
    std::uniform_int_distribution<int> count(1, 12);
    Drawing d;
    const int paths = count(rng) % 5 + 1;
    for (int p = 0; p < paths; ++p) {
        VectorPath path{coord(rng), coord(rng), {}};
        std::int64_t x = path.x0, y = path.y0;
        const int moves = count(rng);
        for (int m = 0; m < moves; ++m) {
            VectorMove mv;
            do {
                mv.x = coord(rng);
                mv.y = coord(rng);
            } while (mv.x == x && mv.y == y);
            if (arcs && rng() % 3 == 0) {
                mv.kind = rng() % 2 ? MoveKind::arc_cw : MoveKind::arc_ccw;
                do {
                    mv.cx = coord(rng);
                    mv.cy = coord(rng);
                } while (mv.cx == x && mv.cy == y);
            }
            path.moves.push_back(mv);
            x = mv.x;
            y = mv.y;
        }
        d.push_back(std::move(path));
    }
    return d;
}

}  // namespace

TEST(VectorRoundTrip, GcodeAbsoluteRelativeAndMillimetres) {
    std::mt19937_64 rng(20240601);
    const char* sizes[] = {"0.1", "0.0125", "0.0254", "1.5", "0.333333333333"};
    for (int iter = 0; iter < 300; ++iter) {
        const Drawing d = random_drawing(rng, true, iter < 150 ? 20 : 1'000'000);
        GcodeWriteOptions o;
        o.relative = iter % 2 == 1;
        VectorReadOptions ro;
        if (iter % 3 == 2) {
            const char* s = sizes[iter % 5];
            o.step_size = *parse_step_size(s);
            ro.step_size = o.step_size;
        }
        const std::string text = write_gcode(d, o);
        auto back = read_gcode(text, ro);
        ASSERT_TRUE(back.ok()) << back.error().message << "\n" << text;
        ASSERT_EQ(*back, d) << text;
    }
}

TEST(VectorRoundTrip, HpglLines) {
    std::mt19937_64 rng(7);
    for (int iter = 0; iter < 300; ++iter) {
        const Drawing d = random_drawing(rng, false, iter < 150 ? 20 : 1'000'000);
        auto text = write_hpgl(d);
        ASSERT_TRUE(text.ok());
        auto back = read_hpgl(*text);
        ASSERT_TRUE(back.ok()) << back.error().message << "\n" << *text;
        ASSERT_EQ(*back, d) << *text;
    }
}

TEST(SegmentsToDrawing, OnePathPerChainOneLinePerSegment) {
    SegmentedChain a;
    a.chain.start = {0, 0};
    a.chain.steps.resize(11, freeman_to_step(0));
    a.segments.push_back(Segment{{8, 3}, {}});
    a.segments.push_back(Segment{{1, 0}, {}});
    SegmentedChain empty;
    empty.chain.start = {4, 4};
    SegmentedChain b;
    b.chain.start = {-3, 2};
    b.segments.push_back(Segment{{-2, -2}, {}});
    auto d = segments_to_drawing({a, empty, b});
    ASSERT_TRUE(d.ok());
    EXPECT_EQ(*d, (Drawing{VectorPath{0, 0, {line_to(8, 3), line_to(9, 3)}},
                           VectorPath{-3, 2, {line_to(-5, 0)}}}));
    SegmentedChain three;
    three.chain.axes = 3;
    three.segments.push_back(Segment{{1, 1, 1}, {}});
    EXPECT_EQ(segments_to_drawing({three}).error().code, Errc::unsupported);
}

TEST(SegmentShapeClass, RunsDiagonalsSlopes) {
    EXPECT_EQ(segment_shape(Segment{{5, 0}, {}}), SegmentShape::run);
    EXPECT_EQ(segment_shape(Segment{{0, -5}, {}}), SegmentShape::run);
    EXPECT_EQ(segment_shape(Segment{{-4, 4}, {}}), SegmentShape::diagonal);
    EXPECT_EQ(segment_shape(Segment{{3, 3, -3}, {}}), SegmentShape::diagonal);
    EXPECT_EQ(segment_shape(Segment{{7, 3}, {}}), SegmentShape::slope);
}
