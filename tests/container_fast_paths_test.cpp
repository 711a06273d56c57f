// The encoder's and decoder's fast paths give exactly the answers of the
// step-by-step definitions they replace:
//  * two-axis expansion by division per run (src/interpolate/linear.cpp)
//    equals the per-step rules of docs/FORMAT.md section 2 for every
//    (dx, dy, phase) in a range, phases outside the exact range included;
//    so does the expansion on 3 to 6 axes (one minor axis at a time);
//  * the two-axis default-phase cut (src/segment/default_phase_cut.cpp) equals the reference
//    cut that expands every candidate pattern, on random chains drawn by
//    the profiles' own interpolators and on random walks.
#include <gtest/gtest.h>

#include <random>

#include "../src/interpolate/expand_into.hpp"
#include "../src/segment/default_phase_cut.hpp"
#include "stepzip/interpolate/linear.hpp"
#include "stepzip/interpolate/segment.hpp"
#include "stepzip/profile.hpp"

namespace stepzip {
namespace {

int sgn(std::int64_t v) { return (v > 0) - (v < 0); }

// The evaluation-function rule (seed 000), written out step by step.
std::vector<Step> eval4_steps(std::int64_t dx, std::int64_t dy, std::int64_t f0) {
    std::vector<Step> out;
    const std::int64_t a = std::llabs(dx), b = std::llabs(dy);
    std::int64_t kx = a, ky = b, f = f0;
    while (kx > 0 || ky > 0) {
        bool x = f >= 0;
        if (x && kx == 0) x = false;
        else if (!x && ky == 0) x = true;
        if (x) { out.push_back(make_step2(sgn(dx), 0)); --kx; f -= b; }
        else { out.push_back(make_step2(0, sgn(dy))); --ky; f += a; }
    }
    return out;
}

// The accelerated rule (leading axis), step by step.
std::vector<Step> eval8_steps(std::int64_t dx, std::int64_t dy, std::int64_t f0) {
    std::vector<Step> out;
    const bool xl = std::llabs(dx) >= std::llabs(dy);
    const std::int64_t l = xl ? std::llabs(dx) : std::llabs(dy), s = xl ? std::llabs(dy) : std::llabs(dx);
    std::int64_t f = f0;
    for (std::int64_t t = 0; t < l; ++t) {
        bool diag;
        if (s == 0) diag = false;
        else if (s == l) diag = true;
        else if (f >= 0) { diag = false; f -= s; }
        else { diag = true; f += l - s; }
        out.push_back(diag ? make_step2(sgn(dx), sgn(dy)) : xl ? make_step2(sgn(dx), 0) : make_step2(0, sgn(dy)));
    }
    return out;
}

TEST(FastExpansion, Eval4EqualsStepRuleOverWholeRange) {
    for (std::int64_t dx = -24; dx <= 24; ++dx)
        for (std::int64_t dy = -24; dy <= 24; ++dy) {
            if (dx == 0 && dy == 0) continue;
            const std::int64_t a = std::llabs(dx), b = std::llabs(dy);
            for (std::int64_t f0 = -b - 3; f0 <= a + 3; ++f0) {
                std::vector<Step> fast;
                eval_linear(dx, dy, f0, fast);
                ASSERT_EQ(fast, eval4_steps(dx, dy, f0)) << dx << " " << dy << " " << f0;
            }
        }
}

TEST(FastExpansion, TwoAxisLeadingEqualsStepRuleOverWholeRange) {
    for (std::int64_t dx = -24; dx <= 24; ++dx)
        for (std::int64_t dy = -24; dy <= 24; ++dy) {
            if (dx == 0 && dy == 0) continue;
            const std::int64_t l = std::max(std::llabs(dx), std::llabs(dy));
            for (std::int64_t f0 = -l - 3; f0 <= l + 3; ++f0) {
                std::vector<Step> fast;
                const Point d{dx, dy};
                multiaxis_linear(d, 2, &f0, fast);
                ASSERT_EQ(fast, eval8_steps(dx, dy, f0)) << dx << " " << dy << " " << f0;
                fast.clear();
                accelerated_linear(dx, dy, f0, fast);
                ASSERT_EQ(fast, eval8_steps(dx, dy, f0)) << dx << " " << dy << " " << f0;
            }
        }
}

TEST(FastExpansion, LongSegmentsEqualStepRule) {
    std::mt19937_64 rng(7);
    for (int i = 0; i < 2000; ++i) {
        const std::int64_t l = 1 + static_cast<std::int64_t>(rng() % 100000);
        const std::int64_t s = static_cast<std::int64_t>(rng() % (l + 1));
        const std::int64_t f0 = -s + static_cast<std::int64_t>(rng() % static_cast<std::uint64_t>(l));
        std::vector<Step> fast;
        const Point d{l, -s};
        multiaxis_linear(d, 2, &f0, fast);
        ASSERT_EQ(fast, eval8_steps(l, -s, f0));
        fast.clear();
        eval_linear(-s, l, f0, fast);
        ASSERT_EQ(fast, eval4_steps(-s, l, f0));
    }
}

// The leading-axis rule on any number of axes, step by step.
std::vector<Step> multi_steps(const Point& d, int axes, const std::int64_t* phases) {
    const int lead = leading_axis(d, axes);
    const std::int64_t l = std::llabs(d[lead]);
    std::int64_t f[kMaxAxes] = {};
    for (int j = 0; j + 1 < axes; ++j) f[j] = phases[j];
    std::vector<Step> out;
    for (std::int64_t t = 0; t < l; ++t) {
        int mv[kMaxAxes] = {};
        mv[lead] = sgn(d[lead]);
        int j = 0;
        for (int i = 0; i < axes; ++i) {
            if (i == lead) continue;
            const std::int64_t s = std::llabs(d[i]);
            bool move;
            if (s == 0) move = false;
            else if (s == l) move = true;
            else if (f[j] >= 0) { move = false; f[j] -= s; }
            else { move = true; f[j] += l - s; }
            mv[i] = move ? sgn(d[i]) : 0;
            ++j;
        }
        out.push_back(make_step(mv, axes));
    }
    return out;
}

TEST(FastExpansion, MoreAxesEqualStepRule) {
    std::mt19937_64 rng(21);
    for (int i = 0; i < 40000; ++i) {
        const int axes = 3 + static_cast<int>(rng() % 4);
        const std::int64_t range = i % 4 == 0 ? 2000 : 13;  // small totals hit ties and degenerate axes
        Point d{};
        for (int a = 0; a < axes; ++a)
            d[a] = static_cast<std::int64_t>(rng() % (2 * range + 1)) - range;
        const int lead = leading_axis(d, axes);
        const std::int64_t l = std::llabs(d[lead]);
        if (l == 0) continue;
        std::int64_t ph[kMaxAxes] = {};
        for (int j = 0; j + 1 < axes; ++j)  // inside the exact range mostly, sometimes just outside
            ph[j] = -l - 2 + static_cast<std::int64_t>(rng() % static_cast<std::uint64_t>(2 * l + 4));
        std::vector<Step> fast;
        multiaxis_linear(d, axes, ph, fast);
        ASSERT_EQ(fast, multi_steps(d, axes, ph)) << "case " << i;
    }
}

// The decoders' expansion into a buffer writes exactly what expand_segment
// appends, wherever it takes a fast path, on every profile, for every
// total and phase in a range (phases outside the exact range included) and
// on 3 to 6 axes; it takes one on every two-axis segment with a phase in
// the exact range, and on every eval4 segment along one axis.
TEST(FastExpansion, IntoBufferEqualsExpandSegment) {
    std::mt19937_64 rng(5);
    std::size_t fast_taken = 0;
    for (Profile p : kAllProfiles) {
        const bool eight = profile_eight_connected(p);
        for (int i = 0; i < 30000; ++i) {
            const int axes = eight && i % 3 == 0 ? 3 + static_cast<int>(rng() % 4) : 2;
            const std::int64_t range = i % 5 == 0 ? 300 : 9;
            Segment seg{};
            for (int a = 0; a < axes; ++a)
                seg.delta[a] = static_cast<std::int64_t>(rng() % (2 * range + 1)) - range;
            const std::int64_t n = segment_length(seg.delta, axes, eight);
            if (n == 0) continue;
            for (int j = 0; j + 1 < axes; ++j)
                seg.phase[j] = -n - 2 + static_cast<std::int64_t>(rng() % static_cast<std::uint64_t>(2 * n + 4));
            if (!check_segment(p, seg, axes)) continue;
            std::vector<Step> want;
            expand_segment(p, seg, axes, want);
            std::vector<Step> got(static_cast<std::size_t>(n), Step{0xFFFF});
            if (!detail::expand_segment_into(p, seg, axes, got.data())) {
                const std::int64_t a = std::llabs(seg.delta[0]), b = std::llabs(seg.delta[1]);
                const std::int64_t l = std::max(a, b), s = std::min(a, b);
                EXPECT_FALSE(axes == 2 && eight && seg.phase[0] >= -s && seg.phase[0] < l - s) << profile_name(p);
                EXPECT_FALSE(p == Profile::eval4 && (a == 0 || b == 0)) << profile_name(p);
                continue;
            }
            ++fast_taken;
            ASSERT_EQ(got, want) << profile_name(p) << " case " << i;
        }
    }
    EXPECT_GT(fast_taken, 20000u);
}

// A chain of segments drawn at the profile's default phase (a controller
// stream), with a few random steps mixed in.
std::vector<Step> controller_chain(Profile p, std::mt19937_64& rng) {
    std::vector<Step> steps;
    const int n = 1 + static_cast<int>(rng() % 40);
    for (int i = 0; i < n; ++i) {
        if (rng() % 6 == 0) {
            const int code = static_cast<int>(rng() % 8);
            if (profile_eight_connected(p) || code % 2 == 0) steps.push_back(freeman_to_step(code));
            continue;
        }
        const std::int64_t l = 1 + static_cast<std::int64_t>(rng() % 200);
        const std::int64_t s = static_cast<std::int64_t>(rng() % (l + 1));
        Point d{};
        const bool swap = rng() % 2;
        d[swap ? 1 : 0] = rng() % 2 ? l : -l;
        d[swap ? 0 : 1] = rng() % 2 ? s : -s;
        expand_segment(p, default_segment(p, d, 2), 2, steps);
    }
    return steps;
}

TEST(FastAlignedCut, EqualsReferenceCut) {
    std::mt19937_64 rng(11);
    for (Profile p : {Profile::eval4, Profile::eval8, Profile::grbl, Profile::marlin}) {
        for (int round = 0; round < 300; ++round) {
            std::vector<Step> steps = controller_chain(p, rng);
            std::vector<Segment> fast, ref;
            const bool ok_fast = cut_preferring_default(steps, 2, p, fast);
            const bool ok_ref = cut_preferring_default_reference(steps, 2, p, ref);
            ASSERT_EQ(ok_fast, ok_ref);
            ASSERT_EQ(fast, ref) << profile_name(p) << " round " << round;
        }
        for (int round = 0; round < 100; ++round) {
            std::vector<Step> steps;
            const int n = static_cast<int>(rng() % 400);
            for (int k = 0; k < n; ++k) {
                const int code = static_cast<int>(rng() % 8);
                steps.push_back(freeman_to_step(profile_eight_connected(p) ? code : code & 6));
            }
            std::vector<Segment> fast, ref;
            ASSERT_EQ(cut_preferring_default(steps, 2, p, fast),
                      cut_preferring_default_reference(steps, 2, p, ref));
            ASSERT_EQ(fast, ref) << profile_name(p) << " walk " << round;
        }
    }
}

}  // namespace
}  // namespace stepzip
