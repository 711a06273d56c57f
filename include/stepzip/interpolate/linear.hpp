// stepzip — linear forward interpolators of the source documents.
//
// All functions are thread-safe (no shared state) and append to `out`.
// An optional `trace` receives the evaluation function after every step, the
// form in which the seeds tabulate their worked examples.
#pragma once

#include <cstdint>
#include <vector>

#include "stepzip/step.hpp"

namespace stepzip {

/// Evaluation-function linear interpolation, 4-connected (seed 000, seed 004
/// §6.2.2.1). Quadrant-normalized with A = |dx|, B = |dy| and F = f0:
/// F >= 0: x-step, F -= B; F < 0: y-step, F += A; signs mirrored per quadrant.
/// Counters KOX, KOY end the run after A x-steps and B y-steps; a counter at
/// zero disables its axis (a "forced" step, counted in *forced when given).
/// For f0 in [-B, A) no step is ever forced and -B <= F < A holds throughout.
/// Complexity: O(A + B).
void eval_linear(std::int64_t dx, std::int64_t dy, std::int64_t f0, std::vector<Step>& out,
                 std::vector<std::int64_t>* trace = nullptr, std::int64_t* forced = nullptr);

/// Accelerated (leading-axis) linear interpolation, 8-connected (seed 000
/// "accelerated", seed 002, seed 004 §6.2.2.2). L = the larger |total|, S the
/// smaller; every tick steps the leading axis; F >= 0: leading only, F -= S;
/// F < 0: diagonal, F += L - S. L == S is a pure diagonal and S == 0 a pure
/// run (product decision). Ties |dx| == |dy| are diagonal, so the leading
/// axis is x when |dx| >= |dy|. Ends exactly for f0 in [-S, L - S).
/// Complexity: O(L).
void accelerated_linear(std::int64_t dx, std::int64_t dy, std::int64_t f0, std::vector<Step>& out,
                        std::vector<std::int64_t>* trace = nullptr);

/// Variants of the multi-axis interpolator.
enum class MultiAxisVariant {
    /// The accelerated rule on every minor axis against the leading axis.
    standard,
    /// Seed 002: "to avoid a one-step error, issue the first step on all
    /// axes", then follow the same rule (F0 = 0 + (L - S) after the first
    /// tick). Every axis with a non-zero total moves on tick 1. A distinct
    /// pattern, not a phase of `standard`; exact for every L > S.
    first_step_all_axes,
};

/// Multi-axis leading-axis linear interpolation (seed 002, up to kMaxAxes
/// axes): α = leading axis (lowest index among the largest |totals|), one
/// evaluation function per minor axis, phases[j] for the j-th minor axis in
/// increasing axis order. Ends exactly when every phase lies in [-S, L - S).
/// Complexity: O(L * axes).
void multiaxis_linear(const Point& delta, int axes, const std::int64_t* phases,
                      std::vector<Step>& out,
                      MultiAxisVariant variant = MultiAxisVariant::standard);

/// SU 1089551 forward mode (Fig. 4): reversible counters hold the remaining
/// X = |dx| and Y = |dy|, the adder starts at f00 (the patent: F00 = Y - X).
/// F < 0: x-step, X -= 1, F += Y; F >= 0: y-step, Y -= 1, F -= X. Stops when
/// both counters are zero; a counter at zero disables its axis (never needed
/// for F00 = Y - X: checked by the tests). Signs mirrored per quadrant.
/// Complexity: O(X + Y).
void patent_forward(std::int64_t dx, std::int64_t dy, std::int64_t f00, std::vector<Step>& out,
                    std::vector<std::int64_t>* trace = nullptr);

}  // namespace stepzip
