// Internal: forward interpolation of one segment into a caller's buffer, for
// the decoders' hot paths (no vector growth per segment). The two-axis fast
// paths are inline here (the table decoder's two-axis loop calls them
// directly); the interpolators of src/interpolate/linear.cpp use the same
// code. Not installed.
#pragma once

#include <array>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <utility>

#include "stepzip/profile.hpp"
#include "stepzip/segment.hpp"
#include "stepzip/step.hpp"

namespace stepzip::detail {

// o[0, n) = v, four steps a store.
inline void fill_steps(Step* o, std::int64_t n, Step v) {
    const std::uint64_t four = std::uint64_t{v} * 0x0001000100010001ull;
    if (n < 4) {
        for (std::int64_t t = 0; t < n; ++t) o[t] = v;
        return;
    }
    for (std::int64_t t = 0; t + 4 <= n; t += 4) std::memcpy(o + t, &four, sizeof four);
    std::memcpy(o + n - 4, &four, sizeof four);  // the last 1-3 steps (overlapping)
}

// Fast path shared by the two-letter rules below (not normative: it emits
// exactly what the per-step loops emit, tests/container_fast_paths_test.cpp
// compares them over whole ranges). Rule: n ticks, f = f0; f >= 0: letter
// `plain`, f -= s; else letter `other`, f += n - s. For f0 in [-s, n - s)
// the invariant -s <= f < n - s holds, so after t ticks the count of
// `other` letters is ceil((t·s - f0 - s) / n), and the j-th one (j >= 1)
// falls on tick floor(((j - 1)·n + f0 + s) / s) + 1: one division per run,
// the next tick by adding the quotient and remainder of n / s.
// Calls at(t) for the 0-based tick t of each `other` letter, in order.
template <class At>
inline void other_ticks(std::int64_t n, std::int64_t s, std::int64_t f0, At at) {
    const std::int64_t num = f0 + s;  // >= 0: f0 >= -s
    std::int64_t t = num / s, rem = num % s;
    const std::int64_t q = n / s, r = n % s;
    for (std::int64_t j = 0; j < s; ++j) {
        at(t);
        t += q;
        rem += r;
        if (rem >= s) {
            rem -= s;
            ++t;
        }
    }
}

// Short runs (n <= 16), where the divisions cost more than the run: the
// ticks of the `other` letters as a mask (bit t: tick t) for every n, s in
// [1, n) and f0 in [-s, n - s), made at compile time by the rule itself.
inline constexpr int kShortRun = 16;
struct ShortRunMasks {
    std::uint16_t at[kShortRun + 1][kShortRun][kShortRun];  // [n][s][f0 + s]
};
inline constexpr ShortRunMasks kShortRunMasks = [] {
    ShortRunMasks m{};
    for (int n = 2; n <= kShortRun; ++n)
        for (int s = 1; s < n; ++s)
            for (int f0 = -s; f0 < n - s; ++f0) {
                unsigned bits = 0;
                for (int t = 0, f = f0; t < n; ++t) {
                    if (f >= 0) {
                        f -= s;
                    } else {
                        bits |= 1u << t;
                        f += n - s;
                    }
                }
                m.at[n][s][f0 + s] = static_cast<std::uint16_t>(bits);
            }
    return m;
}();
// Four steps (16-bit lanes) from four bits of a mask: lane k all ones where
// bit k is set.
inline constexpr auto kLanesOfBits = [] {
    std::array<std::uint64_t, 16> l{};
    for (unsigned b = 0; b < 16; ++b)
        for (unsigned k = 0; k < 4; ++k)
            if ((b >> k) & 1) l[b] |= std::uint64_t{0xFFFF} << (16 * k);
    return l;
}();

// The runs above kShortRun: the letter of the fewer ticks written over a
// fill with the other, one division per run (out of line: its callers
// inline the short runs).
[[gnu::noinline]] inline void emit_long_two_letter(std::int64_t n, std::int64_t s, std::int64_t f0, Step plain,
                                                   Step other, Step* o) {
    if (2 * s > n) {
        // Mostly `other`: the same rule with the letters' roles swapped
        // (g = -f - 1 follows it with s' = n - s from g0 = -f0 - 1, in its
        // exact range), so the loop runs over the fewer letters.
        std::swap(plain, other);
        s = n - s;
        f0 = -f0 - 1;
    }
    fill_steps(o, n, plain);
    other_ticks(n, s, f0, [&](std::int64_t t) { o[t] = other; });
}

[[gnu::always_inline]] inline void emit_two_letter(std::int64_t n, std::int64_t s, std::int64_t f0, Step plain,
                                                   Step other, Step* o) {
    if (n <= kShortRun) {
        // Four steps a store: `plain` in every lane, flipped to `other` in
        // the lanes of the mask (the last 1-3 steps by an overlapping store).
        const unsigned m = kShortRunMasks.at[n][s][f0 + s];
        const std::uint64_t p4 = std::uint64_t{plain} * 0x0001000100010001ull;
        const std::uint64_t d4 = std::uint64_t{static_cast<Step>(plain ^ other)} * 0x0001000100010001ull;
        if (n < 4) {
            for (std::int64_t t = 0; t < n; ++t) o[t] = ((m >> t) & 1) ? other : plain;
            return;
        }
        auto four = [&](std::int64_t t) {
            const std::uint64_t v = p4 ^ (kLanesOfBits[(m >> t) & 15] & d4);
            std::memcpy(o + t, &v, sizeof v);
        };
        std::int64_t t = 0;
        for (; t + 4 <= n; t += 4) four(t);
        if (t < n) four(n - 4);
        return;
    }
    emit_long_two_letter(n, s, f0, plain, other, o);
}
// The fast path of the leading-axis profiles (eval8, grbl, marlin) on two
// axes into o[0, L): false, and nothing written, when the phase `f0` is
// outside its exact range and the run is not degenerate.
[[gnu::always_inline]] inline bool leading_two_axis_into(const Point& delta, std::int64_t f0, Step* o) {
    const std::int64_t ax = std::llabs(delta[0]), ay = std::llabs(delta[1]);
    const bool x_leads = ax >= ay;  // the lowest index among the largest
    const std::int64_t l = x_leads ? ax : ay, s = x_leads ? ay : ax;
    const auto sx = static_cast<Step>(delta[0] > 0 ? 1u : delta[0] < 0 ? 3u : 0u);
    const auto sy = static_cast<Step>(delta[1] > 0 ? 4u : delta[1] < 0 ? 12u : 0u);
    const Step straight = x_leads ? sx : sy, diagonal = static_cast<Step>(sx | sy);
    if (s == 0 || s == l) {
        fill_steps(o, l, s == 0 ? straight : diagonal);
        return true;
    }
    if (f0 < -s || f0 >= l - s) return false;
    emit_two_letter(l, s, f0, straight, diagonal, o);
    return true;
}

/// expand_segment_into on two axes.
[[gnu::always_inline]] inline bool expand_two_axis_into(Profile p, const Segment& seg, Step* out) {
    switch (p) {
        case Profile::eval4: {
            const std::int64_t a = std::llabs(seg.delta[0]), b = std::llabs(seg.delta[1]), f0 = seg.phase[0];
            const auto sx = static_cast<Step>(seg.delta[0] > 0 ? 1u : 3u), sy = static_cast<Step>(seg.delta[1] > 0 ? 4u : 12u);
            if (a == 0 || b == 0) {  // one axis: every step on it (eval_linear forces them)
                fill_steps(out, a + b, a == 0 ? sy : sx);
                return true;
            }
            if (f0 < -b || f0 >= a) return false;
            emit_two_letter(a + b, b, f0, sx, sy, out);
            return true;
        }
        case Profile::eval8:
        case Profile::grbl:
        case Profile::marlin:
            return leading_two_axis_into(seg.delta, seg.phase[0], out);
        case Profile::patent:
            return false;
    }
    return false;
}

/// Writes the steps of `seg` to out[0, segment_length) where a fast path of
/// the profile's interpolator applies (exactly what expand_segment appends,
/// tests/container_fast_paths_test.cpp compares them); false, and nothing
/// written, otherwise (the caller falls back to expand_segment).
/// Precondition: check_segment(p, seg, axes) succeeds and `out` holds
/// segment_length(seg.delta, axes, profile_eight_connected(p)) steps.
bool expand_segment_into(Profile p, const Segment& seg, int axes, Step* out);

}  // namespace stepzip::detail
