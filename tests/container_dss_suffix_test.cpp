// The longest digital straight segment ending at a chain's last step
// (src/container/dss_suffix.hpp, the context of docs/FORMAT.md 1.11.4),
// against the definition: a word over two adjacent Freeman codes is a DSS iff
// it is balanced (any two factors of one length hold the second code a number
// of times that differs by at most one). Chains drawn from digital lines and
// circles of both connectivities, and random turns.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "../src/container/dss_suffix.hpp"

namespace stepzip::stz {
namespace {

// The definition, by brute force: at most two codes, adjacent (45 or 90
// degrees apart), and balanced.
bool is_dss(const std::vector<int>& w, std::size_t from, std::size_t to) {
    int c0 = -1, c1 = -1;
    for (std::size_t i = from; i < to; ++i) {
        if (c0 < 0 || w[i] == c0) c0 = w[i];
        else if (c1 < 0 || w[i] == c1) c1 = w[i];
        else return false;
    }
    if (c1 < 0) return true;
    const int t = (c1 - c0) & 7;
    if (t != 1 && t != 7 && t != 2 && t != 6) return false;
    const std::size_t n = to - from;
    for (std::size_t len = 1; len < n; ++len) {
        int lo = 1 << 30, hi = -1;
        for (std::size_t s = from; s + len <= to; ++s) {
            int ones = 0;
            for (std::size_t i = s; i < s + len; ++i) ones += w[i] == c1;
            lo = std::min(lo, ones);
            hi = std::max(hi, ones);
        }
        if (hi - lo > 1) return false;
    }
    return true;
}

// The longest DSS suffix of w[0, end), by the definition.
std::size_t longest_suffix(const std::vector<int>& w, std::size_t end) {
    std::size_t k = 0;
    while (k < end && is_dss(w, end - k - 1, end)) ++k;
    return k;
}

// Steps of a digital circle (8-connected: one code per step toward the
// nearest next pixel; 4-connected: a step along one axis at a time).
std::vector<int> circle_steps(double r, bool four, double turns) {
    static const int dx[8] = {1, 1, 0, -1, -1, -1, 0, 1}, dy[8] = {0, 1, 1, 1, 0, -1, -1, -1};
    std::vector<int> out;
    long x = std::lround(r), y = 0;
    const int steps = static_cast<int>(turns * 2 * 3.14159265 * r * 2);
    for (int s = 0; s < steps; ++s) {
        int best = -1;
        double best_err = 1e9;
        for (int c = 0; c < 8; c += four ? 2 : 1) {
            const double nx = static_cast<double>(x + dx[c]), ny = static_cast<double>(y + dy[c]);
            // counter-clockwise: the next point must advance in angle
            if (nx * static_cast<double>(y) - ny * static_cast<double>(x) > 0) continue;
            const double err = std::fabs(std::hypot(nx, ny) - r);
            if (err < best_err) best_err = err, best = c;
        }
        out.push_back(best);
        x += dx[best];
        y += dy[best];
    }
    return out;
}

// A word of codes, its longest DSS suffix after every step checked, and
// every next code's status against the definition.
void check_chain(const std::vector<int>& w) {
    DssSuffix d;
    d.start_chain();
    std::vector<int> prefix;
    for (std::size_t i = 0; i < w.size(); ++i) {
        const DssWord& before = d.word();
        for (int c = 0; c < 8; ++c) {
            if (before.len == 0) break;
            std::vector<int> ext(w.begin() + static_cast<std::ptrdiff_t>(i - static_cast<std::size_t>(before.len)),
                                 w.begin() + static_cast<std::ptrdiff_t>(i));
            ext.push_back(c);
            ASSERT_EQ(before.status(c) > 0, is_dss(ext, 0, ext.size())) << "step " << i << " code " << c;
        }
        d.push(w[i]);
        ASSERT_EQ(static_cast<std::size_t>(d.word().len), longest_suffix(w, i + 1)) << "step " << i;
    }
}

TEST(DssSuffix, LongestSuffixAndNextCodesAgreeWithTheDefinitionOnCircles) {
    for (bool four : {false, true})
        for (double r : {3.0, 11.5, 40.0}) {
            SCOPED_TRACE("radius " + std::to_string(r) + (four ? " 4-connected" : " 8-connected"));
            const auto w = circle_steps(r, four, r > 20 ? 0.3 : 1.0);
            ASSERT_GT(w.size(), 10u);
            check_chain(w);
        }
}

TEST(DssSuffix, LongestSuffixAgreesWithTheDefinitionOnRandomChains) {
    std::mt19937_64 rng(7);
    for (int chain = 0; chain < 40; ++chain) {
        // stretches of two adjacent codes at a random rate, then a turn
        std::vector<int> w;
        int c0 = static_cast<int>(rng() % 8);
        while (w.size() < 150) {
            const int t = chain % 2 ? 2 : 1;
            const int c1 = (c0 + (rng() % 2 ? t : 8 - t)) & 7;
            const double rate = static_cast<double>(rng() % 1000) / 1000.0;
            const int n = 1 + static_cast<int>(rng() % 40);
            double acc = 0;
            for (int i = 0; i < n; ++i) {
                acc += rate;
                if (acc >= 1) {
                    acc -= 1;
                    w.push_back(c1);
                } else {
                    w.push_back(c0);
                }
            }
            if (rng() % 4 == 0) w.push_back(static_cast<int>(rng() % 8));
            c0 = rng() % 3 ? c0 : c1;
        }
        check_chain(w);
    }
}

// A straight run longer than the cap: the word stays within it, and the
// suffix is found again (no quadratic reading back on every step).
TEST(DssSuffix, WordsStayWithinTheCap) {
    DssSuffix d;
    d.start_chain();
    for (int i = 0; i < 5 * DssSuffix::kCap; ++i) {
        d.push(i % 3 == 0 ? 1 : 0);
        ASSERT_LT(d.word().len, DssSuffix::kCap);
        ASSERT_GE(d.word().len, std::min(i + 1, DssSuffix::kCap / 2));
    }
}

// The state the weight set is selected by: a run, then the two codes'
// statuses as seen from the last one.
TEST(DssSuffix, StateNamesRunsAndTheOtherCodesSide) {
    DssSuffix d;
    d.start_chain();
    EXPECT_EQ(dss_state(d.word(), 0), 0);
    for (int i = 0; i < 5; ++i) d.push(0);
    EXPECT_EQ(dss_state(d.word(), 0), 1);
    d.push(1);  // 000001: then 0 stays inside the strip, 1 ends the word
    EXPECT_EQ(d.word().status(0), 2);
    EXPECT_EQ(d.word().status(1), 0);
    // from code 1, code 0 is a turn of -45 degrees (c = 1)
    EXPECT_EQ(dss_state(d.word(), 1), 2 + (1 * 3 + d.word().status(1)) * 3 + d.word().status(0));
    EXPECT_LT(dss_state(d.word(), 1), kDssStates);
}

}  // namespace
}  // namespace stepzip::stz
