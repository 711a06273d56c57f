// Arc items in table blocks (docs/FORMAT.md 1.10.1): G-code jobs of random
// lines and arcs, stepped by each arc method, compress with `arc_method` to
// fewer bytes than with lines only (levels 1 and 12) and decompress to the same bytes; arcs
// copied by matches inside a block and from the window; the pinned bytes of
// a small arc payload; damaged arc payloads answered by an error naming a
// byte.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "../src/common/bytes.hpp"
#include "../src/container/arc_items.hpp"
#include "../src/container/block_codec.hpp"
#include "../src/container/table_block.hpp"
#include "../src/container/window.hpp"
#include "stepzip/container.hpp"
#include "stepzip/document.hpp"
#include "stepzip/interpolate/arc.hpp"
#include "stepzip/vectors.hpp"
#include "support/pinned_bytes.hpp"

namespace stepzip::stz {
namespace {

using Cut = std::vector<std::vector<Segment>>;
using test::hex;
using test::unhex;

constexpr ArcMethod kMethods[] = {ArcMethod::evaluation, ArcMethod::accelerated, ArcMethod::dda,
                                  ArcMethod::prediction_correction, ArcMethod::double_recursion};

// G-code of `paths` paths of `moves` random moves each: lines of 20 to 200
// steps, arcs of radius 15 to 150 turning 60 to 300 degrees either way
// (as corpora/tools/arc_job.py).
std::string random_job(std::mt19937_64& rng, int paths, int moves) {
    constexpr double kPi = 3.14159265358979323846;
    std::uniform_real_distribution<double> unit(0, 1);
    std::string g = "G21 G90\n";
    for (int p = 0; p < paths; ++p) {
        std::int64_t x = static_cast<std::int64_t>(rng() % 4000) - 2000;
        std::int64_t y = static_cast<std::int64_t>(rng() % 4000) - 2000;
        g += "G0 X" + std::to_string(x) + " Y" + std::to_string(y) + "\n";
        for (int i = 0; i < moves; ++i) {
            if (rng() % 2 == 0) {
                const double len = 20 + 180 * unit(rng), a = 2 * kPi * unit(rng);
                x += std::llround(len * std::cos(a));
                y += std::llround(len * std::sin(a));
                g += "G1 X" + std::to_string(x) + " Y" + std::to_string(y) + "\n";
                continue;
            }
            const double r = 15 + 135 * unit(rng), a = 2 * kPi * unit(rng);
            const std::int64_t i_off = std::llround(r * std::cos(a)), j_off = std::llround(r * std::sin(a));
            const bool ccw = rng() % 2 == 0;
            const double sweep = (60 + 240 * unit(rng)) * kPi / 180 * (ccw ? 1 : -1);
            const auto sx = static_cast<double>(-i_off), sy = static_cast<double>(-j_off);
            const std::int64_t cx = x + i_off, cy = y + j_off;
            const std::int64_t ex = cx + std::llround(sx * std::cos(sweep) - sy * std::sin(sweep));
            const std::int64_t ey = cy + std::llround(sx * std::sin(sweep) + sy * std::cos(sweep));
            g += std::string(ccw ? "G3" : "G2") + " X" + std::to_string(ex) + " Y" + std::to_string(ey) +
                 " I" + std::to_string(i_off) + " J" + std::to_string(j_off) + "\n";
            x = ex;
            y = ey;
        }
    }
    return g;
}

Profile profile_for(ArcMethod m) {
    return m == ArcMethod::evaluation || m == ArcMethod::prediction_correction ? Profile::eval4 : Profile::eval8;
}

// The chains `interpolate --profile P --arc-method M` draws for `gcode`.
std::vector<Chain> stepped(const std::string& gcode, ArcMethod method) {
    auto drawing = read_gcode(gcode);
    EXPECT_TRUE(drawing) << drawing.error().message;
    DrawingInterpolation how;
    how.profile = profile_for(method);
    how.arc_method = method;
    auto chains = interpolate_drawing(*drawing, how);
    EXPECT_TRUE(chains) << chains.error().message;
    return *chains;
}

std::string freeman(const std::vector<Chain>& chains) {
    auto text = write_chains(InputFormat::freeman, chains);
    EXPECT_TRUE(text);
    return *text;
}

std::size_t count_arcs(const Cut& cut) {
    std::size_t n = 0;
    for (const auto& c : cut)
        for (const Segment& s : c) n += is_arc(s, 2);
    return n;
}

Block block_of(const std::vector<Chain>& chains) {
    Block b;
    b.axes = 2;
    b.chains = chains;
    return b;
}

TEST(ContainerArc, LinesAndArcsJobsRoundTripSmallerUnderEveryMethod) {
    std::mt19937_64 rng(14);
    for (ArcMethod m : kMethods) {
        SCOPED_TRACE(std::string(arc_method_name(m)));
        const std::string text = freeman(stepped(random_job(rng, 2, 6), m));
        for (int level : {1, 12}) {
            CompressOptions o;
            o.level = level;
            o.profile = profile_for(m);
            auto lines = compress(text, o);
            ASSERT_TRUE(lines) << lines.error().message;
            o.arc_method = m;
            auto arcs = compress(text, o);
            ASSERT_TRUE(arcs) << arcs.error().message;
            auto back = decompress(*arcs);
            ASSERT_TRUE(back) << back.error().message;
            EXPECT_EQ(*back, text) << "level " << level;
            // From the strong levels the context-mixing step model, which
            // codes steps whatever their cut, may code both frames.
            if (level < 10) EXPECT_LT(arcs->size(), lines->size()) << "level " << level;
            else EXPECT_LE(arcs->size(), lines->size()) << "level " << level;
        }
    }
}

TEST(ContainerArc, ArcItemsComeBackAsDecoded) {
    std::mt19937_64 rng(7);
    for (ArcMethod m : kMethods) {
        SCOPED_TRACE(std::string(arc_method_name(m)));
        const Block b = block_of(stepped(random_job(rng, 2, 5), m));
        Cut cut;
        ASSERT_TRUE(arc_block_cut(b, profile_for(m), m, cut, 0, "test"));
        ASSERT_GE(count_arcs(cut), 1u);
        const std::string payload = write_table_block(b, profile_for(m), cut);
        Block out;
        BlockCounts counts;
        SegmentItems items;
        auto r = read_table_block(payload, profile_for(m), 2, true, out, counts, "test", nullptr, &items);
        ASSERT_TRUE(r) << r.error().message;
        EXPECT_EQ(out.chains, b.chains);
        EXPECT_TRUE(items.arcs);
        EXPECT_EQ(items.segments.size(), counts.segments);
        // The decoder's items are the encoder's (canonical lines, the arcs as cut).
        const SegmentItems want = segment_items(b, cut);
        std::size_t arcs = 0;
        for (std::size_t k = 0; k < items.segments.size(); ++k)
            if (is_arc(items.segments[k], 2)) {
                EXPECT_EQ(items.segments[k], want.segments[k]);
                EXPECT_EQ(arc_method_of(items.segments[k]), m);
                ++arcs;
            }
        EXPECT_EQ(arcs, count_arcs(cut));
        // Counting only (expand = false) gives the same counts.
        Block none;
        BlockCounts again;
        ASSERT_TRUE(read_table_block(payload, profile_for(m), 2, false, none, again, "test"));
        EXPECT_EQ(again.steps, counts.steps);
        EXPECT_TRUE(none.chains.empty());
    }
}

TEST(ContainerArc, ArcsCopiedByMatchesInTheBlockAndFromTheWindow) {
    std::mt19937_64 rng(3);
    const ArcMethod m = ArcMethod::dda;
    const Profile p = profile_for(m);
    const std::vector<Chain> job = stepped(random_job(rng, 1, 8), m);
    ASSERT_EQ(job.size(), 1u);
    // The same path three times, moved: the second and third are matches.
    std::vector<Chain> thrice;
    for (int k = 0; k < 3; ++k) {
        Chain c = job[0];
        c.start[0] += 1000 * k;
        thrice.push_back(c);
    }
    const Block once = block_of(job), three = block_of(thrice);
    Cut cut1, cut3;
    ASSERT_TRUE(arc_block_cut(once, p, m, cut1, 0, "test"));
    ASSERT_TRUE(arc_block_cut(three, p, m, cut3, 0, "test"));
    ASSERT_GE(count_arcs(cut1), 1u);
    const std::string p1 = write_table_block(once, p, cut1), p3 = write_table_block(three, p, cut3);
    EXPECT_LT(p3.size(), p1.size() + p1.size() / 2) << "the repeats cost far less than the first";
    Block out;
    BlockCounts counts;
    ASSERT_TRUE(read_table_block(p3, p, 2, true, out, counts, "test"));
    EXPECT_EQ(out.chains, three.chains);

    // From the window: the block after `once` holds the same path again.
    auto w = std::make_shared<WindowBlock>();
    w->items = segment_items(once, cut1);
    EXPECT_TRUE(w->items.arcs);
    const WindowView view{w};
    const std::string windowed = write_table_block(once, p, cut1, {}, &view);
    EXPECT_LT(windowed.size() * 2, p1.size());
    Block out2;
    BlockCounts counts2;
    SegmentItems items;
    auto r = read_table_block(windowed, p, 2, true, out2, counts2, "test", &view, &items);
    ASSERT_TRUE(r) << r.error().message;
    EXPECT_EQ(out2.chains, once.chains);
    EXPECT_TRUE(items.arcs);

    // Through the frame: small blocks, the window on, every level's path.
    const std::string text = freeman(thrice);
    for (int level : {3, 12}) {
        CompressOptions o;
        o.level = level;
        o.profile = p;
        o.arc_method = m;
        o.block_steps = job[0].steps.size() / 2;
        auto z = compress(text, o);
        ASSERT_TRUE(z) << z.error().message;
        auto back = decompress(*z);
        ASSERT_TRUE(back) << back.error().message;
        EXPECT_EQ(*back, text) << "level " << level;
    }
}

// One chain: a half turn of radius 12 about (0, 12) drawn by dda
// (counter-clockwise from the bottom of the circle to its top), then a line
// of 100 steps along -x (a block holds an arc only when it has at least the
// arc's step bound, here 124); its arc cut is one arc and one line.
Block small_arc_block(Cut& cut) {
    Chain c;
    c.axes = 2;
    EXPECT_TRUE(interpolate_arc(ArcMethod::dda, 0, -12, 0, 12, true, c.steps));
    for (int k = 0; k < 100; ++k) c.steps.push_back(make_step2(-1, 0));
    Block b = block_of({c});
    EXPECT_TRUE(arc_block_cut(b, Profile::eval8, ArcMethod::dda, cut, 0, "test"));
    return b;
}

TEST(ContainerArc, PinnedPayloadOfASmallArcBlock) {
    Cut cut;
    const Block b = small_arc_block(cut);
    ASSERT_EQ(cut.size(), 1u);
    ASSERT_EQ(count_arcs(cut), 1u);
    // (the arc draws the line's first 7 steps too)
    EXPECT_EQ(cut[0][0], arc_item(ArcFit{0, 12, -7, 24, true, 0}, ArcMethod::dda));
    const std::string payload = write_table_block(b, Profile::eval8, cut);
    EXPECT_EQ(hex(payload),
              "01 02 8b 01 01 00 00 a9 84 80 80 82 80 b0 1e 02 00 5b 01 01 00 00 1e 00 00 01 00 0e 00 00 00 00 "
              "00 00 01 01 00 00 0a 00 00 09 00 0a 08 02 00 04 00 01 00 04 00 48 1c");
    Block out;
    BlockCounts counts;
    ASSERT_TRUE(read_table_block(payload, Profile::eval8, 2, true, out, counts, "test"));
    EXPECT_EQ(out.chains, b.chains);
}

// The error of `payload` decoded as a two-axis (or `axes`) eval8 table block.
std::string error_of(const std::string& payload, int axes = 2) {
    Block out;
    BlockCounts counts;
    auto r = read_table_block(payload, Profile::eval8, axes, true, out, counts, "t");
    return r ? std::string("ok") : r.error().message;
}

TEST(ContainerArc, DamagedArcPayloadsNameAByte) {
    Cut cut;
    const Block b = small_arc_block(cut);
    const std::string good = write_table_block(b, Profile::eval8, cut);
    ASSERT_EQ(error_of(good), "ok");
    // Header: nchains 1, nsegments 2, nsteps, grid, layout (2 bytes), then the
    // table set (a varint of 8 bytes: bits 0..53), then the method byte.
    std::size_t set_at = 0;
    {
        wire::Cursor cur(good);
        std::uint64_t v;
        for (int k = 0; k < 4; ++k) ASSERT_TRUE(cur.varint(v));
        for (int k = 0; k < 2; ++k) ASSERT_TRUE(cur.varint(v));  // layout size, stored (empty layout)
        set_at = cur.pos();
        ASSERT_TRUE(cur.varint(v));
        ASSERT_TRUE((v >> 53) & 1);
    }
    const std::size_t method_at = set_at + 8;
    ASSERT_EQ(static_cast<unsigned char>(good[method_at]), static_cast<unsigned>(ArcMethod::dda));

    std::string bad = good;
    bad[method_at] = 5;  // no such method
    EXPECT_EQ(error_of(bad), "t byte " + std::to_string(method_at) + ": bad arc method");
    // The arc flag cleared: the arc tables (bits 50..52) without it.
    bad = good;
    bad[set_at + 7] = static_cast<char>(static_cast<unsigned char>(bad[set_at + 7]) & ~0x10);
    EXPECT_EQ(error_of(bad), "t byte " + std::to_string(set_at) + ": bad table set");
    // Arcs in a frame of four axes.
    EXPECT_EQ(error_of(good, 4).find("t byte " + std::to_string(set_at) + ": arcs in a frame of 4 axes"), 0u)
        << error_of(good, 4);
    // Fewer steps declared than the arc's bound: the arc is refused before
    // it is drawn (nsteps, 139, is bytes 2-3; 100 written in two bytes).
    ASSERT_EQ(hex(good.substr(2, 2)), "8b 01");
    bad = good;
    bad[2] = static_cast<char>(0xE4);
    bad[3] = 0;
    EXPECT_NE(error_of(bad).find("arc may draw more steps than declared"), std::string::npos) << error_of(bad);
    // Every byte changed: an error naming a byte, or a block (never a crash).
    for (std::size_t i = 0; i < good.size(); ++i)
        for (unsigned x : {0x01u, 0x80u, 0xFFu}) {
            bad = good;
            bad[i] = static_cast<char>(static_cast<unsigned char>(bad[i]) ^ x);
            const std::string e = error_of(bad);
            EXPECT_TRUE(e == "ok" || e.rfind("t byte ", 0) == 0) << i << ": " << e;
        }
}

TEST(ContainerArc, StepBoundHoldsForEveryMethod) {
    // Every end of small circles under every method: no arc draws more
    // steps than arc_step_bound (the decoder's guard).
    for (ArcMethod m : kMethods)
        for (std::int64_t cx = -12; cx <= 12; ++cx)
            for (std::int64_t cy = -12; cy <= 12; ++cy) {
                if (cx == 0 && cy == 0) continue;
                const double r = std::hypot(static_cast<double>(cx), static_cast<double>(cy));
                for (std::int64_t ex = -14; ex <= 14; ++ex)
                    for (std::int64_t ey = -14; ey <= 14; ++ey)
                        for (bool ccw : {false, true}) {
                            // (the interpolator refuses an end farther from the circle)
                            if (std::fabs(std::hypot(static_cast<double>(ex), static_cast<double>(ey)) - r) > 2.5)
                                continue;
                            std::vector<Step> steps;
                            if (!interpolate_arc(m, -cx, -cy, ex, ey, ccw, steps)) continue;
                            ASSERT_LE(steps.size(), arc_step_bound(cx, cy))
                                << arc_method_name(m) << " centre " << cx << "," << cy << " end " << ex << "," << ey;
                        }
            }
}

}  // namespace
}  // namespace stepzip::stz
