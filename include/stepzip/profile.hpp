// stepzip — profiles: a forward interpolator plus its default phase rule.
//
// The container format depends on these definitions: a segment stored under a
// profile must expand, by the arithmetic below, to exactly its steps.
// docs/FORMAT.md gives the same arithmetic as normative pseudocode.
#pragma once

#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "stepzip/error.hpp"
#include "stepzip/segment.hpp"
#include "stepzip/step.hpp"

namespace stepzip {

/// Profile identifiers. The numeric values are stored in .stz files.
enum class Profile : std::uint8_t {
    eval4 = 0,   ///< evaluation function, 4-connected, F0 = 0 (seed 000)
    eval8 = 1,   ///< accelerated leading-axis method, 8-connected, F0 = 0
    patent = 2,  ///< SU 1089551 forward mode, 4-connected, F00 = Y - X
    grbl = 3,    ///< leading-axis method at GRBL's counter phase
    marlin = 4,  ///< leading-axis method at Marlin's error-term phase
};

inline constexpr Profile kAllProfiles[] = {Profile::eval4, Profile::eval8, Profile::patent,
                                           Profile::grbl, Profile::marlin};

/// The profile's name as used on the command line ("eval4", ...).
/// Every function in this header is thread-safe (no shared state).
std::string_view profile_name(Profile p) noexcept;
/// Parses a profile name; nullopt for an unknown name.
std::optional<Profile> parse_profile(std::string_view name) noexcept;
/// True for the 8-connected leading-axis profiles (eval8, grbl, marlin).
inline bool profile_eight_connected(Profile p) noexcept {
    return p == Profile::eval8 || p == Profile::grbl || p == Profile::marlin;
}
/// Largest axis count the profile supports (2 for eval4 and patent, else 6).
inline int profile_max_axes(Profile p) noexcept { return profile_eight_connected(p) ? kMaxAxes : 2; }

/// The default phase of one evaluation function of a segment.
/// For eval4 and patent (a, b) = (|dx|, |dy|); for the leading-axis profiles
/// (a, b) = (L, S), the leading and the minor total.
///   eval4: 0   patent: b - a   eval8: 0
///   grbl: ceil(L/2) - S        marlin: ceil(L/2) - S - 1
inline std::int64_t default_phase(Profile p, std::int64_t a, std::int64_t b) noexcept {
    const std::int64_t ceil_half = a / 2 + (a & 1);  // ceil(a / 2) for a >= 0, without overflow
    switch (p) {
        case Profile::eval4:
        case Profile::eval8: return 0;
        case Profile::patent: return b - a;
        case Profile::grbl: return ceil_half - b;
        case Profile::marlin: return ceil_half - b - 1;
    }
    return 0;
}

/// Half-open range [lo, hi) of phases a segment may carry for one evaluation
/// function; every step pattern the function can produce is produced by a
/// phase in this range, and only phases in it are accepted from a container.
///   eval4: [-b, a)     (ends exactly on its end point, seed 000)
///   eval8, grbl, marlin: [-S, L - S)
///   patent: [b - a - a*b, b - a + a*b + 1)
/// For a degenerate function (a pure run, a pure diagonal) the range is
/// [default, default + 1).
struct PhaseRange {
    std::int64_t lo = 0;
    std::int64_t hi = 1;
    bool contains(std::int64_t f) const noexcept { return lo <= f && f < hi; }
};
inline PhaseRange phase_range(Profile p, std::int64_t a, std::int64_t b) noexcept {
    // A function decides nothing when one letter of its two-letter pattern is absent.
    const bool degenerate = profile_eight_connected(p) ? (b == 0 || b == a) : (a == 0 || b == 0);
    if (degenerate) {
        const std::int64_t d = default_phase(p, a, b);
        return {d, d + 1};
    }
    switch (p) {
        case Profile::eval4: return {-b, a};
        case Profile::patent: return {b - a - a * b, b - a + a * b + 1};
        default: return {-b, a - b};
    }
}

/// Number of evaluation functions (phases) a segment has under the profile:
/// 1 for eval4/patent, axes - 1 for the leading-axis profiles.
inline int phase_count(Profile p, int axes) noexcept { return profile_eight_connected(p) ? axes - 1 : 1; }

/// The (a, b) arguments of evaluation function j of `seg` (see default_phase),
/// or nullopt when j is past the segment's functions.
inline std::optional<std::pair<std::int64_t, std::int64_t>> phase_arguments(Profile p, const Segment& seg,
                                                                            int axes, int j) noexcept {
    if (j < 0 || j >= phase_count(p, axes)) return std::nullopt;
    if (!profile_eight_connected(p)) return std::pair{std::llabs(seg.delta[0]), std::llabs(seg.delta[1])};
    const int lead = leading_axis(seg.delta, axes);
    const int axis = j < lead ? j : j + 1;
    return std::pair{std::llabs(seg.delta[lead]), std::llabs(seg.delta[axis])};
}

/// A segment with every phase set to the profile's default.
Segment default_segment(Profile p, const Point& delta, int axes) noexcept;

/// Checks that `seg` can be expanded under `p` on `axes` axes: axis count,
/// totals within limits, 4-connected profiles on two axes, phases in range.
/// Errors: Errc::invalid_argument / Errc::limit with a message.
Result<void> check_segment(Profile p, const Segment& seg, int axes);

/// Largest |total| per axis accepted in a segment: keeps every evaluation
/// function, including the patent's (up to 3·a·b), inside 64-bit arithmetic.
inline constexpr std::int64_t kMaxSegmentTotal = std::int64_t{1} << 30;

}  // namespace stepzip
