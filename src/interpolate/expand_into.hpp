// Internal: forward interpolation of one segment into a caller's buffer, for
// the decoders' hot paths (no vector growth per segment). The two-axis fast
// paths are inline here (the table decoder's two-axis loop calls them
// directly); the interpolators of src/interpolate/linear.cpp use the same
// code. Not installed.
#pragma once

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

inline void emit_two_letter(std::int64_t n, std::int64_t s, std::int64_t f0, Step plain, Step other, Step* o) {
    if (n <= 16) {  // short runs: the rule a tick at a time costs less than the divisions
        std::int64_t f = f0;
        for (std::int64_t t = 0; t < n; ++t) {
            const bool p = f >= 0;
            o[t] = p ? plain : other;
            f += p ? -s : n - s;
        }
        return;
    }
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
