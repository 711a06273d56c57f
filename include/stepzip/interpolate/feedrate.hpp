// stepzip — the feed-rate block (seed 000 "БЛОК ЗА ЗАДАВАНЕ НА СКОРОСТТА",
// seed 002 "необходимая частота выдачи"): time stamps for the steps of an
// interpolator at a feed rate V, and the synchronization buffer that lets
// the interpolator run ahead of the drive clock. Thread-safe (pure functions).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "stepzip/error.hpp"
#include "stepzip/interpolate/dda.hpp"
#include "stepzip/step.hpp"

namespace stepzip {

/// How a multi-axis step stretches the next interval.
enum class AxisFactor : std::uint8_t {
    seed,   ///< seed 000's constants: 1, 1.41, 1.73, then √k to two decimals
    exact,  ///< √k
};

/// The factor for a step moving `axes` axes (1..kMaxAxes): 1 for one axis,
/// 1.41 / 1.73 (seed) or √2 / √3 (exact) for two / three. Thread-safe.
double axis_factor(int axes, AxisFactor mode = AxisFactor::seed) noexcept;

/// Time stamps (seconds, from the start) of the steps of a pulse
/// interpolator (evaluation function, accelerated, multi-axis) at feed rate
/// `v` in steps per second: base period Δt = 1/v; the first step at Δt; after
/// a step moving k axes the next interval is Δt·axis_factor(k), so the path
/// speed stays about v (seed 000: "ако са изведени импулси по две оси
/// следващият интервал трябва да бъде 1,41 пъти по-дълъг").
/// Errors: Errc::invalid_argument when v is not a positive finite number or
/// a step is not valid on `axes` axes (message names the step index).
Result<std::vector<double>> feed_times(const std::vector<Step>& steps, int axes, double v,
                                       AxisFactor mode = AxisFactor::seed);

/// The DDA clock period (seed 000): a DDA always runs 2^p cycles, so for a
/// line (ΔX, ΔY) at path speed v the period is
/// Δt = T / 2^p = √(ΔX² + ΔY²) / (v·2^p). Returns 0 for v <= 0 (no speed).
double dda_period(std::int64_t dx, std::int64_t dy, double v, int p) noexcept;

/// Time stamps of the steps of a DDA run: the step issued at cycle c is at
/// c·period.
std::vector<double> dda_times(const DdaTrace& trace, double period);

/// Outcome of simulate_sync_buffer.
struct SyncResult {
    std::vector<double> issued;     ///< when each step reached the drive
    std::vector<double> computed;   ///< when the interpolator finished each step
    double interpolator_stall = 0;  ///< total time the full buffer stopped the interpolator
    std::size_t underruns = 0;      ///< drive ticks that found the buffer empty
    std::size_t max_fill = 0;       ///< most steps waiting at once
};

/// The synchronization buffer (seed 000 "схема за синхронизация"): the
/// interpolator computes each step in `compute_time` seconds at its own
/// speed and stores it in a buffer of `capacity` steps; when the buffer is
/// full it stops ("СТОП") until the drive takes a step. The drive issues step
/// i one interval after step i−1 (intervals from `drive_times`, the ideal
/// stamps of feed_times or dda_times; the first at drive_times[0]), or as
/// soon as the step is computed when it was late (an underrun, which delays
/// every later step). Model: start_i = max(computed_{i−1},
/// issued_{i−capacity}), computed_i = start_i + compute_time,
/// issued_i = max(issued_{i−1} + interval_i, computed_i).
/// Invariant: at most `capacity` steps wait at any time. Complexity: O(n).
/// Errors: Errc::invalid_argument for capacity 0, a negative or non-finite
/// compute_time, or decreasing drive_times.
Result<SyncResult> simulate_sync_buffer(const std::vector<double>& drive_times,
                                        double compute_time, std::size_t capacity);

}  // namespace stepzip
