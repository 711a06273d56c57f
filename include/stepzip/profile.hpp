// stepzip — profiles: a forward interpolator plus its default phase rule.
//
// The container format depends on these definitions: a segment stored under a
// profile must expand, by the arithmetic below, to exactly its steps.
// docs/FORMAT.md gives the same arithmetic as normative pseudocode.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
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
bool profile_eight_connected(Profile p) noexcept;
/// Largest axis count the profile supports (2 for eval4 and patent, else 6).
int profile_max_axes(Profile p) noexcept;

/// The default phase of one evaluation function of a segment.
/// For eval4 and patent (a, b) = (|dx|, |dy|); for the leading-axis profiles
/// (a, b) = (L, S), the leading and the minor total.
///   eval4: 0   patent: b - a   eval8: 0
///   grbl: ceil(L/2) - S        marlin: ceil(L/2) - S - 1
std::int64_t default_phase(Profile p, std::int64_t a, std::int64_t b) noexcept;

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
PhaseRange phase_range(Profile p, std::int64_t a, std::int64_t b) noexcept;

/// The (a, b) arguments of evaluation function j of `seg` (see default_phase),
/// or nullopt when j is past the segment's functions.
std::optional<std::pair<std::int64_t, std::int64_t>> phase_arguments(Profile p, const Segment& seg,
                                                                     int axes, int j) noexcept;

/// Number of evaluation functions (phases) a segment has under the profile:
/// 1 for eval4/patent, axes - 1 for the leading-axis profiles.
int phase_count(Profile p, int axes) noexcept;

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
