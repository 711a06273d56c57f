// Limits at their boundaries: segment totals (kMaxSegmentTotal), evaluation
// functions at the extremes of their phase ranges, chain-file coordinates
// (+-2^62), G-code and HP-GL coordinates (kMaxVectorCoord), arc coordinates;
// and that declared sizes in a hostile frame never drive an allocation beyond
// the documented decoder limits, while a large legitimate frame is decoded
// block by block in bounded memory.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <new>
#include <string>

#include "../src/container/memory_io.hpp"
#include "stepzip/container.hpp"
#include "stepzip/document.hpp"
#include "stepzip/interpolate/arc.hpp"
#include "stepzip/profile.hpp"
#include "stepzip/segmenter.hpp"
#include "stepzip/vectors.hpp"

// Largest single allocation through operator new since the last reset: the
// decoder's buffers (payloads, steps, rendered text) all come from here.
namespace {
std::atomic<std::size_t> g_largest_allocation{0};
void note_allocation(std::size_t n) {
    std::size_t seen = g_largest_allocation.load(std::memory_order_relaxed);
    while (n > seen && !g_largest_allocation.compare_exchange_weak(seen, n)) {
    }
}
}  // namespace

void* operator new(std::size_t n) {
    note_allocation(n);
    if (void* p = std::malloc(n ? n : 1)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace stepzip {
namespace {

constexpr std::int64_t kTotal = kMaxSegmentTotal;  // 2^30
constexpr std::int64_t k62 = std::int64_t{1} << 62;

// ------------------------------------------------------------ segment totals

TEST(HardeningLimits, SegmentTotalsUpTo2To30AreAcceptedAndBeyondAreLimit) {
    for (Profile p : kAllProfiles) {
        const int axes = profile_max_axes(p);
        for (int axis = 0; axis < axes; ++axis)
            for (std::int64_t sign : {1, -1}) {
                Point d{};
                d[axis] = sign * kTotal;
                d[(axis + 1) % axes] = sign * (kTotal - 1);
                EXPECT_TRUE(check_segment(p, default_segment(p, d, axes), axes).ok())
                    << profile_name(p) << " axis " << axis;
                d[axis] = sign * (kTotal + 1);
                auto r = check_segment(p, default_segment(p, d, axes), axes);
                ASSERT_FALSE(r.ok()) << profile_name(p);
                EXPECT_EQ(r.error().code, Errc::limit) << profile_name(p);
                d[axis] = sign * std::numeric_limits<std::int64_t>::max();  // never INT64_MIN: |.| is UB
                r = check_segment(p, default_segment(p, d, axes), axes);
                ASSERT_FALSE(r.ok());
                EXPECT_EQ(r.error().code, Errc::limit);
            }
    }
}

TEST(HardeningLimits, PhaseRangesAtTheLargestTotalsStayInsideInt64) {
    // The patent range reaches about a*b = 2^60; every bound must be exact
    // (a UBSan build checks that nothing overflows on the way).
    for (Profile p : kAllProfiles)
        for (std::int64_t a : {std::int64_t{1}, kTotal - 1, kTotal})
            for (std::int64_t b : {std::int64_t{0}, std::int64_t{1}, kTotal - 1, kTotal}) {
                if (profile_eight_connected(p) && b > a) continue;
                const PhaseRange r = phase_range(p, a, b);
                EXPECT_LT(r.lo, r.hi) << profile_name(p) << " " << a << " " << b;
                EXPECT_TRUE(r.contains(default_phase(p, a, b))) << profile_name(p) << " " << a << " " << b;
            }
    EXPECT_EQ(phase_range(Profile::patent, kTotal, kTotal).lo, -kTotal * kTotal);
    EXPECT_EQ(phase_range(Profile::patent, kTotal, kTotal).hi, kTotal * kTotal + 1);
}

// A segment of `n` steps whose minor total is `s` on `len` ticks, with
// extreme phases, expands to exactly its totals. Keeps the length small and
// puts the large values into the phase.
void expect_exact_totals(Profile p, const Segment& seg, int axes) {
    ASSERT_TRUE(check_segment(p, seg, axes).ok());
    std::vector<Step> steps;
    expand_segment(p, seg, axes, steps);
    Point end{};
    for (Step s : steps) apply_step(end, s, axes);
    EXPECT_EQ(end, seg.delta) << profile_name(p);
}

TEST(HardeningLimits, ExtremePhasesExpandToTheirTotals) {
    for (Profile p : kAllProfiles)
        for (std::int64_t a : {1, 2, 7, 1000})
            for (std::int64_t b : {1, 3, 999}) {
                const int axes = 2;
                Point d{a, profile_eight_connected(p) ? std::min(a, b) : b};
                Segment seg = default_segment(p, d, axes);
                const auto ab = *phase_arguments(p, seg, axes, 0);
                const PhaseRange r = phase_range(p, ab.first, ab.second);
                for (std::int64_t f : {r.lo, r.hi - 1}) {
                    seg.phase[0] = f;
                    expect_exact_totals(p, seg, axes);
                }
            }
}

TEST(HardeningLimits, LongestSegmentExpandsExactlyUnderEveryLeadingAxisProfile) {
    // 2^22 ticks with the largest minor total below the leading one: the
    // evaluation functions run through their whole range.
    const std::int64_t L = std::int64_t{1} << 22;
    for (Profile p : {Profile::eval8, Profile::grbl, Profile::marlin}) {
        Segment seg = default_segment(p, Point{L, -(L - 1), 1, -L, 0, L / 3}, 6);
        expect_exact_totals(p, seg, 6);
    }
}

// ------------------------------------------------------ chain-file coordinates

Errc read_error(InputFormat f, const std::string& text) {
    auto r = read_chains(f, text, "limits");
    return r.ok() ? Errc::ok : r.error().code;
}

TEST(HardeningLimits, ChainFileCoordinatesUpTo2To62) {
    const std::string max = std::to_string(k62), min = std::to_string(-k62);
    const std::string over = std::to_string(k62 + 1), under = std::to_string(-k62 - 1);
    EXPECT_EQ(read_error(InputFormat::freeman, max + " " + min + " 0\n"), Errc::ok);
    EXPECT_EQ(read_error(InputFormat::freeman, over + " 0 0\n"), Errc::overflow);
    EXPECT_EQ(read_error(InputFormat::freeman, "0 " + under + " 0\n"), Errc::overflow);
    EXPECT_EQ(read_error(InputFormat::freeman, "0 99999999999999999999999999 0\n"), Errc::overflow);
    EXPECT_EQ(read_error(InputFormat::points, max + " " + min + "\n"), Errc::ok);
    EXPECT_EQ(read_error(InputFormat::points, over + " 0\n"), Errc::overflow);
    EXPECT_EQ(read_error(InputFormat::points, "0 " + under + "\n"), Errc::overflow);
}

void expect_round_trip(InputFormat f, const std::string& text, const char* what) {
    for (Profile p : kAllProfiles) {
        CompressOptions opt;
        opt.profile = p;
        opt.format = f;
        opt.block_steps = 3;
        auto z = compress(text, opt);
        if (!z.ok()) {
            // Only a profile that cannot represent the chains may refuse.
            EXPECT_TRUE(z.error().code == Errc::connectivity ||
                        z.error().code == Errc::invalid_argument)
                << what << " " << profile_name(p) << ": " << z.error().message;
            continue;
        }
        auto back = decompress(*z);
        ASSERT_TRUE(back.ok()) << what << " " << profile_name(p) << ": " << back.error().message;
        EXPECT_EQ(*back, text) << what << " " << profile_name(p);
    }
}

// Every chain start the readers accept is coded: coordinates go up to
// +-2^62, so the jump from one chain to the next reaches 2^63 + steps (coded
// as a wrapping difference; tests/regressions/*/chain-start-beyond-2to40).
TEST(HardeningLimits, ChainsAtOppositeCoordinateExtremesRoundTrip) {
    // The jump between two chain starts is up to 2^63 + steps: more than an
    // int64 difference holds.
    const std::string max = std::to_string(k62), min = std::to_string(-k62);
    expect_round_trip(InputFormat::freeman, "0 2222444002222 12\n", "freeman start beyond 2^40");
    expect_round_trip(InputFormat::freeman, max + " " + max + " 0000\n" + min + " " + min + " 4444\n",
                      "freeman max then min");
    expect_round_trip(InputFormat::freeman, min + " " + max + " 2266\n" + max + " " + min + " 0011\n",
                      "freeman min then max");
    expect_round_trip(InputFormat::points,
                      max + " " + min + "\n" + std::to_string(k62 - 1) + " " + min + "\n\n" + min +
                          " " + max + "\n" + min + " " + std::to_string(k62 - 1) + "\n",
                      "points max then min");
}

// --------------------------------------------------- G-code and HP-GL coordinates

Errc vector_error(VectorFormat f, const std::string& text, const char* step = nullptr) {
    VectorReadOptions o;
    o.source = "limits";
    if (step) o.step_size = *parse_step_size(step);
    auto r = read_vectors(f, text, o);
    return r.ok() ? Errc::ok : r.error().code;
}

TEST(HardeningLimits, VectorCoordinatesUpTo2To30) {
    const std::string max = std::to_string(kMaxVectorCoord), over = std::to_string(kMaxVectorCoord + 1);
    const std::string min = std::to_string(-kMaxVectorCoord), under = std::to_string(-kMaxVectorCoord - 1);
    EXPECT_EQ(vector_error(VectorFormat::gcode, "G0 X" + min + " Y" + max + "\nG1 X" + max + "\n"), Errc::ok);
    EXPECT_EQ(vector_error(VectorFormat::gcode, "G1 X" + over + "\n"), Errc::limit);
    EXPECT_EQ(vector_error(VectorFormat::gcode, "G1 Y" + under + "\n"), Errc::limit);
    EXPECT_EQ(vector_error(VectorFormat::gcode, "G1 X999999999999999\n"), Errc::limit);
    // Relative moves that accumulate past the limit.
    EXPECT_EQ(vector_error(VectorFormat::gcode, "G91\nG1 X" + max + "\nG1 X1\n"), Errc::limit);
    EXPECT_EQ(vector_error(VectorFormat::gcode, "G91\nG1 X" + max + "\nG1 X-1\n"), Errc::ok);
    // A tiny step size turns a small number of millimetres into too many steps.
    EXPECT_EQ(vector_error(VectorFormat::gcode, "G1 X1\n", "0.000000000001"), Errc::limit);
    EXPECT_EQ(vector_error(VectorFormat::gcode, "G1 X0.001073741824\n", "0.000000000001"), Errc::ok);
    // Arc centres are coordinates too.
    EXPECT_EQ(vector_error(VectorFormat::gcode, "G2 X0 Y0 I" + over + " J0\n"), Errc::limit);
    EXPECT_EQ(vector_error(VectorFormat::hpgl, "IN;PU" + min + "," + max + ";PD" + max + "," + min + ";"), Errc::ok);
    EXPECT_EQ(vector_error(VectorFormat::hpgl, "IN;PD" + over + ",0;"), Errc::limit);
    EXPECT_EQ(vector_error(VectorFormat::hpgl, "IN;PR;PD" + max + ",0," + max + ",0;"), Errc::limit);
    EXPECT_EQ(vector_error(VectorFormat::hpgl, "IN;PD1,0;", "0.000000000001"), Errc::limit);
}

TEST(HardeningLimits, LineBetweenExtremeVectorCoordinatesIsRefusedBySegmentLimit) {
    // From -2^30 to 2^30 is 2^31 steps: more than one segment may hold.
    for (Profile p : kAllProfiles) {
        auto r = check_segment(p, default_segment(p, Point{2 * kMaxVectorCoord, 0}, 2), 2);
        ASSERT_FALSE(r.ok());
        EXPECT_EQ(r.error().code, Errc::limit);
    }
}

TEST(HardeningLimits, ArcAndCarrierLineCoordinatesUpTo2To24) {
    const std::int64_t m = kMaxInterpolateCoord;
    std::vector<Step> out;
    for (ArcMethod a : {ArcMethod::evaluation, ArcMethod::accelerated, ArcMethod::dda,
                        ArcMethod::prediction_correction, ArcMethod::double_recursion}) {
        out.clear();
        auto r = interpolate_arc(a, m + 1, 0, 0, m + 1, true, out);
        ASSERT_FALSE(r.ok());
        EXPECT_EQ(r.error().code, Errc::invalid_argument) << r.error().message;  // as documented
        EXPECT_TRUE(out.empty());
        r = interpolate_arc(a, std::numeric_limits<std::int64_t>::min(), 0, 0, 5, true, out);
        EXPECT_FALSE(r.ok());
    }
    for (LineMethod l : {LineMethod::dda, LineMethod::carrier}) {
        out.clear();
        auto r = interpolate_line(l, m + 1, 1, out);
        ASSERT_FALSE(r.ok());
        EXPECT_EQ(r.error().code, Errc::invalid_argument) << r.error().message;
        r = interpolate_line(l, std::numeric_limits<std::int64_t>::min(), 0, out);
        EXPECT_FALSE(r.ok());
    }
}

// ---------------------------------------------------------- decompression bombs

constexpr std::size_t kAllocationBound = std::size_t{kMaxBlockBytes} + (std::size_t{16} << 20);

std::string make_frame(const std::string& text, std::size_t block_steps) {
    CompressOptions opt;
    opt.profile = Profile::eval8;
    opt.allow_raw = false;
    opt.block_steps = block_steps;
    opt.window_log = 0;  // blocks independent: the decoder holds one block at a time
    auto z = compress(text, opt);
    EXPECT_TRUE(z.ok()) << (z.ok() ? "" : z.error().message);
    return z.ok() ? *z : std::string();
}

TEST(HardeningLimits, HostileSizeFieldsNeverDriveAnAllocationPastTheLimits) {
    // Any 4- or 8-byte window of a valid frame overwritten with huge values
    // (wherever the format keeps its sizes and counts) is rejected or decoded
    // without allocating more than the documented limits.
    const std::string frame = make_frame("0 0 000010000100001\n3 -2 2222322223\n", 8);
    ASSERT_FALSE(frame.empty());
    for (std::size_t width : {4u, 8u})
        for (char fill : {'\xFF', '\x7F', '\x80'})
            for (std::size_t i = 0; i + width <= frame.size(); ++i) {
                std::string bad = frame;
                std::fill_n(bad.begin() + static_cast<std::ptrdiff_t>(i), width, fill);
                g_largest_allocation = 0;
                auto r = decompress(bad);
                EXPECT_LE(g_largest_allocation.load(), kAllocationBound) << "window at " << i;
                if (!r.ok()) {
                    const Errc e = r.error().code;
                    EXPECT_TRUE(e == Errc::bad_magic || e == Errc::bad_version || e == Errc::corrupt ||
                                e == Errc::truncated || e == Errc::reserved_bits ||
                                e == Errc::checksum || e == Errc::limit)
                        << "window at " << i << ": " << r.error().message;
                }
            }
}

TEST(HardeningLimits, LargeFrameDecodesBlockByBlockInBoundedMemory) {
    // 2^20 steps in one chain (1 MiB of text) squeeze into a small frame;
    // decoding streams it with 2^13-step blocks: no buffer near the size of
    // the output is ever allocated.
    const std::size_t n = std::size_t{1} << 20;
    std::string text = "0 0 ";
    for (std::size_t i = 0; i < n; ++i) text += (i % 7 == 3) ? '1' : '0';
    text += '\n';
    const std::string frame = make_frame(text, std::size_t{1} << 13);
    ASSERT_FALSE(frame.empty());
    EXPECT_LT(frame.size(), text.size() / 100);
    std::size_t written = 0;
    const ReadFn in = stz::memory_reader(frame);
    WriteFn out = [&](std::string_view b) -> Result<void> {
        written += b.size();
        return {};
    };
    g_largest_allocation = 0;
    auto info = decompress_stream(in, out, "large");
    ASSERT_TRUE(info.ok()) << info.error().message;
    EXPECT_EQ(written, text.size());
    EXPECT_EQ(info->steps, n);
    EXPECT_LT(g_largest_allocation.load(), text.size() / 4);
}

}  // namespace
}  // namespace stepzip
