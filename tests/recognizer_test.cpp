// The online recognizer against brute force: a prefix is one exact segment
// iff some phase in phase_range() reproduces it by forward interpolation.
#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <random>
#include <span>
#include <vector>

#include "stepzip/profile.hpp"
#include "stepzip/segment/recognizer.hpp"
#include "stepzip/segment/segmenters.hpp"
#include "stepzip/segmenter.hpp"

namespace stepzip {
namespace {

Point totals(const std::vector<Step>& steps, int axes) {
    Point d{};
    for (Step s : steps) apply_step(d, s, axes);
    return d;
}

// Every phase of the (single) evaluation function of a two-axis segment that
// reproduces `steps`, by trying the whole phase range.
std::vector<std::int64_t> brute_phases(Profile p, const std::vector<Step>& steps) {
    std::vector<std::int64_t> ok;
    if (steps.empty()) return ok;
    Segment seg = default_segment(p, totals(steps, 2), 2);
    if (!check_segment(p, seg, 2)) return ok;
    const auto ab = *phase_arguments(p, seg, 2, 0);
    const PhaseRange r = phase_range(p, ab.first, ab.second);
    std::vector<Step> out;
    for (std::int64_t f = r.lo; f < r.hi; ++f) {
        seg.phase[0] = f;
        out.clear();
        expand_segment(p, seg, 2, out);
        if (out == steps) ok.push_back(f);
    }
    return ok;
}

// The phase nearest `d` among `v` (lower on a tie).
std::int64_t nearest(const std::vector<std::int64_t>& v, std::int64_t d) {
    std::int64_t best = v.front();
    for (std::int64_t f : v)
        if (std::llabs(f - d) < std::llabs(best - d) ||
            (std::llabs(f - d) == std::llabs(best - d) && f < best))
            best = f;
    return best;
}

// Steps of a two-letter word for profile p: eval4/patent letter 0 = +x,
// letter 1 = +y; 8-connected letter 0 = +x, letter 1 = +x+y.
std::vector<Step> word_steps(Profile p, unsigned bits, int n) {
    std::vector<Step> steps;
    for (int k = 0; k < n; ++k) {
        const bool one = (bits >> k) & 1u;
        if (profile_eight_connected(p)) steps.push_back(make_step2(1, one ? 1 : 0));
        else steps.push_back(one ? make_step2(0, 1) : make_step2(1, 0));
    }
    return steps;
}

// Checks recognizer, fit_segment and the greedy length against brute force
// on every prefix of `steps` (two axes, signs already fixed).
void check_prefixes(Profile p, const std::vector<Step>& steps) {
    SegmentRecognizer rec(p == Profile::patent ? Profile::eval4 : p, 2);
    bool alive = true;
    std::int64_t longest = 0;
    std::vector<Step> prefix;
    for (std::size_t k = 0; k < steps.size(); ++k) {
        prefix.push_back(steps[k]);
        const auto phases = brute_phases(p, prefix);
        const bool valid = !phases.empty();
        if (valid) longest = static_cast<std::int64_t>(k + 1);
        const auto fit = fit_segment(p, prefix, 2);
        ASSERT_EQ(fit.has_value(), valid) << profile_name(p) << " prefix length " << k + 1;
        if (valid) {
            const auto ab = *phase_arguments(p, *fit, 2, 0);
            EXPECT_EQ(fit->phase[0], nearest(phases, default_phase(p, ab.first, ab.second)))
                << profile_name(p) << " prefix length " << k + 1;
        }
        if (p == Profile::patent) continue;
        if (alive) {
            ASSERT_TRUE(rec.can_extend(steps[k]));
            alive = rec.extend(steps[k]);
        }
        ASSERT_EQ(alive && rec.valid(), valid) << profile_name(p) << " prefix length " << k + 1;
        if (!alive) {
            EXPECT_FALSE(valid) << "a prefix is valid after the recognizer gave up";
        }
    }
    EXPECT_EQ(GreedySegmenter(p, 2).longest(steps), longest);
}

// Exhaustive: every word of 12 letters, hence every prefix of up to 12.
TEST(Recognizer, EveryWordUpToTwelveLettersMatchesBruteForce) {
    constexpr int n = 12;
    for (Profile p : kAllProfiles)
        for (unsigned bits = 0; bits < (1u << n); ++bits) {
            check_prefixes(p, word_steps(p, bits, n));
            if (::testing::Test::HasFatalFailure()) return;
        }
}

// Long words near digital lines: a line drawn at a random phase, then a few
// letters flipped, so that validity comes and goes along the prefixes.
TEST(Recognizer, PerturbedLinesMatchBruteForce) {
    std::mt19937_64 rng(7);
    for (Profile p : kAllProfiles)
        for (int rep = 0; rep < 60; ++rep) {
            const std::int64_t a = std::uniform_int_distribution<int>(1, 40)(rng);
            const std::int64_t b = std::uniform_int_distribution<int>(1, 40)(rng);
            Point delta{};
            delta[0] = profile_eight_connected(p) ? a + b : a;
            delta[1] = b;
            Segment seg = default_segment(p, delta, 2);
            const auto ab = *phase_arguments(p, seg, 2, 0);
            const PhaseRange r = phase_range(p, ab.first, ab.second);
            seg.phase[0] = std::uniform_int_distribution<std::int64_t>(r.lo, r.hi - 1)(rng);
            std::vector<Step> steps;
            expand_segment(p, seg, 2, steps);
            for (int flips = rep % 3; flips > 0; --flips) {
                const auto k = std::uniform_int_distribution<std::size_t>(0, steps.size() - 1)(rng);
                if (profile_eight_connected(p)) steps[k] ^= make_step2(0, 1);  // toggles +y
                else steps[k] = steps[k] == make_step2(1, 0) ? make_step2(0, 1) : make_step2(1, 0);
            }
            check_prefixes(p, steps);
            if (::testing::Test::HasFatalFailure()) return;
        }
}

// A line drawn by each profile's own interpolator at its default phase is one
// segment, with the default phase: every (dx, dy) up to 40, all quadrants.
TEST(Recognizer, OwnLinesAreOneSegmentAtTheDefaultPhase) {
    for (Profile p : kAllProfiles)
        for (int dx = -40; dx <= 40; ++dx)
            for (int dy = -40; dy <= 40; ++dy) {
                if (dx == 0 && dy == 0) continue;
                Point delta{};
                delta[0] = dx;
                delta[1] = dy;
                const Segment seg = default_segment(p, delta, 2);
                std::vector<Step> steps;
                expand_segment(p, seg, 2, steps);
                std::vector<Segment> out;
                ASSERT_TRUE(segment_steps(steps, 2, p, SegmenterKind::greedy, out).ok());
                ASSERT_EQ(out.size(), 1u) << profile_name(p) << " " << dx << " " << dy;
                EXPECT_EQ(out[0], seg) << profile_name(p) << " " << dx << " " << dy;
            }
}

// grbl and marlin lines are eval8 patterns: one eval8 segment each, also on
// more axes.
TEST(Recognizer, GrblAndMarlinLinesAreOneEval8Segment) {
    std::mt19937_64 rng(5);
    for (Profile src : {Profile::grbl, Profile::marlin})
        for (int axes = 2; axes <= 6; ++axes)
            for (int rep = 0; rep < 300; ++rep) {
                Point delta{};
                for (int i = 0; i < axes; ++i)
                    delta[i] = std::uniform_int_distribution<int>(-200, 200)(rng);
                delta[0] = delta[0] == 0 ? 1 : delta[0];
                std::vector<Step> steps;
                expand_segment(src, default_segment(src, delta, axes), axes, steps);
                std::vector<Segment> out;
                ASSERT_TRUE(segment_steps(steps, axes, Profile::eval8, SegmenterKind::greedy, out).ok());
                ASSERT_EQ(out.size(), 1u);
                EXPECT_EQ(out[0].delta, delta);
                // ... and under their own profile at zero phase cost
                out.clear();
                ASSERT_TRUE(segment_steps(steps, axes, src, SegmenterKind::greedy, out).ok());
                ASSERT_EQ(out.size(), 1u);
                EXPECT_EQ(out[0], default_segment(src, delta, axes));
            }
}

// The greedy segmenter reads whole runs of identical steps at once; its answer
// must be that of the letter-by-letter recognizer: at every start of random
// chains made of long lines (long runs), near-lines, walks with repeated
// codes, sign changes and 3-6 axes.
std::int64_t longest_letter_by_letter(Profile p, int axes, std::span<const Step> steps) {
    SegmentRecognizer rec(p, axes);
    std::int64_t best = 1;
    for (Step s : steps) {
        if (!rec.can_extend(s) || !rec.extend(s)) break;
        if (rec.valid()) best = rec.length();
    }
    return best;
}

std::vector<Step> mixed_chain(std::mt19937_64& rng, Profile p, int axes, std::size_t n) {
    std::vector<Step> steps;
    const bool eight = profile_eight_connected(p);
    while (steps.size() < n) {
        const int kind = static_cast<int>(rng() % 3);
        if (kind == 0) {  // a line at a random phase, maybe long
            Point d{};
            const int span = rng() % 4 == 0 ? 400 : 30;
            for (int i = 0; i < axes; ++i) d[i] = std::uniform_int_distribution<int>(-span, span)(rng);
            if (!eight) d[1] = d[1] == 0 && d[0] == 0 ? 1 : d[1];
            bool any = false;
            for (int i = 0; i < axes; ++i) any = any || d[i] != 0;
            if (!any) d[0] = 1;
            Segment seg = default_segment(p, d, axes);
            for (int j = 0; j < phase_count(p, axes); ++j) {
                const auto ab = *phase_arguments(p, seg, axes, j);
                const PhaseRange r = phase_range(p, ab.first, ab.second);
                seg.phase[j] = std::uniform_int_distribution<std::int64_t>(r.lo, r.hi - 1)(rng);
            }
            expand_segment(p, seg, axes, steps);
        } else if (kind == 1 && !steps.empty()) {  // perturb a few recent ticks
            for (int f = 0; f < 2; ++f) {
                const auto k = steps.size() - 1 - rng() % std::min<std::size_t>(steps.size(), 50);
                const int axis = static_cast<int>(rng() % static_cast<unsigned>(axes));
                Step t = static_cast<Step>(steps[k] ^ (1u << (2 * axis)));
                t = static_cast<Step>(t & ~(((~t) & (1u << (2 * axis))) << 1));  // no DIR on a rest
                if (step_valid(t, axes) && (eight || step_weight(t) == 1)) steps[k] = t;
            }
        } else {  // runs of one code
            int d[kMaxAxes] = {};
            if (eight) {
                for (int i = 0; i < axes; ++i) d[i] = static_cast<int>(rng() % 3) - 1;
                d[0] = d[0] == 0 ? 1 : d[0];
            } else {
                d[rng() % 2] = rng() % 2 ? 1 : -1;
            }
            const std::size_t len = 1 + rng() % 12;
            steps.insert(steps.end(), len, make_step(d, axes));
        }
    }
    steps.resize(n);
    return steps;
}

TEST(Recognizer, RunByRunGreedyMatchesLetterByLetter) {
    std::mt19937_64 rng(11);
    for (Profile p : {Profile::eval4, Profile::eval8, Profile::grbl, Profile::marlin})
        for (int axes = 2; axes <= profile_max_axes(p); ++axes)
            for (int rep = 0; rep < 4; ++rep) {
                const auto steps = mixed_chain(rng, p, axes, 1500);
                const GreedySegmenter greedy(p, axes);
                for (std::size_t s = 0; s < steps.size(); ++s) {
                    const auto rest = std::span<const Step>(steps).subspan(s);
                    ASSERT_EQ(greedy.longest(rest), longest_letter_by_letter(p, axes, rest))
                        << profile_name(p) << " axes " << axes << " rep " << rep << " start " << s;
                }
            }
}

// Multi-axis: the segment recognizer agrees with brute force over all phase
// combinations on random 3-axis runs near a line.
TEST(Recognizer, ThreeAxesMatchesBruteForce) {
    std::mt19937_64 rng(3);
    for (int rep = 0; rep < 300; ++rep) {
        Point delta{};
        delta[0] = std::uniform_int_distribution<int>(1, 12)(rng);
        delta[1] = std::uniform_int_distribution<int>(0, 12)(rng);
        delta[2] = std::uniform_int_distribution<int>(-12, 12)(rng);
        Segment seg = default_segment(Profile::eval8, delta, 3);
        for (int j = 0; j < 2; ++j) {
            const auto ab = *phase_arguments(Profile::eval8, seg, 3, j);
            const PhaseRange r = phase_range(Profile::eval8, ab.first, ab.second);
            seg.phase[j] = std::uniform_int_distribution<std::int64_t>(r.lo, r.hi - 1)(rng);
        }
        std::vector<Step> steps;
        expand_segment(Profile::eval8, seg, 3, steps);
        if (rep % 2) {
            const auto k = std::uniform_int_distribution<std::size_t>(0, steps.size() - 1)(rng);
            steps[k] ^= make_step2(0, 1);  // toggle +y on one tick
            if (!step_valid(steps[k], 3)) continue;
        }
        SegmentRecognizer rec(Profile::eval8, 3);
        std::vector<Step> prefix;
        bool alive = true;
        for (Step s : steps) {
            prefix.push_back(s);
            // brute force: every phase pair in range
            const Point d = totals(prefix, 3);
            Segment t = default_segment(Profile::eval8, d, 3);
            bool brute = false;
            const auto ab0 = *phase_arguments(Profile::eval8, t, 3, 0);
            const auto ab1 = *phase_arguments(Profile::eval8, t, 3, 1);
            const PhaseRange r0 = phase_range(Profile::eval8, ab0.first, ab0.second);
            const PhaseRange r1 = phase_range(Profile::eval8, ab1.first, ab1.second);
            std::vector<Step> out;
            for (t.phase[0] = r0.lo; t.phase[0] < r0.hi && !brute; ++t.phase[0])
                for (t.phase[1] = r1.lo; t.phase[1] < r1.hi && !brute; ++t.phase[1]) {
                    out.clear();
                    expand_segment(Profile::eval8, t, 3, out);
                    brute = out == prefix;
                }
            bool got = false;
            if (alive && rec.can_extend(s)) {
                alive = rec.extend(s);
                got = alive && rec.valid();
            } else {
                alive = false;
            }
            ASSERT_EQ(got, brute) << "rep " << rep << " length " << prefix.size();
            ASSERT_EQ(fit_segment(Profile::eval8, prefix, 3).has_value(), brute);
        }
    }
}

}  // namespace
}  // namespace stepzip
