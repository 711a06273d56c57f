// stepzip — the stroke font of HP-GL labels (see stroke_font.hpp).
//
// Each glyph is written as strokes separated by spaces; a stroke is a run of
// points, two characters each: x as '0'..'4', y as '0'..'9' for -2..7.
#include "stroke_font.hpp"

#include <cctype>
#include <string_view>

namespace stepzip::vec {

namespace {

// Printable ASCII from '!' (33) to '~' (126); lower case is drawn from the
// upper case entries.
constexpr std::string_view kGlyphs[] = {
    "2824 2223",                                  // !
    "1817 3837",                                  // "
    "1713 3733 0646 0444",                        // #
    "473818070615354443321203 2921",              // $
    "0248 0717180807 3242433332",                 // %
    "42060718282703123244",                       // &
    "2826",                                       // '
    "38272332",                                   // (
    "18272312",                                   // )
    "2327 0545 1436 1634",                        // *
    "2327 0545",                                  // +
    "2311",                                       // ,
    "0545",                                       // -
    "2223",                                       // .
    "0248",                                       // /
    "183847433212030718 0347",                    // 0
    "162822 1232",                                // 1
    "07183847460242",                             // 2
    "07183847463515 354443321203",                // 3
    "32380444",                                   // 4
    "480805354443321203",                         // 5
    "4738180703123243443505",                     // 6
    "084812",                                     // 7
    "15060718384746351504031232434435",           // 8
    "0312324347381807061545",                     // 9
    "2627 2223",                                  // :
    "2627 2311",                                  // ;
    "470543",                                     // <
    "0646 0444",                                  // =
    "074503",                                     // >
    "07183847462524 2223",                        // ?
    "183847433212030718 3525263635",              // @
    "022842 1434",                                // A
    "0208 083847463505 3544433202",               // B
    "4738180703123243",                           // C
    "02083847433202",                             // D
    "42020848 0535",                              // E
    "020848 0535",                                // F
    "47381807031232434525",                       // G
    "0208 4248 0545",                             // H
    "1838 2822 1232",                             // I
    "4843321203",                                 // J
    "0208 4804 1542",                             // K
    "080242",                                     // L
    "0208254842",                                 // M
    "02084248",                                   // N
    "183847433212030718",                         // O
    "02083847463505",                             // P
    "183847433212030718 2442",                    // Q
    "02083847463505 2542",                        // R
    "473818070615354443321203",                   // S
    "0848 2822",                                  // T
    "080312324348",                               // U
    "082248",                                     // V
    "0812253248",                                 // W
    "0842 0248",                                  // X
    "082548 2522",                                // Y
    "08480242",                                   // Z
    "38282232",                                   // [
    "0842",                                       // backslash
    "18282212",                                   // ]
    "062846",                                     // ^
    "0141",                                       // _
    "1827",                                       // `
};
constexpr std::string_view kBraces[] = {
    "3828261524233232",  // {  (drawn as a bracket with a tick)
    "2820",              // |
    "1828361524231212",  // }
    "06173546",          // ~
};

std::vector<GlyphStroke> parse(std::string_view spec, double y_scale) {
    std::vector<GlyphStroke> strokes;
    GlyphStroke cur;
    for (std::size_t i = 0; i < spec.size();) {
        if (spec[i] == ' ') {
            if (!cur.empty()) strokes.push_back(std::move(cur));
            cur.clear();
            ++i;
            continue;
        }
        const double x = spec[i] - '0';
        const double y = spec[i + 1] - '2';
        cur.push_back({x, y * y_scale});
        i += 2;
    }
    if (!cur.empty()) strokes.push_back(std::move(cur));
    return strokes;
}

}  // namespace

std::vector<GlyphStroke> glyph_strokes(unsigned char c) {
    if (c >= 'a' && c <= 'z') return parse(kGlyphs[c - 'a' + 'A' - '!'], 0.7);
    if (c >= '!' && c <= '`') return parse(kGlyphs[c - '!'], 1.0);
    if (c >= '{' && c <= '~') return parse(kBraces[c - '{'], 1.0);
    return {};
}

}  // namespace stepzip::vec
