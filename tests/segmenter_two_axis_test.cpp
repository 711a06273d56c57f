// The two-axis greedy path (src/segment/two_axis.cpp) against the
// letter-by-letter SegmentRecognizer and fit_segment: the same cut lengths at
// every start and the same segments, phases included, over every word of up
// to 14 letters in every sign combination and on random chains.
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

constexpr Profile kLinear[] = {Profile::eval4, Profile::eval8, Profile::grbl, Profile::marlin};

std::int64_t longest_letter_by_letter(Profile p, std::span<const Step> steps) {
    SegmentRecognizer rec(p, 2);
    std::int64_t best = 1;
    for (Step s : steps) {
        if (!rec.can_extend(s) || !rec.extend(s)) break;
        if (rec.valid()) best = rec.length();
    }
    return best;
}

// The greedy cut made with the reference pieces.
std::vector<Segment> reference_cut(Profile p, std::span<const Step> steps) {
    std::vector<Segment> out;
    for (std::size_t pos = 0; pos < steps.size();) {
        const auto rest = steps.subspan(pos);
        const auto m = static_cast<std::size_t>(longest_letter_by_letter(p, rest));
        const auto seg = fit_segment(p, rest.first(m), 2);
        EXPECT_TRUE(seg.has_value());
        if (!seg) return out;
        out.push_back(*seg);
        pos += m;
    }
    return out;
}

void check_chain(Profile p, const std::vector<Step>& steps, bool every_start) {
    const GreedySegmenter greedy(p, 2);
    std::vector<Segment> got;
    greedy.run(steps, got);
    ASSERT_EQ(got, reference_cut(p, steps)) << profile_name(p) << " " << steps.size() << " steps";
    if (!every_start) return;
    for (std::size_t s = 0; s < steps.size(); ++s) {
        const auto rest = std::span<const Step>(steps).subspan(s);
        ASSERT_EQ(greedy.longest(rest), longest_letter_by_letter(p, rest))
            << profile_name(p) << " start " << s;
    }
}

// The two step values of a word: eval4 an x-step and a y-step; 8-connected
// profiles an axis step and a diagonal it is a projection of. `which`
// enumerates the sign (and axis) choices.
std::pair<Step, Step> letters(Profile p, int which) {
    const int sx = (which & 1) ? -1 : 1, sy = (which & 2) ? -1 : 1;
    if (!profile_eight_connected(p)) return {make_step2(sx, 0), make_step2(0, sy)};
    const Step diag = make_step2(sx, sy);
    return {(which & 4) ? make_step2(0, sy) : make_step2(sx, 0), diag};
}

TEST(TwoAxisGreedy, EveryWordOfFourteenLettersMatchesLetterByLetter) {
    constexpr int n = 14;
    for (Profile p : kLinear)
        for (int which = 0; which < (profile_eight_connected(p) ? 8 : 4); ++which) {
            const auto [zero, one] = letters(p, which);
            const GreedySegmenter greedy(p, 2);
            std::vector<Step> steps(n);
            for (unsigned bits = 0; bits < (1u << n); ++bits) {
                for (int k = 0; k < n; ++k) steps[k] = ((bits >> k) & 1u) ? one : zero;
                ASSERT_EQ(greedy.longest(steps), longest_letter_by_letter(p, steps))
                    << profile_name(p) << " word " << bits << " letters " << which;
            }
            // whole cuts (phases included) on a sample of the words
            for (unsigned bits = 0; bits < (1u << n); bits += 97) {
                for (int k = 0; k < n; ++k) steps[k] = ((bits >> k) & 1u) ? one : zero;
                check_chain(p, steps, false);
                if (::testing::Test::HasFatalFailure()) return;
            }
        }
}

