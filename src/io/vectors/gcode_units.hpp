// stepzip — exact decimal numbers and unit conversion shared by the G-code
// and HP-GL readers and writers (internal header).
//
// Numbers are read exactly as integers of 10^-12 of a file unit; positions
// are kept exactly as integers of 10^-15 mm, a unit in which millimetres
// (x1000), inches (x25400) and HP-GL plotter units of 0.025 mm (x25) are all
// whole, so relative moves accumulate without rounding. Only the final
// division by the step size rounds (to nearest, halves away from zero).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "stepzip/error.hpp"
#include "stepzip/vectors.hpp"

namespace stepzip::vec {

__extension__ typedef __int128 i128;  // GCC and Clang; exact 10^-15 mm positions

/// 10^n for n in [0, 30].
i128 pow10(int n) noexcept;

/// Parses a decimal at text[pos] ("-12", "+.5", "3.", "0.125"): optional
/// sign, digits, optional point and digits (at least one digit in all).
/// On success stores the value in units of 10^-12, advances `pos` and
/// returns an empty string; otherwise returns why (`pos` unchanged).
/// At most 12 fraction digits and 15 integer digits.
std::string parse_decimal(std::string_view text, std::size_t& pos, i128& value_e12);

/// The decimal text of value_e12 / 10^12 without trailing zeros ("-1.25", "8").
std::string format_e12(i128 value_e12);

/// Factors from 10^-12 file units to 10^-15 mm.
inline constexpr i128 kPerMm = 1000;      // millimetres
inline constexpr i128 kPerInch = 25400;   // inches: 25.4 mm
inline constexpr i128 kPerPlotterUnit = 25;  // HP-GL: 0.025 mm

/// How a position in 10^-15 mm becomes steps: steps = pos * num / den,
/// rounded to the nearest step (halves away from zero) when `rounds`, else
/// required to be whole.
struct AxisScale {
    i128 num = 1;
    i128 den = pow10(15);  // no step size: values are steps, whole
    bool rounds = false;
    /// mm per step (absent: values are steps).
    static AxisScale of(const std::optional<StepSize>& step) noexcept;
    /// Steps per mm, in 10^-12 steps.
    static AxisScale per_mm(i128 steps_per_mm_e12) noexcept;
};

/// Position to steps under `scale`. Errors: Errc::syntax (not whole when the
/// scale does not round), Errc::limit (beyond kMaxVectorCoord).
Result<std::int64_t> to_steps(i128 pos_e15, const AxisScale& scale, const std::string& where,
                              std::string_view text);

/// Converts a position in 10^-15 mm (or, without a step size, in 10^-15
/// steps) to whole steps. Without a step size the position must be whole;
/// with one it is rounded to the nearest step, halves away from zero.
/// `where` prefixes error messages ("file:3:7"); `text` is the number as
/// written. Errors: Errc::syntax (not whole), Errc::limit (beyond
/// kMaxVectorCoord).
Result<std::int64_t> to_steps(i128 pos_e15, const std::optional<StepSize>& step,
                              const std::string& where, std::string_view text);

/// "SOURCE:LINE:COLUMN".
std::string place(const std::string& source, std::size_t line, std::size_t column);

/// A printable rendering of one byte for messages ("'*'", "byte 0x1b").
std::string describe_char(char c);

}  // namespace stepzip::vec
