// PatentRecognizer against brute force: a prefix is one exact segment under
// the `patent` profile iff some phase in phase_range() reproduces it by the
// forward mode (Fig. 4); the hard limits refuse what no segment can hold.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "stepzip/interpolate/segment.hpp"
#include "stepzip/profile.hpp"
#include "stepzip/segment/recognizer.hpp"

namespace stepzip {
namespace {

bool brute_exact(const std::vector<Step>& steps) {
    Point d{};
    for (Step s : steps) apply_step(d, s, 2);
    Segment seg = default_segment(Profile::patent, d, 2);
    if (!check_segment(Profile::patent, seg, 2)) return false;
    const auto ab = *phase_arguments(Profile::patent, seg, 2, 0);
    const PhaseRange r = phase_range(Profile::patent, ab.first, ab.second);
    std::vector<Step> out;
    for (std::int64_t f = r.lo; f < r.hi; ++f) {
        seg.phase[0] = f;
        out.clear();
        expand_segment(Profile::patent, seg, 2, out);
        if (out == steps) return true;
    }
    return false;
}

// Every word of up to 11 steps, in every quadrant: valid() and
// longest_valid() after each step agree with brute force.
TEST(PatentRecognizer, EveryShortWordEveryQuadrant) {
    for (int sx : {-1, 1})
        for (int sy : {-1, 1})
            for (int n = 1; n <= 11; ++n)
                for (unsigned bits = 0; bits < (1u << n); ++bits) {
                    PatentRecognizer rec;
                    std::vector<Step> steps;
                    std::int64_t longest = 0;
                    for (int k = 0; k < n; ++k) {
                        const Step s = ((bits >> k) & 1u) ? make_step2(0, sy) : make_step2(sx, 0);
                        ASSERT_TRUE(rec.can_extend(s));
                        EXPECT_TRUE(rec.extend(s));
                        steps.push_back(s);
                        const bool exact = brute_exact(steps);
                        ASSERT_EQ(rec.valid(), exact) << "bits " << bits << " length " << k + 1;
                        if (exact) longest = k + 1;
                        ASSERT_EQ(rec.longest_valid(), longest);
                    }
                    EXPECT_EQ(rec.length(), n);
                    EXPECT_EQ(rec.delta()[0], sx * (n - __builtin_popcount(bits)));
                }
}

TEST(PatentRecognizer, HardLimits) {
    PatentRecognizer rec;
    EXPECT_EQ(rec.longest_valid(), 0);
    EXPECT_FALSE(rec.valid());
    EXPECT_FALSE(rec.can_extend(make_step2(1, 1)));  // one axis per step
    ASSERT_TRUE(rec.extend(make_step2(1, 0)));
    ASSERT_TRUE(rec.extend(make_step2(0, -1)));
    EXPECT_FALSE(rec.can_extend(make_step2(-1, 0)));  // one sign per axis
    EXPECT_FALSE(rec.can_extend(make_step2(0, 1)));
    EXPECT_TRUE(rec.can_extend(make_step2(1, 0)));
    rec.reset();
    EXPECT_EQ(rec.length(), 0);
    EXPECT_TRUE(rec.can_extend(make_step2(-1, 0)));
    // The cap: extend() says no once kPatentMaxSegment steps are read.
    for (std::int64_t k = 1; k <= kPatentMaxSegment; ++k) {
        ASSERT_TRUE(rec.can_extend(make_step2(1, 0)));
        EXPECT_EQ(rec.extend(make_step2(1, 0)), k < kPatentMaxSegment);
    }
    EXPECT_FALSE(rec.can_extend(make_step2(1, 0)));
    EXPECT_TRUE(rec.valid());
    EXPECT_EQ(rec.longest_valid(), kPatentMaxSegment);
}

// make_recognizer() picks the patent recognizer for `patent` only; the two
// kinds agree with fit_segment() on random chains.
TEST(PatentRecognizer, MakeRecognizerAndFitAgree) {
    std::mt19937 rng(9);
    for (Profile p : {Profile::patent, Profile::eval4}) {
        ProfileRecognizer any = make_recognizer(p, 2);
        EXPECT_EQ(std::holds_alternative<PatentRecognizer>(any), p == Profile::patent);
        for (int trial = 0; trial < 300; ++trial) {
            std::vector<Step> steps;
            std::visit([](auto& r) { r.reset(); }, any);
            const int slope = static_cast<int>(rng() % 7);
            for (int k = 0; k < 40; ++k) {
                const Step s = static_cast<int>(rng() % 8) < slope ? make_step2(0, 1) : make_step2(1, 0);
                const bool ok = std::visit([&](auto& r) { return r.can_extend(s); }, any);
                if (!ok) break;
                std::visit([&](auto& r) { r.extend(s); }, any);
                steps.push_back(s);
                const bool valid = std::visit([](auto& r) { return r.valid(); }, any);
                ASSERT_EQ(valid, fit_segment(p, steps, 2).has_value());
            }
        }
    }
}

// read() takes what can_extend() and extend() take, and longest_valid()
// after it is the longest prefix fit_segment() fits, on words much longer
// than their segments (most candidates rejected by the last contradicting
// pair) with a change of sign or a diagonal step here and there.
TEST(PatentRecognizer, ReadAgreesWithExtendAndFit) {
    std::mt19937 rng(17);
    PatentRecognizer rec, one_by_one;
    for (int trial = 0; trial < 400; ++trial) {
        const int sx = rng() % 2 ? 1 : -1, sy = rng() % 2 ? 1 : -1;
        const int slope = 1 + static_cast<int>(rng() % 14);
        std::vector<Step> steps;
        for (int k = 0; k < 150; ++k) {
            const unsigned r = rng() % 1000;
            if (r < 3) steps.push_back(make_step2(-sx, 0));
            else if (r < 5) steps.push_back(make_step2(sx, sy));
            else steps.push_back(static_cast<int>(rng() % 16) < slope ? make_step2(0, sy) : make_step2(sx, 0));
        }
        one_by_one.reset();
        for (Step s : steps) {
            if (!one_by_one.can_extend(s)) break;
            one_by_one.extend(s);
        }
        ASSERT_EQ(rec.read(steps), one_by_one.length());
        ASSERT_EQ(rec.delta(), one_by_one.delta());
        std::int64_t longest = 0;
        for (std::int64_t m = 1; m <= rec.length(); ++m)
            if (fit_segment(Profile::patent, std::span<const Step>(steps.data(), static_cast<std::size_t>(m)), 2))
                longest = m;
        ASSERT_EQ(rec.longest_valid(), longest) << "trial " << trial;
        ASSERT_EQ(one_by_one.longest_valid(), longest) << "trial " << trial;
    }
}

}  // namespace
}  // namespace stepzip
