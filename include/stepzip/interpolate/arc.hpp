// stepzip — uniform entry points for the forward arc and line interpolators
// that the G-code reader (G1/G2/G3) and the CLI call by method name.
//
// Each method lives in its own header (circular.hpp, dda.hpp, carrier.hpp,
// prediction.hpp, recursion.hpp); these functions only dispatch and put the
// common argument checks and end-point guarantee in one place.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "stepzip/error.hpp"
#include "stepzip/step.hpp"

namespace stepzip {

/// Largest |coordinate| accepted by interpolate_arc and interpolate_line:
/// 2^24. It keeps x^2 + y^2 - R^2 and every register product well inside
/// int64 and the step count of one call below ~10^9.
inline constexpr std::int64_t kMaxInterpolateCoord = std::int64_t{1} << 24;

/// Forward circular interpolation methods (SPEC §2.4).
enum class ArcMethod : std::uint8_t {
    evaluation,             ///< evaluation function, 4-connected (seed 000)
    accelerated,            ///< evaluation function by octants, diagonal steps (seed 000)
    dda,                    ///< digital differential analyzer (seed 004 §6.2)
    prediction_correction,  ///< tangent step, then correction toward the centre (seed 004)
    double_recursion,       ///< x[k+2] = 2a·x[k+1] − x[k] (seed 002)
};

/// The short name of a method: "evaluation", "accelerated", "dda",
/// "prediction", "recursion". Thread-safe.
std::string_view arc_method_name(ArcMethod method) noexcept;

/// The method with that short name (see arc_method_name), or nullopt.
/// Thread-safe.
std::optional<ArcMethod> parse_arc_method(std::string_view name) noexcept;

/// Steps of a circular arc about the origin from (x0, y0) to (x1, y1)
/// (integer points relative to the centre; R = |start|, counter-clockwise
/// when `ccw`). end == start means a full circle. Appends unit steps to `out`
/// (4-connected for evaluation and prediction_correction; 8-connected for
/// accelerated, dda and double_recursion).
///
/// The arc is cut at the coordinate axes into quadrant pieces; each piece
/// ends on the axis at distance round(R) (or on the end point), counted by
/// the seeds' end counters KOX, KOY. The path ends exactly on (x1, y1): when
/// the method cannot reach a piece's target by its own rule (|end| differs
/// from R by rounding), a final straight correction run (eval_linear for
/// 4-connected methods, accelerated_linear otherwise) closes the gap. An end
/// on the start's ray at another radius counts as a full circle.
///
/// Errors: Errc::invalid_argument when R == 0 or a coordinate's magnitude
/// exceeds kMaxInterpolateCoord, or when end == (0, 0), or when |end| and R
/// differ by more than max(2, R/8) (the end cannot lie on that arc). On
/// error `out` is unchanged.
/// Thread-safe (no shared state). Does not promise a particular step
/// sequence across versions for methods other than evaluation and
/// accelerated, whose sequences follow seed 000 exactly.
Result<void> interpolate_arc(ArcMethod method, std::int64_t x0, std::int64_t y0,
                             std::int64_t x1, std::int64_t y1, bool ccw,
                             std::vector<Step>& out);

/// Forward linear methods beyond those in linear.hpp.
enum class LineMethod : std::uint8_t {
    dda,      ///< digital differential analyzer on a constant carrier (seed 004)
    carrier,  ///< evaluation function on a constant carrier frequency (seed 004)
};

/// The short name: "dda" or "carrier". Thread-safe.
std::string_view line_method_name(LineMethod method) noexcept;

/// The method with that short name, or nullopt. Thread-safe.
std::optional<LineMethod> parse_line_method(std::string_view name) noexcept;

/// Steps of a line from the origin to (dx, dy) by DDA or the constant-carrier
/// evaluation function; ends exactly on (dx, dy). Steps may be diagonal (both
/// axes move in one carrier period). (0, 0) appends nothing.
/// Errors: Errc::invalid_argument when |dx| or |dy| exceeds
/// kMaxInterpolateCoord; `out` is then unchanged. Thread-safe.
Result<void> interpolate_line(LineMethod method, std::int64_t dx, std::int64_t dy,
                              std::vector<Step>& out);

}  // namespace stepzip
