// Profiles: SPEC section 3. The arithmetic here is normative for .stz files.
#include "stepzip/profile.hpp"

#include <cstdlib>
#include <string>

namespace stepzip {

std::string_view profile_name(Profile p) noexcept {
    switch (p) {
        case Profile::eval4: return "eval4";
        case Profile::eval8: return "eval8";
        case Profile::patent: return "patent";
        case Profile::grbl: return "grbl";
        case Profile::marlin: return "marlin";
    }
    return "?";
}

std::optional<Profile> parse_profile(std::string_view name) noexcept {
    for (Profile p : kAllProfiles)
        if (profile_name(p) == name) return p;
    return std::nullopt;
}

bool profile_eight_connected(Profile p) noexcept {
    return p == Profile::eval8 || p == Profile::grbl || p == Profile::marlin;
}

int profile_max_axes(Profile p) noexcept { return profile_eight_connected(p) ? kMaxAxes : 2; }

int phase_count(Profile p, int axes) noexcept { return profile_eight_connected(p) ? axes - 1 : 1; }

namespace {
// ceil(l / 2) for l >= 0, without overflow at INT64_MAX.
std::int64_t ceil_half(std::int64_t l) { return l / 2 + (l & 1); }
// A function decides nothing when one letter of its two-letter pattern is absent.
bool degenerate(Profile p, std::int64_t a, std::int64_t b) {
    return profile_eight_connected(p) ? (b == 0 || b == a) : (a == 0 || b == 0);
}
}  // namespace

std::int64_t default_phase(Profile p, std::int64_t a, std::int64_t b) noexcept {
    switch (p) {
        case Profile::eval4:
        case Profile::eval8: return 0;
        case Profile::patent: return b - a;
        case Profile::grbl: return ceil_half(a) - b;
        case Profile::marlin: return ceil_half(a) - b - 1;
    }
    return 0;
}

PhaseRange phase_range(Profile p, std::int64_t a, std::int64_t b) noexcept {
    if (degenerate(p, a, b)) {
        const std::int64_t d = default_phase(p, a, b);
        return {d, d + 1};
    }
    switch (p) {
        case Profile::eval4: return {-b, a};
        case Profile::patent: return {b - a - a * b, b - a + a * b + 1};
        default: return {-b, a - b};
    }
}

std::optional<std::pair<std::int64_t, std::int64_t>> phase_arguments(Profile p, const Segment& seg,
                                                                     int axes, int j) noexcept {
    if (j < 0 || j >= phase_count(p, axes)) return std::nullopt;
    if (!profile_eight_connected(p)) return std::pair{std::llabs(seg.delta[0]), std::llabs(seg.delta[1])};
    const int lead = leading_axis(seg.delta, axes);
    const int axis = j < lead ? j : j + 1;
    return std::pair{std::llabs(seg.delta[lead]), std::llabs(seg.delta[axis])};
}

Segment default_segment(Profile p, const Point& delta, int axes) noexcept {
    Segment seg;
    seg.delta = delta;
    for (int j = 0; j < phase_count(p, axes); ++j) {
        const auto ab = *phase_arguments(p, seg, axes, j);
        seg.phase[j] = default_phase(p, ab.first, ab.second);
    }
    return seg;
}

Result<void> check_segment(Profile p, const Segment& seg, int axes) {
    if (axes < 2 || axes > profile_max_axes(p))
        return make_error(Errc::invalid_argument,
                          "profile " + std::string(profile_name(p)) + " does not take " +
                              std::to_string(axes) + " axes");
    bool any = false;
    for (int i = 0; i < kMaxAxes; ++i) {
        if (i >= axes && seg.delta[i] != 0)
            return make_error(Errc::invalid_argument, "segment moves an axis past the axis count");
        if (seg.delta[i] > kMaxSegmentTotal || seg.delta[i] < -kMaxSegmentTotal)
            return make_error(Errc::limit, "segment total exceeds 2^30 steps on an axis");
        any = any || seg.delta[i] != 0;
    }
    if (!any) return make_error(Errc::invalid_argument, "empty segment");
    for (int j = 0; j < phase_count(p, axes); ++j) {
        const auto ab = *phase_arguments(p, seg, axes, j);
        if (!phase_range(p, ab.first, ab.second).contains(seg.phase[j]))
            return make_error(Errc::invalid_argument, "segment phase out of range");
    }
    return {};
}

}  // namespace stepzip
