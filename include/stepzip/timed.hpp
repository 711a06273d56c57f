// stepzip — what a timed STEP/DIR log tells about the controller that made it.
#pragma once

#include <cstdint>
#include <span>
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

/// The path of a timed chain: its ticks that move an axis, with time
/// dropped (a chain on axes 1.., starting at the timed chain's start on
/// those axes), and the tick (index in the timed chain) of each of its steps.
struct TimedPath {
    Chain path;
    std::vector<std::uint64_t> ticks;  ///< ticks[k]: the tick of path.steps[k]
};
/// Thread-safe. Complexity: O(ticks).
TimedPath timed_path(const Chain& timed_chain);

/// Speeds of one straight move read out of the ticks of its steps, along
/// the move's path: `length` is its Euclidean length in steps, and the
/// path position after the k-th of the n steps of its leading axis is
/// (k + 1) · length / n. Speeds in steps/s along the path, acceleration in
/// steps/s^2.
struct MoveSpeeds {
    double entry = 0;         ///< speed where the move starts
    double cruise = 0;        ///< speed held between the ramps (see move_speeds())
    double exit = 0;          ///< speed where the move ends
    double acceleration = 0;  ///< of the ramps (0 when neither ramp has 6 steps)
    std::uint64_t ramp_steps = 0;  ///< leading-axis steps the acceleration was fitted on
};

/// Reads a move's speeds from `lead_ticks`, the ticks of the steps of its
/// leading axis (strictly increasing), `length` (> 0) and the tick length.
/// The local speed at step k is taken over a window of w steps on either
/// side (w = n / 16, clamped to 2..16). The cruise speed is the mean speed
/// from the first to the last step whose local speed reaches 97 % of the
/// 90th percentile of the local speeds, when that plateau spans more than
/// 4w steps, else the largest local speed (a peak); when the entry and
/// exit speeds (below) are both 85 % of that or more, the mean speed over
/// the whole move instead, and the move has no ramps (acceleration and
/// ramp_steps 0: the ramps found then are stepper segments a few per cent
/// apart). The ramp up runs from the first step to the
/// first whose local speed reaches 97 % of the largest, the ramp down from
/// the last such step to the end. A ramp of
/// at least 6 steps is fitted with a parabola in time by least squares
/// (step times at the middle of their tick); its curvature is its
/// acceleration and the entry (exit) speed is the parabola's speed where it
/// passes position 0 (length), or 0 where it does not reach it (a start
/// from rest). Without a ramp the entry (exit) speed is the local speed of
/// the first (last) step. `acceleration` is the mean of the ramps' values,
/// weighted by their steps. Fewer than 2 steps: every speed 0.
/// Thread-safe. Complexity: O(n).
MoveSpeeds move_speeds(std::span<const std::uint64_t> lead_ticks, double length, double tick_seconds);

/// One straight move of a timed chain's path.
struct TimedMove {
    std::size_t first = 0, last = 0;  ///< its steps: path.steps[first .. last] (TimedPath)
    std::uint64_t first_tick = 0, last_tick = 0;  ///< ticks of its first and last step
    Point delta{};                    ///< where it goes, on the path's axes
    double length = 0;                ///< Euclidean, in steps
    MoveSpeeds speeds;                ///< move_speeds() on the ticks of its leading axis
};

/// How far (in steps) the path of a timed_moves() move may stray from the
/// line between its ends by default.
inline constexpr double kTimedMoveTolerance = 1.5;

/// The moves of a timed chain: its path (timed_path()) cut into straight
/// stretches that stay within `tolerance` steps of the line between their
/// end points, each with its speeds. A controller's multi-axis smoothing
/// lets the steps of a straight move wander from the exact digital line by
/// a step or more, so exact segments would cut its moves apart: the path is
/// cut by Douglas-Peucker, then each corner is moved (up to 10 points along
/// the path) to where the squared distances of the points of its two
/// stretches from their lines add up to the least, and corners whose
/// neighbours' line keeps the points between within `tolerance` are
/// dropped, until nothing changes (at most 12 rounds); then neighbouring
/// corners are moved in pairs (up to 2 points each) where their three
/// stretches fit better and stay within `tolerance`, until nothing
/// changes. On generated logs with known moves this finds 90-100 % of the
/// move ends exactly, on a Grbl 1.1h log 93 % (docs/benchmarks.md "Timed
/// streams: neighbouring corners moved together"); collinear moves that
/// follow each other become one. Thread-safe.
/// Complexity: O(n log n) typical for the cut, O(n^2) worst; O(n) a round
/// for each point of a corner's reach, and for each pair of places of two
/// neighbouring corners.
std::vector<TimedMove> timed_moves(const TimedPath& path, double tick_seconds,
                                   double tolerance = kTimedMoveTolerance);

/// All that a timed chain is read for, as `stepzip segment --format timed`
/// reports it: its path, its moves (timed_moves()) and what each axis of
/// the path says (estimate_axis_motion(), without the time axis).
struct TimedReading {
    TimedPath path;
    std::vector<TimedMove> moves;
    std::vector<AxisMotion> axes;  ///< axes[i]: axis i of the path (axis i + 1 of the timed chain)
};
/// Thread-safe. Complexity: as timed_moves().
TimedReading read_timed(const Chain& timed_chain, double tick_seconds, double tolerance = kTimedMoveTolerance);

}  // namespace stepzip
