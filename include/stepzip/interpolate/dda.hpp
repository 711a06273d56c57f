// stepzip — digital differential analyzer (DDA) on a constant carrier
// frequency, linear and circular (seed 004 §6.2.2.4, seed 000 "БЛОК ЗА
// ЗАДАВАНЕ НА СКОРОСТТА": N_cycles = 2^p).
//
// A DDA runs a fixed clock (the carrier). Each cycle adds a rate to a p-bit
// accumulator per axis; a carry out of the register (the accumulator reaching
// 2^p) is one unit step on that axis and the remainder (the fractional part,
// in units of 2^-p) stays. Cycles without a carry produce no step; the trace
// keeps the cycle number of every step so the feed-rate block (feedrate.hpp)
// can time them. Steps are 8-connected (both registers may carry in one
// cycle). Thread-safe (no shared state).
#pragma once

#include <cstdint>
#include <vector>

#include "stepzip/error.hpp"
#include "stepzip/interpolate/circular.hpp"
#include "stepzip/step.hpp"

namespace stepzip {

/// Register width and cycle numbers of a DDA run.
struct DdaTrace {
    int p = 0;                               ///< register width in bits (capacity 2^p)
    std::uint64_t cycles = 0;                ///< carrier cycles run
    std::vector<std::uint64_t> step_cycle;   ///< 1-based cycle of each output step
    std::vector<ArcTracePoint> points;       ///< circular only: point and F after each step
};

/// Largest register width accepted by dda_linear (2^40 cycles is already
/// far beyond any practical run).
inline constexpr int kMaxDdaBits = 40;

/// Linear DDA from the origin to (dx, dy): 2^p cycles, each adds |dx| and
/// |dy| to registers that start at 0; a carry (register >= 2^p, then −2^p)
/// steps that axis in the sign of its total. After 2^p cycles each register
/// has carried exactly |d| times and is back at 0, so the run ends exactly on
/// (dx, dy) for any p with 2^p >= max(|dx|, |dy|) (one carry per cycle at
/// most). p <= 0 picks the smallest such p (the seed's "обем на суматора").
/// The path lies on or below the line (the axis count after cycle i is
/// floor(i·|d| / 2^p)), as seed 004 states.
/// Complexity: O(2^p) cycles. Errors: Errc::invalid_argument when |dx| or
/// |dy| exceeds kMaxInterpolateCoord (arc.hpp) or 2^p < max(|dx|, |dy|) or
/// p > kMaxDdaBits. Nothing is appended on error.
Result<void> dda_linear(std::int64_t dx, std::int64_t dy, int p, std::vector<Step>& out,
                        DdaTrace* trace = nullptr);

/// Circular DDA about the origin (seed 004 Fig. 6.28: the x register sums
/// the current |y|, the y register sums the current |x|; Euler integration of
/// dx/dt = −y·ω, dy/dt = x·ω with ω = 2^-p radian per cycle). p is the
/// smallest width with 2^p >= round(R) + 2, so a register carries at most
/// once per cycle. The y register adds |x| after the cycle's x move
/// (Euler–Cromer: seed 004 warns that the error must not enter twice; with
/// the plain Euler update the orbit spirals outward). Each quadrant piece is
/// a new frame: the registers restart at 2^(p−1) (half a step: rounding
/// instead of truncation). A carry on an axis whose end counter is zero is
/// discarded, as in hardware. A piece that stalls (every axis left to move
/// has rate 0) or overruns 8·2^p cycles ends with the correction run of
/// interpolate_arc.
/// Invariant: points stay within 1.5 steps of the circle (checked, R <= 100;
/// measured worst 1.31 for R <= 30). The DDA has no feedback from F: it
/// integrates the orbit through its current point, which after the first
/// quadrant is the axis point at round(R), and lags its registers by up to
/// one step — the looser band is the method's, as seed 004 notes.
/// Complexity: O(R) cycles per quadrant. Errors: as interpolate_arc.
Result<void> dda_circular(std::int64_t x0, std::int64_t y0, std::int64_t x1, std::int64_t y1,
                          bool ccw, std::vector<Step>& out, DdaTrace* trace = nullptr);

}  // namespace stepzip
