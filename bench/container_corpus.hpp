// Synthetic chain corpora for the container benchmark and layout measurements:
// traced contours (many small closed curves), plotter lines (vectors expanded
// by a controller's interpolator) and a random walk with momentum.
// Deterministic for a given seed.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "stepzip/chain.hpp"
#include "stepzip/interpolate/segment.hpp"
#include "stepzip/profile.hpp"

namespace stepzip::corpus {

inline int sgn(std::int64_t v) { return (v > 0) - (v < 0); }

/// Appends 8-connected steps from `p` to `q` (straight moves first, as a
/// naive tracer does) and moves `p` to `q`.
inline void walk_to(Chain& c, Point& p, std::int64_t qx, std::int64_t qy) {
    while (p[0] != qx || p[1] != qy) {
        const int dx = sgn(qx - p[0]), dy = sgn(qy - p[1]);
        c.steps.push_back(make_step2(dx, dy));
        p[0] += dx;
        p[1] += dy;
    }
}

/// Closed contours of wobbly ellipses, radii 3..`max_radius`, traced as
/// 8-connected chains; about `target_steps` steps in all.
inline std::vector<Chain> contours(std::uint64_t seed, std::size_t target_steps, double max_radius = 40) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Chain> out;
    std::size_t total = 0;
    while (total < target_steps) {
        const double cx = std::floor(u(rng) * 4000), cy = std::floor(u(rng) * 4000);
        const double rx = 3 + u(rng) * (max_radius - 3), ry = 3 + u(rng) * (max_radius - 3);
        const double a2 = u(rng) * 0.15, p2 = u(rng) * 6.28, a3 = u(rng) * 0.08, p3 = u(rng) * 6.28;
        Chain c;
        const int n = static_cast<int>(8 * (rx + ry)) + 16;
        auto at = [&](int k, std::int64_t& x, std::int64_t& y) {
            const double t = 6.283185307179586 * k / n;
            const double w = 1 + a2 * std::sin(2 * t + p2) + a3 * std::sin(3 * t + p3);
            x = std::llround(cx + rx * w * std::cos(t));
            y = std::llround(cy + ry * w * std::sin(t));
        };
        std::int64_t x, y;
        at(0, x, y);
        c.start[0] = x;
        c.start[1] = y;
        Point p = c.start;
        for (int k = 1; k <= n; ++k) {
            at(k % n, x, y);
            walk_to(c, p, x, y);
        }
        total += c.steps.size();
        if (!c.steps.empty()) out.push_back(std::move(c));
    }
    return out;
}

/// Plotter lines: polylines of random vectors (length up to `max_len`),
/// each vector expanded by profile `p`'s own interpolator at its default phase.
inline std::vector<Chain> plotter(std::uint64_t seed, std::size_t target_steps, Profile p = Profile::grbl,
                                  int max_len = 400) {
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<int> len(-max_len, max_len);
    std::uniform_int_distribution<int> nvec(3, 30);
    std::vector<Chain> out;
    std::size_t total = 0;
    while (total < target_steps) {
        Chain c;
        c.start[0] = len(rng) * 10;
        c.start[1] = len(rng) * 10;
        const int k = nvec(rng);
        for (int i = 0; i < k; ++i) {
            Point d{};
            d[0] = len(rng);
            d[1] = len(rng);
            if (d[0] == 0 && d[1] == 0) continue;
            expand_segment(p, default_segment(p, d, 2), 2, c.steps);
        }
        total += c.steps.size();
        if (!c.steps.empty()) out.push_back(std::move(c));
    }
    return out;
}

/// A random walk with momentum: keeps its Freeman direction with
/// probability 0.7, else turns by -1 or +1; chains of 50..2000 steps.
inline std::vector<Chain> random_walk(std::uint64_t seed, std::size_t target_steps) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::uniform_int_distribution<int> clen(50, 2000);
    std::vector<Chain> out;
    std::size_t total = 0;
    while (total < target_steps) {
        Chain c;
        c.start[0] = clen(rng);
        c.start[1] = clen(rng);
        int dir = static_cast<int>(u(rng) * 8);
        const int n = clen(rng);
        for (int i = 0; i < n; ++i) {
            const double r = u(rng);
            if (r > 0.85) dir = (dir + 1) & 7;
            else if (r > 0.7) dir = (dir + 7) & 7;
            c.steps.push_back(freeman_to_step(dir));
        }
        total += c.steps.size();
        out.push_back(std::move(c));
    }
    return out;
}

/// Freeman text of two-axis chains ("X0 Y0 CODES\n" per chain).
inline std::string freeman_text(const std::vector<Chain>& chains) {
    std::string s;
    for (const Chain& c : chains) {
        s += std::to_string(c.start[0]) + " " + std::to_string(c.start[1]) + " ";
        for (Step st : c.steps) s.push_back(static_cast<char>('0' + step_to_freeman(st)));
        s.push_back('\n');
    }
    return s;
}

}  // namespace stepzip::corpus
