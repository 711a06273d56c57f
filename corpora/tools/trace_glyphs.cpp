// Renders the glyphs of a TrueType font with FreeType, thresholds them, and
// traces every region boundary into Freeman chains: 8-connected (Moore
// neighbour tracing of boundary pixels) or 4-connected (crack code: the walk
// along pixel edges between a region and its background).
//
// Usage: trace_glyphs FONT.ttf PIXEL_SIZE 8|4 [FIRST_CHAR LAST_CHAR] > out.fc
// Chains are placed glyph after glyph on a page, as a digitizer would see
// them; one chain per line, "X0 Y0 CODES".
#include <ft2build.h>
#include FT_FREETYPE_H

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

struct Bitmap {
    int w = 0, h = 0;
    std::vector<unsigned char> px;  // 1 = ink, with a one-pixel empty border
    bool at(int x, int y) const { return x >= 0 && y >= 0 && x < w && y < h && px[y * w + x]; }
};

// Freeman directions with y pointing up (the page's y = -row).
const int kDx[8] = {1, 1, 0, -1, -1, -1, 0, 1};
const int kDy[8] = {0, 1, 1, 1, 0, -1, -1, -1};

// Moore-neighbour tracing of the 8-connected boundary starting at ink pixel
// (sx, sy) whose west neighbour is background: from the backtrack pixel, scan
// the eight neighbours clockwise; the first ink pixel is the next boundary
// pixel and the pixel scanned just before it the new backtrack. Stops when
// the walk is back on the start pixel about to repeat its first move.
// Coordinates are image rows (y down); codes are Freeman y-up.
int dir_to(int fx, int fy, int tx, int ty) {
    for (int d = 0; d < 8; ++d)
        if (fx + kDx[d] == tx && fy - kDy[d] == ty) return d;
    return -1;
}

