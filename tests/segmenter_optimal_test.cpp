// The optimal segmenter finds the fewest exact segments: it equals a
// brute-force minimum (every cut, every phase) on all short chains, and never
// uses more segments than greedy.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <span>
#include <vector>

#include "stepzip/profile.hpp"
#include "stepzip/segment/recognizer.hpp"
#include "stepzip/segment/segmenters.hpp"
#include "stepzip/segmenter.hpp"

namespace stepzip {
namespace {

// Brute force: is steps[s, e) one segment under p with some phase in range?
bool brute_exact(Profile p, const std::vector<Step>& steps, std::size_t s, std::size_t e) {
    const std::vector<Step> run(steps.begin() + s, steps.begin() + e);
    Point d{};
    for (Step st : run) apply_step(d, st, 2);
    Segment seg = default_segment(p, d, 2);
    if (!check_segment(p, seg, 2)) return false;
    const auto ab = *phase_arguments(p, seg, 2, 0);
    const PhaseRange r = phase_range(p, ab.first, ab.second);
    std::vector<Step> out;
    for (std::int64_t f = r.lo; f < r.hi; ++f) {
        seg.phase[0] = f;
        out.clear();
        expand_segment(p, seg, 2, out);
        if (out == run) return true;
    }
    return false;
}

// Minimum segment count over every way of cutting the chain.
std::size_t brute_minimum(Profile p, const std::vector<Step>& steps) {
    const std::size_t n = steps.size();
    std::vector<std::size_t> best(n + 1, n + 1);
    best[0] = 0;
    for (std::size_t e = 1; e <= n; ++e)
        for (std::size_t s = 0; s < e; ++s)
            if (best[s] + 1 < best[e] && brute_exact(p, steps, s, e)) best[e] = best[s] + 1;
    return best[n];
}

std::size_t count(Profile p, SegmenterKind k, const std::vector<Step>& steps) {
    std::vector<Segment> out;
    auto r = segment_steps(steps, 2, p, k, out);
    EXPECT_TRUE(r.ok());
    return out.size();
}

TEST(OptimalSegmenter, EveryEightConnectedChainUpToTenStepsInOneOctantPair) {
    std::size_t strictly_better = 0;
    for (Profile p : {Profile::eval8, Profile::grbl, Profile::marlin})
        for (int n = 1; n <= 10; ++n)
            for (unsigned bits = 0; bits < (1u << n); ++bits) {
                std::vector<Step> steps;
                for (int k = 0; k < n; ++k) steps.push_back(freeman_to_step((bits >> k) & 1u));
                const std::size_t opt = count(p, SegmenterKind::optimal, steps);
                const std::size_t greedy = count(p, SegmenterKind::greedy, steps);
                ASSERT_EQ(opt, brute_minimum(p, steps)) << profile_name(p) << " bits " << bits;
                ASSERT_LE(opt, greedy);
                strictly_better += opt < greedy;
            }
    // Greedy is not optimal (SPEC §4): the exhaustive set contains such chains.
    EXPECT_GT(strictly_better, 0u);
}

TEST(OptimalSegmenter, EveryFourConnectedChainUpToTenStepsInOneQuadrant) {
    for (Profile p : {Profile::eval4, Profile::patent})
        for (int n = 1; n <= 10; ++n)
            for (unsigned bits = 0; bits < (1u << n); ++bits) {
                std::vector<Step> steps;
                for (int k = 0; k < n; ++k) steps.push_back(freeman_to_step(((bits >> k) & 1u) * 2));
                const std::size_t opt = count(p, SegmenterKind::optimal, steps);
                ASSERT_EQ(opt, brute_minimum(p, steps)) << profile_name(p) << " bits " << bits;
                ASSERT_LE(opt, count(p, SegmenterKind::greedy, steps));
            }
}

TEST(OptimalSegmenter, RandomShortChainsAllDirections) {
    std::mt19937_64 rng(21);
    for (Profile p : kAllProfiles) {
        const bool eight = profile_eight_connected(p);
        for (int rep = 0; rep < 300; ++rep) {
            const int n = std::uniform_int_distribution<int>(1, 16)(rng);
            // three neighbouring codes, so that segments longer than one step occur
            const int base = std::uniform_int_distribution<int>(0, 7)(rng);
            std::vector<Step> steps;
            for (int k = 0; k < n; ++k) {
                int code = base + std::uniform_int_distribution<int>(0, 2)(rng);
                if (!eight) code = (code / 2) * 2;
                steps.push_back(freeman_to_step(code));
            }
            const std::size_t opt = count(p, SegmenterKind::optimal, steps);
            ASSERT_EQ(opt, brute_minimum(p, steps)) << profile_name(p) << " rep " << rep;
            ASSERT_LE(opt, count(p, SegmenterKind::greedy, steps));
        }
    }
}

TEST(OptimalSegmenter, NeverMoreSegmentsThanGreedyOnLongChains) {
    std::mt19937_64 rng(22);
    for (Profile p : kAllProfiles) {
        const bool eight = profile_eight_connected(p);
        for (int rep = 0; rep < 4; ++rep) {
            std::vector<Step> steps;
            while (steps.size() < 2000) {
                // polyline: random slopes, each drawn by eval4/eval8 at a random phase
                Point d{};
                d[0] = std::uniform_int_distribution<int>(1, 300)(rng);
                d[1] = std::uniform_int_distribution<int>(0, 300)(rng);
                if (rep % 2) d[1] = -d[1];
                const Profile draw = eight ? Profile::eval8 : Profile::eval4;
                Segment seg = default_segment(draw, d, 2);
                const auto ab = *phase_arguments(draw, seg, 2, 0);
                const PhaseRange r = phase_range(draw, ab.first, ab.second);
                seg.phase[0] = std::uniform_int_distribution<std::int64_t>(r.lo, r.hi - 1)(rng);
                expand_segment(draw, seg, 2, steps);
            }
            const std::size_t opt = count(p, SegmenterKind::optimal, steps);
            const std::size_t greedy = count(p, SegmenterKind::greedy, steps);
            ASSERT_LE(opt, greedy) << profile_name(p) << " rep " << rep;
        }
    }
}

// The optimal segmenter enumerates exact ends run by run; its count must equal
// a shortest path whose edges come from the letter-by-letter recognizer (every
// exact end within kOptimalWindow of each start, plus the greedy cut), on
// polylines with long lines and on near-lines with flipped ticks.
std::size_t reference_optimal(Profile p, const std::vector<Step>& steps) {
    const std::size_t n = steps.size();
    std::vector<std::size_t> dist(n + 1, n + 1);
    dist[0] = 0;
    std::vector<std::size_t> greedy_end(n, 0);
    const GreedySegmenter greedy(p, 2);
    for (std::size_t pos = 0; pos < n;)
        pos = greedy_end[pos] = pos + static_cast<std::size_t>(greedy.longest(
                                          std::span<const Step>(steps).subspan(pos)));
    SegmentRecognizer rec(p, 2);
    for (std::size_t s = 0; s < n; ++s) {
        if (greedy_end[s] != 0) dist[greedy_end[s]] = std::min(dist[greedy_end[s]], dist[s] + 1);
        rec.reset();
        const std::size_t lim = std::min(n, s + static_cast<std::size_t>(kOptimalWindow));
        for (std::size_t e = s; e < lim; ++e) {
            if (!rec.can_extend(steps[e]) || !rec.extend(steps[e])) break;
            if (rec.valid()) dist[e + 1] = std::min(dist[e + 1], dist[s] + 1);
        }
    }
    return dist[n];
}

TEST(OptimalSegmenter, RunByRunEnumerationMatchesLetterByLetter) {
    std::mt19937_64 rng(33);
    for (Profile p : {Profile::eval4, Profile::eval8, Profile::grbl, Profile::marlin}) {
        const bool eight = profile_eight_connected(p);
        for (int rep = 0; rep < 6; ++rep) {
            std::vector<Step> steps;
            while (steps.size() < 3000) {
                Point d{};
                const int span = rep % 3 == 0 ? 1500 : 60;
                d[0] = std::uniform_int_distribution<int>(-span, span)(rng);
                d[1] = std::uniform_int_distribution<int>(-span, span)(rng);
                if (d[0] == 0 && d[1] == 0) continue;
                Segment seg = default_segment(p, d, 2);
                const auto ab = *phase_arguments(p, seg, 2, 0);
                const PhaseRange r = phase_range(p, ab.first, ab.second);
                seg.phase[0] = std::uniform_int_distribution<std::int64_t>(r.lo, r.hi - 1)(rng);
                const std::size_t from = steps.size();
                expand_segment(p, seg, 2, steps);
                if (rep % 2 && steps.size() > from + 2) {  // flip one tick inside the line
                    const auto k = std::uniform_int_distribution<std::size_t>(from, steps.size() - 1)(rng);
                    if (eight) {
                        const Step t = static_cast<Step>(steps[k] ^ 0x4);  // toggle the y step
                        if (step_valid(t, 2) && (t & 0x8) == 0) steps[k] = t;
                    } else if (steps[k] == steps[from]) {
                        steps[k] = steps.back();
                    }
                }
            }
            ASSERT_EQ(count(p, SegmenterKind::optimal, steps), reference_optimal(p, steps))
                << profile_name(p) << " rep " << rep;
        }
    }
}

}  // namespace
}  // namespace stepzip
