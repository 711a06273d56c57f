// Traces the ink regions of binary images (PBM, P4 or P1; 1 = ink) into
// Freeman chains, by other rules than trace_glyphs.cpp:
//   8: the 8-connected boundary of each region, walked counter-clockwise on
//      the page (ink on the left) from the region's topmost pixel of its
//      leftmost column (the image is scanned column by column), by a Moore
//      neighbour walk that scans the neighbours counter-clockwise;
//   4: the 4-connected inner boundary of each region (the region's pixels
//      that touch the background through an edge, visited through edges
//      only), walked by the left-hand rule from the same start.
// Images are placed left to right on a page, 8 to a row, as a scanner would
// hand them over; one chain per line, "X0 Y0 CODES".
//
// Usage: trace_pbm 8|4 IMAGE.pbm [IMAGE.pbm ...] > out.fc
#include <cctype>
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

int header_number(FILE* f) {
    int c = std::fgetc(f);
    for (;;) {
        while (c != EOF && std::isspace(c)) c = std::fgetc(f);
        if (c != '#') break;
        while (c != EOF && c != '\n') c = std::fgetc(f);
    }
    int v = 0;
    bool any = false;
    while (c != EOF && std::isdigit(c)) {
        v = v * 10 + (c - '0');
        any = true;
        c = std::fgetc(f);
    }
    if (!any) return -1;
    return v;  // the single white space after the number is consumed
}

bool read_pbm(const char* path, Bitmap& b) {
    FILE* f = std::fopen(path, "rb");
    if (!f) return false;
    const int p = std::fgetc(f), kind = std::fgetc(f);
    const int w = header_number(f), h = header_number(f);
    if (p != 'P' || (kind != '4' && kind != '1') || w <= 0 || h <= 0) {
        std::fclose(f);
        return false;
    }
    b.w = w + 2;
    b.h = h + 2;
    b.px.assign(static_cast<std::size_t>(b.w) * b.h, 0);
    for (int y = 0; y < h; ++y) {
        if (kind == '4') {
            std::vector<unsigned char> row(static_cast<std::size_t>((w + 7) / 8));
            if (std::fread(row.data(), 1, row.size(), f) != row.size()) break;
            for (int x = 0; x < w; ++x)
                if (row[x >> 3] & (0x80 >> (x & 7))) b.px[(y + 1) * b.w + x + 1] = 1;
        } else {
            for (int x = 0; x < w; ++x) {
                int c = std::fgetc(f);
                while (c != EOF && std::isspace(c)) c = std::fgetc(f);
                if (c == '1') b.px[(y + 1) * b.w + x + 1] = 1;
            }
        }
    }
    std::fclose(f);
    return true;
}

// Freeman directions with y pointing up (the page's y = -row).
const int kDx[8] = {1, 1, 0, -1, -1, -1, 0, 1};
const int kDy[8] = {0, 1, 1, 1, 0, -1, -1, -1};

// The walk of one boundary from (sx, sy), whose north neighbour is
// background: the first scan starts just counter-clockwise of north. `step`
// is 1 (8-connected: every direction) or 2 (4-connected: even directions
// only). After a move in direction `dir` the
// neighbours are scanned counter-clockwise from (dir + 7) % 8 for an even
// and (dir + 6) % 8 for an odd move (8-connected), from (dir + 6) % 8
// (4-connected): the first ink pixel is the next one, so ink stays on the
// left. Stops back on the start about to repeat its first move.
std::string trace(const Bitmap& b, int sx, int sy, int step, std::vector<unsigned char>& seen) {
    std::string codes;
    int x = sx, y = sy;
    int dir = -1;
    int first_move = -1;
    for (;;) {
        seen[y * b.w + x] = 1;
        const int from = dir < 0 ? 2 + step : step == 2 ? (dir + 6) % 8 : dir % 2 ? (dir + 6) % 8 : (dir + 7) % 8;
        int found = -1;
        for (int k = 0; k < 8; k += step) {
            const int d = (from + k) % 8;
            if (b.at(x + kDx[d], y - kDy[d])) {
                found = d;
                break;
            }
        }
        if (found < 0) break;  // an isolated pixel
        if (x == sx && y == sy && found == first_move) break;
        if (first_move < 0) first_move = found;
        x += kDx[found];
        y -= kDy[found];
        codes.push_back(static_cast<char>('0' + found));
        dir = found;
        if (codes.size() > 4 * b.px.size()) {  // cannot happen on a closed walk
            std::fprintf(stderr, "trace_pbm: the walk from (%d, %d) does not close\n", sx, sy);
            std::exit(1);
        }
    }
    return codes;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3 || (std::atoi(argv[1]) != 8 && std::atoi(argv[1]) != 4)) {
        std::fprintf(stderr, "usage: trace_pbm 8|4 IMAGE.pbm [IMAGE.pbm ...]\n");
        return 2;
    }
    const int step = std::atoi(argv[1]) == 8 ? 1 : 2;
    long pen_x = 0, pen_y = 0, row_height = 0;
    int on_row = 0;
    std::printf("# %d-connected boundaries (trace_pbm), %d images\n", 8 / step, argc - 2);
    for (int i = 2; i < argc; ++i) {
        Bitmap b;
        if (!read_pbm(argv[i], b)) {
            std::fprintf(stderr, "trace_pbm: %s: not a readable PBM image\n", argv[i]);
            return 1;
        }
        std::vector<unsigned char> seen(b.px.size(), 0);
        // column by column; a start is an ink pixel whose north is background
        // that no walk has visited (outer boundaries and holes alike)
        for (int x = 0; x < b.w; ++x)
            for (int y = 0; y < b.h; ++y)
                if (b.at(x, y) && !b.at(x, y - 1) && !seen[y * b.w + x]) {
                    const std::string codes = trace(b, x, y, step, seen);
                    if (codes.empty()) continue;
                    std::printf("%ld %ld %s\n", pen_x + x, pen_y - y, codes.c_str());
                }
        pen_x += b.w;
        if (b.h > row_height) row_height = b.h;
        if (++on_row == 8) {
            on_row = 0;
            pen_x = 0;
            pen_y -= row_height;
            row_height = 0;
        }
    }
    return 0;
}
