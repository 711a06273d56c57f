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
