// stepzip — what a timed STEP/DIR log tells about the controller that made it.
#pragma once

#include <cstdint>
#include <vector>

#include "stepzip/chain.hpp"

namespace stepzip {

/// Motion of one axis of a timed chain, in steps and seconds.
struct AxisMotion {
    std::uint64_t steps = 0;    ///< steps of the axis in the chain
    double max_rate = 0;        ///< fastest step rate held over a window of moves (steps/s)
    double acceleration = 0;    ///< acceleration of the ramps (steps/s^2), see estimate_axis_motion
    std::uint64_t windows = 0;  ///< windows of moves the acceleration was read from
};

/// Reads, for each axis 1.. of a chain read with InputFormat::timed (axis 0
/// is time, one step per tick of `tick_seconds`), the step rate and the
/// acceleration of the ramps. Each window of 128 consecutive moves of an
/// axis in one direction, without a pause (no gap over three times the
/// window's mean), is fitted with a parabola in time by least squares; a
/// window whose fit is within 0.6 steps (RMS) gives its curvature as an
/// acceleration sample. `max_rate` is the fastest window; `acceleration`
/// is the 90th percentile of the samples (a controller ramps at its limit
/// along the axis that leads a move; cruise and junction windows give
/// smaller values). Result index i is axis i; index 0 (time) is empty.
/// Thread-safe. Complexity: O(steps).
std::vector<AxisMotion> estimate_axis_motion(const Chain& timed_chain, double tick_seconds);

}  // namespace stepzip
