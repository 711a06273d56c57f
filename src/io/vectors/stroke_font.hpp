// stepzip — the stroke font HP-GL labels are drawn with (internal).
//
// A small single-stroke font of this project's own design: printable ASCII
// (32-126) on a grid four units wide and six high (cap height), baseline at
// 0, descenders to -2. Lower-case letters are the capitals at 0.7 of their
// height. A glyph is a list of strokes; a stroke a polyline.
#pragma once

#include <vector>

namespace stepzip::vec {

struct GlyphPoint {
    double x, y;
};
using GlyphStroke = std::vector<GlyphPoint>;

/// Glyph width and cap height in font units.
inline constexpr double kGlyphWidth = 4;
inline constexpr double kGlyphHeight = 6;

/// The strokes of character `c`; empty for a space and for characters
/// outside printable ASCII (they are not drawn). Thread-safe.
std::vector<GlyphStroke> glyph_strokes(unsigned char c);

}  // namespace stepzip::vec
