// stepzip — steps: one tick's unit increment on up to six axes.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

namespace stepzip {

/// Largest number of axes a chain may have.
inline constexpr int kMaxAxes = 6;

/// A point or a per-axis vector with up to kMaxAxes integer coordinates;
/// coordinates past a chain's axis count are zero.
using Point = std::array<std::int64_t, kMaxAxes>;

/// One step, packed as in the STEP/DIR log format: bit 2i set = axis i moved,
/// bit 2i+1 set = axis i moved in the negative direction. A valid step moves
/// at least one axis and sets no direction bit on an axis that does not move.
using Step = std::uint16_t;

/// The move of `axis` (-1, 0 or +1) in step `s`.
constexpr int step_axis(Step s, int axis) noexcept {
    const unsigned bits = (s >> (2 * axis)) & 3u;
    return bits == 1u ? 1 : bits == 3u ? -1 : 0;
}

/// The step moving each axis i by d[i] (each -1, 0 or +1), over `axes` axes.
constexpr Step make_step(const int* d, int axes) noexcept {
    Step s = 0;
    for (int i = 0; i < axes; ++i) {
        if (d[i] > 0) s = static_cast<Step>(s | (1u << (2 * i)));
        if (d[i] < 0) s = static_cast<Step>(s | (3u << (2 * i)));
    }
    return s;
}

/// The two-axis step (dx, dy).
constexpr Step make_step2(int dx, int dy) noexcept {
    const int d[2] = {dx, dy};
    return make_step(d, 2);
}

/// True when `s` is a valid step on `axes` axes: it moves at least one axis,
/// touches no axis >= axes and sets no direction bit on a resting axis.
constexpr bool step_valid(Step s, int axes) noexcept {
    if (s == 0) return false;
    if (axes < kMaxAxes && (s >> (2 * axes)) != 0) return false;
    for (int i = 0; i < axes; ++i)
        if (((s >> (2 * i)) & 3u) == 2u) return false;
    return true;
}

/// Number of axes that move in step `s`.
constexpr int step_weight(Step s) noexcept {
    int n = 0;
    for (int i = 0; i < kMaxAxes; ++i) n += (s >> (2 * i)) & 1u;
    return n;
}

/// True when exactly one axis moves in step `s` (step_weight(s) == 1,
/// without a population count, which baseline x86-64 makes a call).
constexpr bool step_moves_one_axis(Step s) noexcept {
    const unsigned moving = s & 0x555u;
    return moving != 0 && (moving & (moving - 1)) == 0;
}

/// Adds step `s` to point `p` over `axes` axes.
constexpr void apply_step(Point& p, Step s, int axes) noexcept {
    for (int i = 0; i < axes; ++i) p[i] += step_axis(s, i);
}

/// Freeman-8 code (0..7) to a two-axis step:
/// 0:+x 1:+x+y 2:+y 3:-x+y 4:-x 5:-x-y 6:-y 7:+x-y.
constexpr Step freeman_to_step(int code) noexcept {
    constexpr Step table[8] = {0x01, 0x05, 0x04, 0x07, 0x03, 0x0F, 0x0C, 0x0D};
    return table[code & 7];
}

/// Two-axis step to its Freeman-8 code, or -1 when `s` is not a valid
/// two-axis step.
constexpr int step_to_freeman(Step s) noexcept {
    switch (s) {
        case 0x01: return 0;
        case 0x05: return 1;
        case 0x04: return 2;
        case 0x07: return 3;
        case 0x03: return 4;
        case 0x0F: return 5;
        case 0x0C: return 6;
        case 0x0D: return 7;
        default: return -1;
    }
}

}  // namespace stepzip
