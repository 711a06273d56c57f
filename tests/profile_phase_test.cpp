// Profiles (SPEC section 3): grbl and marlin are eval8 patterns at their
// default phase, checked against the controllers' own counter arithmetic.
#include <gtest/gtest.h>

#include <vector>

#include "stepzip/interpolate/linear.hpp"
#include "stepzip/interpolate/segment.hpp"
#include "stepzip/profile.hpp"

namespace stepzip {
namespace {

// GRBL-style counters: c = floor(L/2); each tick c += S; if c > L: minor step, c -= L.
std::vector<bool> grbl_minor(std::int64_t l, std::int64_t s) {
    std::vector<bool> m;
    std::int64_t c = l / 2;
    for (std::int64_t t = 0; t < l; ++t) {
        c += s;
        const bool step = c > l;
        if (step) c -= l;
        m.push_back(step);
    }
    return m;
}

// Marlin-style error term: e = -L; each tick e += 2S; if e >= 0: minor step, e -= 2L.
std::vector<bool> marlin_minor(std::int64_t l, std::int64_t s) {
    std::vector<bool> m;
    std::int64_t e = -l;
    for (std::int64_t t = 0; t < l; ++t) {
        e += 2 * s;
        const bool step = e >= 0;
        if (step) e -= 2 * l;
        m.push_back(step);
    }
    return m;
}

std::vector<bool> profile_minor(Profile p, std::int64_t l, std::int64_t s) {
    Point delta{};
    delta[0] = l;
    delta[1] = s;
    std::vector<Step> steps;
    expand_segment(p, default_segment(p, delta, 2), 2, steps);
    std::vector<bool> m;
    for (Step st : steps) m.push_back(step_axis(st, 1) != 0);
    return m;
}

TEST(Profiles, GrblAndMarlinAreEval8AtTheirDefaultPhase) {
    for (std::int64_t l = 2; l < 60; ++l)
        for (std::int64_t s = 1; s < l; ++s) {
            ASSERT_EQ(profile_minor(Profile::grbl, l, s), grbl_minor(l, s)) << l << "," << s;
            ASSERT_EQ(profile_minor(Profile::marlin, l, s), marlin_minor(l, s)) << l << "," << s;
        }
}

TEST(Profiles, MarlinMinorCountIsRoundedProportion) {
    for (std::int64_t l = 2; l < 60; ++l)
        for (std::int64_t s = 1; s < l; ++s) {
            const auto m = profile_minor(Profile::marlin, l, s);
            std::int64_t count = 0;
            for (std::int64_t k = 1; k <= l; ++k) {
                count += m[k - 1];
                // floor(k*S/L + 1/2) == floor((2kS + L) / 2L)
                ASSERT_EQ(count, (2 * k * s + l) / (2 * l)) << l << "," << s << " k=" << k;
            }
        }
}

TEST(Profiles, DefaultPhasesLieInTheirRange) {
    for (Profile p : kAllProfiles)
        for (std::int64_t a = 0; a < 80; ++a)
            for (std::int64_t b = 0; b < 80; ++b) {
                if (a + b == 0) continue;
                if (profile_eight_connected(p) && b > a) continue;
                EXPECT_TRUE(phase_range(p, a, b).contains(default_phase(p, a, b)))
                    << profile_name(p) << " " << a << "," << b;
            }
}

TEST(Profiles, NamesRoundTrip) {
    for (Profile p : kAllProfiles) EXPECT_EQ(parse_profile(profile_name(p)), p);
    EXPECT_FALSE(parse_profile("bresenham").has_value());
}

TEST(Profiles, CheckSegmentRejectsBadSegments) {
    Segment seg;
    EXPECT_FALSE(check_segment(Profile::eval8, seg, 2));  // empty
    seg.delta[0] = 5;
    seg.delta[1] = 2;
    EXPECT_TRUE(check_segment(Profile::eval8, seg, 2));
    seg.phase[0] = 3;  // [-2, 3) excludes 3
    EXPECT_FALSE(check_segment(Profile::eval8, seg, 2));
    seg.phase[0] = 0;
    EXPECT_FALSE(check_segment(Profile::eval4, seg, 3));  // eval4 is two-axis
    seg.delta[0] = kMaxSegmentTotal + 1;
    EXPECT_EQ(check_segment(Profile::eval8, seg, 2).error().code, Errc::limit);
}

// Every profile's expansion of a valid segment ends on the segment's end point.
TEST(Profiles, ExpansionEndsOnEndPointForEveryPhase) {
    for (Profile p : kAllProfiles)
        for (int dx = -25; dx <= 25; ++dx)
            for (int dy = -25; dy <= 25; ++dy) {
                if (dx == 0 && dy == 0) continue;
                Point delta{};
                delta[0] = dx;
                delta[1] = dy;
                Segment seg = default_segment(p, delta, 2);
                const auto ab = *phase_arguments(p, seg, 2, 0);
                const PhaseRange r = phase_range(p, ab.first, ab.second);
                for (std::int64_t f = r.lo; f < r.hi; ++f) {
                    seg.phase[0] = f;
                    ASSERT_TRUE(check_segment(p, seg, 2));
                    std::vector<Step> steps;
                    expand_segment(p, seg, 2, steps);
                    Point e{};
                    for (Step s : steps) {
                        ASSERT_TRUE(step_valid(s, 2));
                        if (!profile_eight_connected(p)) ASSERT_EQ(step_weight(s), 1);
                        apply_step(e, s, 2);
                    }
                    ASSERT_EQ(e, delta) << profile_name(p) << " f0=" << f;
                }
            }
}

}  // namespace
}  // namespace stepzip