// Every prefix length of every 12-letter word, ended by a step that cannot
// join the segment (a sign change): the cut is the longest exact prefix of
// exactly that length, so each prefix's validity is checked on its own.
TEST(TwoAxisGreedy, EveryWordEndedAtEveryLengthMatchesLetterByLetter) {
    constexpr int n = 12;
    for (Profile p : kLinear)
        for (int which = 0; which < (profile_eight_connected(p) ? 8 : 4); ++which) {
            const auto [zero, one] = letters(p, which);
            // the opposite of the axis step: never joins either letter
            const Step stop = static_cast<Step>(zero ^ ((zero & 0x1u) ? 0x2u : 0x8u));
            const GreedySegmenter greedy(p, 2);
            std::vector<Step> steps;
            for (unsigned bits = 0; bits < (1u << n); ++bits)
                for (int j = 1; j <= n + 2; ++j) {
                    steps.clear();
                    for (int k = 0; k < j; ++k) steps.push_back(((bits >> (k % n)) & 1u) ? one : zero);
                    steps.push_back(stop);
                    ASSERT_EQ(greedy.longest(steps), longest_letter_by_letter(p, steps))
                        << profile_name(p) << " word " << bits << " length " << j;
                }
        }
}

// Random chains: lines at random phases (short and long, so that hulls grow
// and runs are long), perturbed ticks, runs of one code and every step value
// (sign changes, incompatible axis steps and diagonals).
std::vector<Step> random_chain(std::mt19937_64& rng, Profile p, std::size_t n) {
    const bool eight = profile_eight_connected(p);
    std::vector<Step> steps;
    auto random_step = [&] {
        for (;;) {
            const int dx = static_cast<int>(rng() % 3) - 1, dy = static_cast<int>(rng() % 3) - 1;
            if ((dx == 0 && dy == 0) || (!eight && dx != 0 && dy != 0)) continue;
            return make_step2(dx, dy);
        }
    };
    while (steps.size() < n) {
        const int kind = static_cast<int>(rng() % 4);
        if (kind == 0) {
            const int span = rng() % 5 == 0 ? 3000 : 40;
            Point d{};
            d[0] = std::uniform_int_distribution<int>(-span, span)(rng);
            d[1] = std::uniform_int_distribution<int>(-span, span)(rng);
            if (d[0] == 0 && d[1] == 0) d[0] = 1;
            Segment seg = default_segment(p, d, 2);
            const auto ab = *phase_arguments(p, seg, 2, 0);
            const PhaseRange r = phase_range(p, ab.first, ab.second);
            seg.phase[0] = std::uniform_int_distribution<std::int64_t>(r.lo, r.hi - 1)(rng);
            expand_segment(p, seg, 2, steps);
        } else if (kind == 1 && !steps.empty()) {
            for (int f = 0; f < 2; ++f) {
                const auto k = steps.size() - 1 - rng() % std::min<std::size_t>(steps.size(), 60);
                steps[k] = random_step();
            }
        } else if (kind == 2) {
            steps.insert(steps.end(), 1 + rng() % 30, random_step());
        } else {
            steps.push_back(random_step());
        }
    }
    steps.resize(n);
    return steps;
}

TEST(TwoAxisGreedy, RandomChainsMatchLetterByLetter) {
    std::mt19937_64 rng(23);
    for (Profile p : kLinear)
        for (int rep = 0; rep < 6; ++rep) {
            check_chain(p, random_chain(rng, p, 4000), rep < 2);
            if (::testing::Test::HasFatalFailure()) return;
        }
}

// Digitized lines of up to 600 letters with one letter flipped (a point
// just off the strip, or far off it), in both orders and both letter
// assignments: the strip turns and leaning points move letter by letter,
// and the longest exact prefix ends anywhere. Compared at several starts.
TEST(TwoAxisGreedy, PerturbedLinesMatchLetterByLetter) {
    std::mt19937_64 rng(31);
    for (Profile p : kLinear) {
        const auto [zero, one] = letters(p, static_cast<int>(rng() % 4));
        const GreedySegmenter greedy(p, 2);
        std::vector<Step> steps;
        for (int rep = 0; rep < 1500; ++rep) {
            const std::int64_t a = 1 + static_cast<std::int64_t>(rng() % 300), b = static_cast<std::int64_t>(rng() % 300);
            std::int64_t acc = static_cast<std::int64_t>(rng() % static_cast<std::uint64_t>(a + b));
            const std::size_t len = 13 + rng() % 600;
            std::vector<int> w;
            for (std::size_t i = 0; i < len; ++i) {
                acc += b;
                const bool y = acc >= a + b;
                if (y) acc -= a + b;
                w.push_back(y ? 1 : 0);
            }
            w[rng() % len] ^= 1;
            if (rng() % 2) std::reverse(w.begin(), w.end());
            const int swap = static_cast<int>(rng() % 2);
            steps.clear();
            for (int c : w) steps.push_back((c ^ swap) ? one : zero);
            for (int t = 0; t < 3; ++t) {
                const std::size_t at = t == 0 ? 0 : rng() % len;
                const auto rest = std::span<const Step>(steps).subspan(at);
                ASSERT_EQ(greedy.longest(rest), longest_letter_by_letter(p, rest))
                    << profile_name(p) << " line " << a << "/" << b << " start " << at;
            }
        }
    }
}

