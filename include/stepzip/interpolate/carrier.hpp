// stepzip — evaluation function on a constant carrier frequency, linear
// (seed 004 §6.2.2.3). Thread-safe (no shared state).
#pragma once

#include <cstdint>
#include <vector>

#include "stepzip/error.hpp"
#include "stepzip/step.hpp"

namespace stepzip {

/// One carrier period of carrier_linear.
struct CarrierPeriod {
    int dx = 0;           ///< Δx_i, 0 or ±1
    int dy = 0;           ///< Δy_i, 0 or ±1
    std::int64_t n = 0;   ///< N_i = n·Σ|Δx| − i·|X|, the accumulated x error (scaled by n)
    std::int64_t m = 0;   ///< M_i = n·Σ|Δy| − i·|Y|, the accumulated y error
    friend bool operator==(const CarrierPeriod&, const CarrierPeriod&) = default;
};

/// Line from the origin to (dx, dy) over `periods` carrier periods (the
/// frame time τ divided by the period T; periods <= 0 picks max(|dx|, |dy|),
/// one unit per period on the leading axis). The average per-period
/// increments are |X|/n and |Y|/n; the accumulated error functions, scaled by
/// n to stay integral, are N_i = n·Σ_{k<=i}|Δx_k| − i·|X| and likewise M_i.
/// Each period takes the integer part of the average increment and, when the
/// error function would be negative, adds one discrete (seed 004: "якщо
/// значення оцінної функції від'ємне, то скоригувати ... додавши одну
/// дискрету"). So Σ|Δx| = ceil(i·|X|/n), 0 <= N_i < n, the path lies on or
/// above the line, and after n periods N_n = M_n = 0: it ends exactly.
/// Periods with no move produce no step (they remain in `trace`). Steps are
/// 8-connected.
/// Complexity: O(n). Errors: Errc::invalid_argument when |dx| or |dy|
/// exceeds kMaxInterpolateCoord (arc.hpp) or when 0 < periods <
/// max(|dx|, |dy|) (a period would need more than one unit per axis) or
/// periods > 2^40. Nothing is appended on error.
Result<void> carrier_linear(std::int64_t dx, std::int64_t dy, std::int64_t periods,
                            std::vector<Step>& out, std::vector<CarrierPeriod>* trace = nullptr);

}  // namespace stepzip
