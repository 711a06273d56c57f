// Chain files: each bad input gives the right error code and a message naming
// the exact place "SOURCE:LINE:COLUMN:"; format detection.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "stepzip/document.hpp"

namespace stepzip {
namespace {

using namespace std::string_literals;

struct Bad {
    std::string input;
    Errc code;
    std::string place;  // expected message prefix
};

// Feeds the whole input, then 1 byte at a time: both must fail the same way.
void expect_error(InputFormat f, const Bad& bad) {
    SCOPED_TRACE("input: " + bad.input);
    for (const bool bytewise : {false, true}) {
        BlockReader r(f, "t.txt", 3);
        Result<void> res;
        if (bytewise) {
            for (std::size_t i = 0; i < bad.input.size() && res.ok(); ++i)
                res = r.feed(bad.input.substr(i, 1), i + 1 == bad.input.size());
            if (bad.input.empty()) res = r.feed({}, true);
        } else {
            res = r.feed(bad.input, true);
        }
        ASSERT_FALSE(res.ok());
        EXPECT_EQ(res.error().code, bad.code) << res.error().message;
        EXPECT_EQ(res.error().message.rfind(bad.place, 0), 0u) << res.error().message;
        // The reader stays failed.
        auto again = r.feed("0 0 0\n", true);
        ASSERT_FALSE(again.ok());
        EXPECT_EQ(again.error().message, res.error().message);
    }
    auto chains = read_chains(f, bad.input, "t.txt");
    ASSERT_FALSE(chains.ok());
    EXPECT_EQ(chains.error().code, bad.code);
}

TEST(FreemanErrors, NameLineAndColumn) {
    const std::vector<Bad> cases = {
        {"0 0 0128\n", Errc::syntax, "t.txt:1:8: "},
        {"# ok\n0 0 01 2\n", Errc::syntax, "t.txt:2:8: "},
        {"0\n", Errc::syntax, "t.txt:1:2: "},
        {"0 x 01\n", Errc::syntax, "t.txt:1:3: "},
        {"a b c\n", Errc::syntax, "t.txt:1:1: "},
        {"0 0 01\r3\n", Errc::syntax, "t.txt:1:7: "},
        {"0 0 01\r", Errc::syntax, "t.txt:1:7: "},
        {"0 0 01\x00\n"s, Errc::syntax, "t.txt:1:7: "},
        {"# \x01 comment\n", Errc::syntax, "t.txt:1:3: "},
        {"0 0 -1\n", Errc::syntax, "t.txt:1:5: "},
        {"9999999999999999999 0 0\n", Errc::overflow, "t.txt:1:1: "},
        {"0 -4611686018427387905 0\n", Errc::overflow, "t.txt:1:3: "},
        // 10 x a 19-digit value wraps past 2^64 to below 2^62 if checked late
        {"40000000000000001204 0 0\n", Errc::overflow, "t.txt:1:1: "},
        {"+ 0 0\n", Errc::syntax, "t.txt:1:2: "},
        {"0 0 0\n1", Errc::syntax, "t.txt:2:2: "},
        {"0 0 0\r\n1 1 1\r\n2 2 2a\r\n", Errc::syntax, "t.txt:3:6: "},
        {"0 0 0\n\n\n  7 7 77x\n", Errc::syntax, "t.txt:4:9: "},
        {"0 0 0\n0" + std::string(5000, ' ') + "0 1\n", Errc::limit, "t.txt:2:4098: "},
        {"0,0 1\n", Errc::syntax, "t.txt:1:2: "},
        {"0 0 01\x80\n", Errc::syntax, "t.txt:1:7: "},
    };
    for (const Bad& b : cases) expect_error(InputFormat::freeman, b);
    // The largest coordinates are accepted.
    EXPECT_TRUE(read_chains(InputFormat::freeman, "4611686018427387904 -4611686018427387904 0\n").ok());
}

TEST(FreemanErrors, ErrorInsideALongLineAfterBlocksWereCut) {
    std::string in = "1 1 " + std::string(1000, '0') + "8\n";
    expect_error(InputFormat::freeman, {in, Errc::syntax, "t.txt:1:1005: "});
}

TEST(PointsErrors, NameLineAndColumn) {
    const std::vector<Bad> cases = {
        {"0 0\n2 0\n", Errc::not_a_step, "t.txt:2:1: "},
        {"0 0\n1 3\n", Errc::not_a_step, "t.txt:2:3: "},
        {"0 0\n0 0\n", Errc::not_a_step, "t.txt:2:1: "},
        {"0,0\n1,  -1\n0,  -3\n", Errc::not_a_step, "t.txt:3:5: "},
        {"0 0\n\n5 5\n7 5\n", Errc::not_a_step, "t.txt:4:1: "},
        {"0 0\n1 1 1\n", Errc::syntax, "t.txt:2:5: "},
        {"0 0 0\n1 1\n", Errc::syntax, "t.txt:2:4: "},
        {"5\n", Errc::syntax, "t.txt:1:2: "},
        {"1 2 3 4 5 6 7\n", Errc::syntax, "t.txt:1:13: "},
        {"1,,2\n", Errc::syntax, "t.txt:1:3: "},
        {"1 2 # c\n", Errc::syntax, "t.txt:1:5: "},
        {"1.5 2\n", Errc::syntax, "t.txt:1:2: "},
        {"0 0\n1 1\r2 2\n", Errc::syntax, "t.txt:2:4: "},
        {"0\x00 0"s, Errc::syntax, "t.txt:1:2: "},
        {"x y\n0 0\n", Errc::syntax, "t.txt:1:1: "},
        {"0 0\n1 99999999999999999999\n", Errc::overflow, "t.txt:2:3: "},
        {"40000000000000001204\t5 5\n", Errc::overflow, "t.txt:1:1: "},
        {std::string(70000, ' ') + "0 0\n", Errc::limit, "t.txt:1:65537: "},
        {"# fine\n0 0\n# \x1b[31m\n", Errc::syntax, "t.txt:3:3: "},
    };
    for (const Bad& b : cases) expect_error(InputFormat::points, b);
}

TEST(DocumentErrors, FeedAfterTheEndIsRefused) {
    for (InputFormat f : {InputFormat::freeman, InputFormat::points, InputFormat::steps}) {
        BlockReader r(f, "t");
        ASSERT_TRUE(r.feed("0 0\n", true).ok());
        auto res = r.feed("1 1\n", true);
        ASSERT_FALSE(res.ok());
        EXPECT_EQ(res.error().code, Errc::invalid_argument);
    }
}

TEST(FormatNames, RoundTrip) {
    for (InputFormat f : {InputFormat::freeman, InputFormat::points, InputFormat::steps})
        EXPECT_EQ(parse_format(format_name(f)), f);
    EXPECT_FALSE(parse_format("gcode").has_value());
}

// A head of Freeman text with one byte replaced, at every position of a
// head longer than two 16-byte lanes, by every byte value: binary exactly
// when the byte is a control other than TAB, LF and CR, or DEL.
TEST(DetectFormat, ABinaryByteAnywhereMakesStepBytes) {
    const std::string text = "0 0 0123456701234567\n10 -3 7654321076543210\n";
    for (std::size_t at = 0; at < text.size(); ++at)
        for (int c = 0; c < 256; ++c) {
            std::string head = text;
            head[at] = static_cast<char>(c);
            const bool binary = (c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7F;
            EXPECT_EQ(detect_format(head) == InputFormat::steps, binary) << "byte " << c << " at " << at;
        }
}

TEST(DetectFormat, FromTheFirstBytes) {
    EXPECT_EQ(detect_format(""), InputFormat::freeman);
    EXPECT_EQ(detect_format("# only a comment\n"), InputFormat::freeman);
    EXPECT_EQ(detect_format("0 0 0123\n1 1 45\n"), InputFormat::freeman);
    EXPECT_EQ(detect_format("# c\r\n0 0 0123"), InputFormat::freeman);
    EXPECT_EQ(detect_format("0 0 0123\n5 5 01"), InputFormat::freeman);  // cut mid-line
    EXPECT_EQ(detect_format("0 0 " + std::string(5000, '1')), InputFormat::freeman);
    EXPECT_EQ(detect_format("0 0\n1 0\n1 1\n"), InputFormat::points);
    EXPECT_EQ(detect_format("0,0\n1,1\n"), InputFormat::points);
    EXPECT_EQ(detect_format("1 2 3\n2 3 4\n"), InputFormat::points);
    EXPECT_EQ(detect_format("10\t20\n11\t21\n\n0\t0\n"), InputFormat::points);
    EXPECT_EQ(detect_format("\x01\x05\x00\x04"s), InputFormat::steps);
    EXPECT_EQ(detect_format("0 0 0\n\x01"s), InputFormat::steps);
    EXPECT_EQ(detect_format("hello world\n"), std::nullopt);
    // A file with a mistake is named after the format it follows longest,
    // so that the user sees that format's error.
    EXPECT_EQ(detect_format("0 0 012\n1 1 2\n2 2 9\n"), InputFormat::freeman);
    EXPECT_EQ(detect_format("0,0\n1,1\n5,5\n"), InputFormat::points);
}

}  // namespace
}  // namespace stepzip