// Words (0^k 1)^c 0^j, ended by a step that cannot join, by the other
// letter or by the input's end: after the c-th 1 the prefixes stop being
// exact while the word stays a digital straight segment for up to k + 1
// more letters. longest() reads such stretches again from strips it kept
// every 16 letters (the last 8 of them) or, past those, from its 12th
// letter: with k up to 400 every case occurs, at every offset from a kept
// strip. The words where the last exact prefix lies more than 8 * 16 letters
// before the segment's end are counted to show that the last case occurs.
TEST(TwoAxisGreedy, LongStretchesWithoutExactPrefixMatchLetterByLetter) {
    std::mt19937_64 rng(37);
    int far = 0;
    for (Profile p : kLinear) {
        const auto [zero, one] = letters(p, static_cast<int>(rng() % 4));
        const Step stop = static_cast<Step>(zero ^ ((zero & 0x1u) ? 0x2u : 0x8u));
        const GreedySegmenter greedy(p, 2);
        std::vector<Step> steps;
        for (int rep = 0; rep < 600; ++rep) {
            const int k = rep < 40 ? rep + 1 : 1 + static_cast<int>(rng() % 400);
            const int c = 1 + static_cast<int>(rng() % 3);
            const int j = static_cast<int>(rng() % static_cast<std::uint64_t>(k + 3));
            const bool swap = rng() % 2 != 0;
            steps.clear();
            for (int t = 0; t < c; ++t) {
                steps.insert(steps.end(), static_cast<std::size_t>(k), swap ? one : zero);
                steps.push_back(swap ? zero : one);
            }
            steps.insert(steps.end(), static_cast<std::size_t>(j), swap ? one : zero);
            const int end = static_cast<int>(rng() % 3);
            if (end == 0) steps.push_back(stop);
            if (end == 1) steps.push_back(swap ? zero : one);
            const std::int64_t want = longest_letter_by_letter(p, steps);
            ASSERT_EQ(greedy.longest(steps), want)
                << profile_name(p) << " k " << k << " c " << c << " j " << j << " end " << end;
            SegmentRecognizer rec(p, 2);
            std::int64_t dss = 0;
            for (Step s : steps) {
                if (!rec.can_extend(s) || !rec.extend(s)) break;
                ++dss;
            }
            far += dss - want > 8 * 16 + 16 ? 1 : 0;
            check_chain(p, steps, false);
            if (::testing::Test::HasFatalFailure()) return;
        }
    }
    EXPECT_GT(far, 100);
}

// Long exact lines: one segment each, with the phase they were drawn at
// whenever that is the valid phase nearest the default (fit_segment decides).
TEST(TwoAxisGreedy, LongLinesAreOneSegment) {
    std::mt19937_64 rng(29);
    for (Profile p : kLinear)
        for (int rep = 0; rep < 40; ++rep) {
            Point d{};
            d[0] = std::uniform_int_distribution<int>(-20000, 20000)(rng);
            d[1] = std::uniform_int_distribution<int>(-20000, 20000)(rng);
            if (d[0] == 0) d[0] = 1;
            Segment seg = default_segment(p, d, 2);
            const auto ab = *phase_arguments(p, seg, 2, 0);
            const PhaseRange r = phase_range(p, ab.first, ab.second);
            seg.phase[0] = std::uniform_int_distribution<std::int64_t>(r.lo, r.hi - 1)(rng);
            std::vector<Step> steps;
            expand_segment(p, seg, 2, steps);
            std::vector<Segment> out;
            GreedySegmenter(p, 2).run(steps, out);
            ASSERT_EQ(out.size(), 1u) << profile_name(p) << " " << d[0] << " " << d[1];
            EXPECT_EQ(out[0], *fit_segment(p, steps, 2));
        }
}

}  // namespace
}  // namespace stepzip