std::string trace8(const Bitmap& b, int sx, int sy, std::vector<unsigned char>& seen) {
    std::string codes;
    int x = sx, y = sy, bx = sx - 1, by = sy;
    int first_move = -1;
    for (;;) {
        seen[y * b.w + x] = 1;
        const int bd = dir_to(x, y, bx, by);
        int found = -1;
        for (int k = 1; k <= 8; ++k) {
            const int d = (bd - k + 16) % 8;  // clockwise on the page
            if (b.at(x + kDx[d], y - kDy[d])) { found = d; break; }
            bx = x + kDx[d];
            by = y - kDy[d];
        }
        if (found < 0) break;  // an isolated pixel has no boundary walk
        if (x == sx && y == sy && found == first_move) break;
        if (first_move < 0) first_move = found;
        x += kDx[found];
        y -= kDy[found];
        codes.push_back(static_cast<char>('0' + found));
    }
    return codes;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 4) {
        std::fprintf(stderr, "usage: trace_glyphs FONT PIXELS 8|4 [FIRST LAST]\n");
        return 2;
    }
    const int pixels = std::atoi(argv[2]);
    const int conn = std::atoi(argv[3]);
    const int first = argc > 5 ? std::atoi(argv[4]) : 33;
    const int last = argc > 5 ? std::atoi(argv[5]) : 126;
    FT_Library lib;
    FT_Face face;
    if (FT_Init_FreeType(&lib) || FT_New_Face(lib, argv[1], 0, &face)) {
        std::fprintf(stderr, "cannot open %s\n", argv[1]);
        return 1;
    }
    FT_Set_Pixel_Sizes(face, 0, pixels);
    long pen_x = 0, pen_y = 0;
    const long line_height = pixels * 5 / 4;
    int on_line = 0;
    std::printf("# %s, %d px, %d-connected boundaries, characters %d-%d\n", argv[1], pixels, conn,
                first, last);
    for (int ch = first; ch <= last; ++ch) {
        if (FT_Load_Char(face, ch, FT_LOAD_RENDER | FT_LOAD_TARGET_MONO)) continue;
        const FT_Bitmap& src = face->glyph->bitmap;
        Bitmap b;
        b.w = static_cast<int>(src.width) + 2;
        b.h = static_cast<int>(src.rows) + 2;
        b.px.assign(static_cast<std::size_t>(b.w) * b.h, 0);
        for (unsigned r = 0; r < src.rows; ++r)
            for (unsigned c = 0; c < src.width; ++c) {
                const unsigned char byte = src.buffer[r * src.pitch + (c >> 3)];
                if (byte & (0x80 >> (c & 7))) b.px[(r + 1) * b.w + c + 1] = 1;
            }
        const long ox = pen_x + face->glyph->bitmap_left - 1;
        const long oy = pen_y + face->glyph->bitmap_top + 1;  // row 0 is the top
        std::vector<unsigned char> seen(b.px.size(), 0);
        if (conn == 8) {
            // outer and hole boundaries: start at every ink pixel whose west
            // neighbour is background and that no trace has visited yet
            for (int y = 0; y < b.h; ++y)
                for (int x = 0; x < b.w; ++x)
                    if (b.at(x, y) && !b.at(x - 1, y) && !seen[y * b.w + x]) {
                        const std::string codes = trace8(b, x, y, seen);
                        if (codes.empty()) continue;  // an isolated pixel: no boundary walk
                        std::printf("%ld %ld %s\n", ox + x, oy - y, codes.c_str());
                    }
        } else {
            // crack code: walk the edges of pixel squares keeping ink on the
            // left; every vertical edge with ink on its left starts at most one walk
            std::vector<unsigned char> used(static_cast<std::size_t>(b.w + 1) * (b.h + 1) * 4, 0);
            auto ink = [&](int x, int y) { return b.at(x, y); };
            for (int y = 0; y < b.h; ++y)
                for (int x = 0; x < b.w; ++x) {
                    // edge on the west side of ink pixel (x,y) whose west is background:
                    // walk downward (image) = direction 6 in y-up coordinates
                    if (!(ink(x, y) && !ink(x - 1, y))) continue;
                    // corner coordinates: (cx, cy) in image space, corner (x, y) = top-left of pixel
                    int cx = x, cy = y, d = 6;
                    const std::size_t key0 = (static_cast<std::size_t>(cy) * (b.w + 1) + cx) * 4 + 3;
                    if (used[key0]) continue;
                    std::string codes;
                    const int sx = cx, sy = cy;
                    do {
                        const std::size_t key =
                            (static_cast<std::size_t>(cy) * (b.w + 1) + cx) * 4 + d / 2;
                        used[key] = 1;
                        codes.push_back(static_cast<char>('0' + d));
                        cx += kDx[d];
                        cy -= kDy[d];
                        // at the new corner, pixels around it (image coords):
                        // choose the next direction keeping ink on the left
                        // (left of travel in y-up space).
                        const int order[3] = {(d + 2) % 8, d, (d + 6) % 8};  // left, straight, right
                        int next = (d + 4) % 8;
                        for (int o : order) {
                            // pixel on the left of edge leaving (cx,cy) in direction o,
                            // and pixel on the right
                            int lx, ly, rx, ry;
                            switch (o) {
                                case 0: lx = cx; ly = cy - 1; rx = cx; ry = cy; break;
                                case 2: lx = cx - 1; ly = cy - 1; rx = cx; ry = cy - 1; break;
                                case 4: lx = cx - 1; ly = cy; rx = cx - 1; ry = cy - 1; break;
                                default: lx = cx; ly = cy; rx = cx - 1; ry = cy; break;
                            }
                            if (ink(lx, ly) && !ink(rx, ry)) { next = o; break; }
                        }
                        d = next;
                    } while (!(cx == sx && cy == sy && d == 6));
                    std::printf("%ld %ld %s\n", ox + sx, oy - sy, codes.c_str());
                }
        }
        pen_x += face->glyph->advance.x >> 6;
        if (++on_line == 16) {
            on_line = 0;
            pen_x = 0;
            pen_y -= line_height;
        }
    }
    FT_Done_Face(face);
    FT_Done_FreeType(lib);
    return 0;
}
