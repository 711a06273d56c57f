// stepzip — axis rates and accelerations read out of a timed chain
// (include/stepzip/timed.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <set>
#include <utility>
#include <vector>

#include "stepzip/timed.hpp"

namespace stepzip {

namespace {

constexpr std::size_t kWindow = 128;
constexpr double kMaxRms = 0.6;
constexpr double kQuantile = 0.9;

// Least-squares parabola s = c0 + c1·t + c2·t² through (t[k], s[k]), k in [a, b); false when singular.
bool fit_quadratic(const std::vector<double>& t, const std::vector<double>& s, std::size_t a, std::size_t b,
                   std::array<double, 3>& c) {
    double m[3][4] = {};
    for (std::size_t k = a; k < b; ++k) {
        const double p[3] = {1.0, t[k], t[k] * t[k]};
        for (int r = 0; r < 3; ++r) {
            for (int q = 0; q < 3; ++q) m[r][q] += p[r] * p[q];
            m[r][3] += p[r] * s[k];
        }
    }
    for (int col = 0; col < 3; ++col) {
        int piv = col;
        for (int r = col + 1; r < 3; ++r)
            if (std::fabs(m[r][col]) > std::fabs(m[piv][col])) piv = r;
        if (std::fabs(m[piv][col]) < 1e-300) return false;
        for (int q = 0; q < 4; ++q) std::swap(m[col][q], m[piv][q]);
        for (int r = 0; r < 3; ++r) {
            if (r == col) continue;
            const double f = m[r][col] / m[col][col];
            for (int q = col; q < 4; ++q) m[r][q] -= f * m[col][q];
        }
    }
    for (int r = 0; r < 3; ++r) c[static_cast<std::size_t>(r)] = m[r][3] / m[r][r];
    return true;
}

// Least-squares parabola k = c0 + c1·u + c2·u² through (u_j, j); false when singular.
bool fit_parabola(const std::array<double, kWindow>& u, std::array<double, 3>& c, double& rms) {
    const std::vector<double> t(u.begin(), u.end());
    std::vector<double> k(kWindow);
    for (std::size_t j = 0; j < kWindow; ++j) k[j] = static_cast<double>(j);
    if (!fit_quadratic(t, k, 0, kWindow, c)) return false;
    double ss = 0;
    for (std::size_t j = 0; j < kWindow; ++j) {
        const double e = static_cast<double>(j) - (c[0] + c[1] * u[j] + c[2] * u[j] * u[j]);
        ss += e * e;
    }
    rms = std::sqrt(ss / kWindow);
    return true;
}

}  // namespace

std::vector<AxisMotion> estimate_axis_motion(const Chain& chain, double tick_seconds) {
    std::vector<AxisMotion> out(static_cast<std::size_t>(std::max(chain.axes, 1)));
    for (int axis = 1; axis < chain.axes; ++axis) {
        std::vector<std::uint64_t> tick;
        std::vector<int> dir;
        for (std::size_t k = 0; k < chain.steps.size(); ++k) {
            const int d = step_axis(chain.steps[k], axis);
            if (d == 0) continue;
            tick.push_back(k);
            dir.push_back(d);
        }
        AxisMotion& m = out[static_cast<std::size_t>(axis)];
        m.steps = tick.size();
        std::vector<double> samples;
        for (std::size_t i = 0; i + kWindow <= tick.size(); i += kWindow / 2) {
            const auto span = static_cast<double>(tick[i + kWindow - 1] - tick[i]);
            if (span <= 0) continue;
            bool ok = true;
            for (std::size_t j = i + 1; j < i + kWindow && ok; ++j)
                ok = dir[j] == dir[i] && static_cast<double>(tick[j] - tick[j - 1]) * (kWindow - 1) <= 3 * span;
            if (!ok) continue;
            const double secs = span * tick_seconds;
            m.max_rate = std::max(m.max_rate, static_cast<double>(kWindow - 1) / secs);
            const double mid = static_cast<double>(tick[i]) + span / 2;
            std::array<double, kWindow> u{};
            for (std::size_t j = 0; j < kWindow; ++j) u[j] = (static_cast<double>(tick[i + j]) - mid) * tick_seconds;
            std::array<double, 3> c{};
            double rms = 0;
            if (fit_parabola(u, c, rms) && rms <= kMaxRms) samples.push_back(std::fabs(2 * c[2]));
        }
        m.windows = samples.size();
        if (!samples.empty()) {
            const auto q = static_cast<std::size_t>(kQuantile * static_cast<double>(samples.size() - 1));
            std::nth_element(samples.begin(), samples.begin() + static_cast<std::ptrdiff_t>(q), samples.end());
            m.acceleration = samples[q];
        }
    }
    return out;
}

}  // namespace stepzip

namespace stepzip {

TimedPath timed_path(const Chain& timed) {
    TimedPath out;
    out.path.axes = std::max(timed.axes - 1, 1);
    for (int i = 1; i < timed.axes; ++i) out.path.start[static_cast<std::size_t>(i - 1)] = timed.start[static_cast<std::size_t>(i)];
    for (std::size_t k = 0; k < timed.steps.size(); ++k) {
        const auto s = static_cast<Step>(timed.steps[k] >> 2);  // time is axis 0
        if (s == 0) continue;
        out.path.steps.push_back(s);
        out.ticks.push_back(k);
    }
    return out;
}

namespace {

// Speed of the parabola c where it passes position `at` while rising (where
// c1 + 2·c2·t > 0): the square root of its discriminant there; 0 when it
// never reaches `at` (its turning point: a start from rest or a stop).
double speed_at(const std::array<double, 3>& c, double at) {
    const double disc = c[1] * c[1] - 4 * c[2] * (c[0] - at);
    return disc > 0 ? std::sqrt(disc) : 0;
}

constexpr std::size_t kMinRamp = 6;
constexpr double kCruiseShare = 0.97;
// Entry and exit at this share of the cruise or more: no ramp to speak of
// (chosen on generated logs, docs/benchmarks.md "Timed streams: the moves
// of a log").
constexpr double kFlatShare = 0.85;

// The first of the speeds `v` that reaches `level` (v.size() when none) and
// one past the last (0 when none).
std::pair<std::size_t, std::size_t> reaching(const std::vector<double>& v, double level) {
    std::size_t first = 0, last = v.size();
    while (first < v.size() && v[first] < level) ++first;
    while (last > 0 && v[last - 1] < level) --last;
    return {first, last};
}

}  // namespace

MoveSpeeds move_speeds(std::span<const std::uint64_t> ticks, double length, double tick_seconds) {
    MoveSpeeds out;
    const std::size_t n = ticks.size();
    if (n < 2 || !(length > 0) || !(tick_seconds > 0)) return out;
    std::vector<double> t(n), s(n);
    for (std::size_t k = 0; k < n; ++k) {
        t[k] = (static_cast<double>(ticks[k] - ticks[0]) + 0.5) * tick_seconds;
        s[k] = static_cast<double>(k + 1) * length / static_cast<double>(n);
    }
    const std::size_t w = std::clamp<std::size_t>(n / 16, 2, 16);
    std::vector<double> v(n);
    double fastest = 0;
    for (std::size_t k = 0; k < n; ++k) {
        const std::size_t a = k >= w ? k - w : 0, b = std::min(n - 1, k + w);
        v[k] = t[b] > t[a] ? (s[b] - s[a]) / (t[b] - t[a]) : 0;
        fastest = std::max(fastest, v[k]);
    }
    // The cruise: the mean speed over the plateau, from the first to the
    // last step whose local speed reaches kCruiseShare of the 90th
    // percentile of them, when it spans more than 4 windows; else the fastest
    // window. (A constant-rate move's stepper segments run a few per cent
    // apart, and its fastest window overstated the rate by 4-10 % on
    // generated logs: docs/benchmarks.md "Timed streams: the moves of a log".)
    std::vector<double> sorted = v;
    const std::size_t q = 9 * (n - 1) / 10;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(q), sorted.end());
    const auto [first, last] = reaching(v, kCruiseShare * sorted[q]);
    out.cruise = fastest;
    if (last > first + 4 * w && t[last - 1] > t[first]) out.cruise = (s[last - 1] - s[first]) / (t[last - 1] - t[first]);
    // The ramps: up to and down from the fastest window's kCruiseShare.
    const auto [up, down] = reaching(v, kCruiseShare * fastest);
    out.entry = v.front();
    out.exit = v.back();
    double weighted = 0;
    std::array<double, 3> c{};
    if (up + 1 >= kMinRamp && fit_quadratic(t, s, 0, up + 1, c) && c[2] > 0) {
        out.entry = speed_at(c, 0);
        weighted += 2 * c[2] * static_cast<double>(up + 1);
        out.ramp_steps += up + 1;
    }
    if (down > 0 && n - (down - 1) >= kMinRamp && fit_quadratic(t, s, down - 1, n, c) && c[2] < 0) {
        out.exit = speed_at(c, length);
        weighted += -2 * c[2] * static_cast<double>(n - (down - 1));
        out.ramp_steps += n - (down - 1);
    }
    if (out.ramp_steps != 0) out.acceleration = weighted / static_cast<double>(out.ramp_steps);
    // A move that starts and ends near its cruise speed (a constant-speed
    // move, stepper segments a few per cent apart): its mean speed, and no
    // ramps (what reached the fastest window late was a faster segment: its
    // parabola read a few per cent of the planner's acceleration, or less).
    if (out.entry >= kFlatShare * out.cruise && out.exit >= kFlatShare * out.cruise && t[n - 1] > t[0]) {
        out.cruise = (s[n - 1] - s[0]) / (t[n - 1] - t[0]);
        out.acceleration = 0;
        out.ramp_steps = 0;
    }
    return out;
}

}  // namespace stepzip

namespace stepzip {

namespace {

// How far the points strictly between pts[a] and pts[b] lie from the
// segment between them (each point from its projection, clamped to the
// segment): the largest squared distance and the first point at it (-1 and
// a when there is no point between), and the sum of the squares. With a
// finite `limit`, it stops as soon as base + the sum so far reaches it
// (`cut` then set): the whole sum would reach it too, since every term is
// at least 0 and rounded addition is monotonic.
struct Deviation {
    double worst = -1;
    std::size_t at = 0;
    double sum = 0;
    bool cut = false;
};
Deviation deviation(const std::vector<Point>& pts, int axes, std::size_t a, std::size_t b, double base = 0,
                    double limit = std::numeric_limits<double>::infinity()) {
    // pts[k] - pts[a] per axis, and a dot product of two such offsets
    auto offset = [&](std::size_t k) {
        std::array<double, kMaxAxes> o{};
        for (int i = 0; i < axes; ++i)
            o[static_cast<std::size_t>(i)] = static_cast<double>(pts[k][static_cast<std::size_t>(i)] - pts[a][static_cast<std::size_t>(i)]);
        return o;
    };
    auto dot = [axes](const std::array<double, kMaxAxes>& x, const std::array<double, kMaxAxes>& y) {
        double r = 0;
        for (int i = 0; i < axes; ++i) r += x[static_cast<std::size_t>(i)] * y[static_cast<std::size_t>(i)];
        return r;
    };
    Deviation d;
    d.at = a;
    const std::array<double, kMaxAxes> dir = offset(b);
    const double len2 = dot(dir, dir);
    for (std::size_t k = a + 1; k < b; ++k) {
        const std::array<double, kMaxAxes> v = offset(k);
        const double t = len2 > 0 ? std::clamp(dot(v, dir) / len2, 0.0, 1.0) : 0.0;
        double d2 = 0;
        for (int i = 0; i < axes; ++i) {
            const auto u = static_cast<std::size_t>(i);
            const double e = v[u] - t * dir[u];
            d2 += e * e;
        }
        d.sum += d2;
        if (d2 > d.worst) {
            d.worst = d2;
            d.at = k;
        }
        if (base + d.sum >= limit) {
            d.cut = true;
            break;
        }
    }
    return d;
}

// Douglas-Peucker: the points kept (first and last included), in order, by
// an explicit stack of spans.
std::vector<std::size_t> douglas_peucker(const std::vector<Point>& pts, int axes, double tolerance) {
    std::vector<char> keep(pts.size(), 0);
    keep.front() = keep.back() = 1;
    std::vector<std::pair<std::size_t, std::size_t>> todo{{0, pts.size() - 1}};
    while (!todo.empty()) {
        const auto [a, b] = todo.back();
        todo.pop_back();
        if (b <= a + 1) continue;
        const Deviation d = deviation(pts, axes, a, b);
        if (d.worst > tolerance * tolerance) {
            keep[d.at] = 1;
            todo.emplace_back(a, d.at);
            todo.emplace_back(d.at, b);
        }
    }
    std::vector<std::size_t> v;
    for (std::size_t k = 0; k < pts.size(); ++k)
        if (keep[k]) v.push_back(k);
    return v;
}

// Douglas-Peucker puts a corner on the point farthest from the chord, which
// on a controller's path (a minor axis a step off the digital line) is
// often a step or two beside the move's end, and then cuts the moves next
// to it once more. Each round moves every inner corner in turn, within
// kCornerReach points, to where the squared distances of the points of its
// two stretches from their chords add up to the least (the first such
// point), then drops every corner whose neighbours' chord keeps the points
// between within the tolerance; rounds repeat until nothing moves (at most
// kCornerRounds). Chosen on generated logs, docs/benchmarks.md "Timed
// streams: the moves of a log".
constexpr std::size_t kCornerReach = 10;
constexpr int kCornerRounds = 12;

// The place of a corner between corners a and c, searched from `from`.
// A place's cost stops being summed once it cannot beat the best so far
// (the stretch after the place first: its first points, near the corner,
// deviate the most); the same place is chosen as when every cost is whole.
std::size_t best_corner(const std::vector<Point>& pts, int axes, std::size_t a, std::size_t from, std::size_t c) {
    const std::size_t lo = std::max(a + 1, from > kCornerReach ? from - kCornerReach : 0);
    const std::size_t hi = std::min(c - 1, from + kCornerReach);
    double limit = std::numeric_limits<double>::infinity();  // best - 1e-9
    std::size_t at = from;
    for (std::size_t k = lo; k <= hi; ++k) {
        const Deviation after = deviation(pts, axes, k, c, 0, limit);
        if (after.cut) continue;
        const Deviation before = deviation(pts, axes, a, k, after.sum, limit);
        if (before.cut) continue;
        const double cost = before.sum + after.sum;
        if (cost < limit) {
            limit = cost - 1e-9;
            at = k;
        }
    }
    return at;
}

void settle_corners(const std::vector<Point>& pts, int axes, double tolerance, std::vector<std::size_t>& v) {
    // (a, from, c) of the searches that left their corner in place: the
    // same search again would too
    std::set<std::array<std::size_t, 3>> settled;
    // the chords found too far from their points to drop the corner between
    std::set<std::array<std::size_t, 2>> needed;
    for (int round = 0; round < kCornerRounds; ++round) {
        const std::vector<std::size_t> before = v;
        for (std::size_t i = 1; i + 1 < v.size(); ++i) {
            const std::array<std::size_t, 3> key{v[i - 1], v[i], v[i + 1]};
            if (settled.contains(key)) continue;
            v[i] = best_corner(pts, axes, v[i - 1], v[i], v[i + 1]);
            if (v[i] == key[1]) settled.insert(key);
        }
        std::vector<std::size_t> kept{v.front()};
        for (std::size_t i = 1; i < v.size(); ++i) {
            // (worst is -1 when no point lies between: dropped as well)
            if (i + 1 < v.size()) {
                const std::array<std::size_t, 2> chord{kept.back(), v[i + 1]};
                if (!needed.contains(chord)) {
                    if (deviation(pts, axes, chord[0], chord[1]).worst <= tolerance * tolerance) continue;
                    needed.insert(chord);
                }
            }
            kept.push_back(v[i]);
        }
        v = std::move(kept);
        if (v == before) return;
    }
}

// Two neighbouring corners a step or two off their moves' ends (a short
// move between, both its ends beside the truth) hold each other in place:
// moving either alone costs more. Each round therefore moves every pair of
// neighbouring corners together, each within kPairReach points, to where
// the squared distances of the points of their three stretches from their
// chords add up to the least, when that is less than where they are (by
// more than 1e-9; places tried by the first corner's offset, then the
// second's, each from -kPairReach up, a later one kept only when less by
// more than 1e-9; none that lets a stretch stray farther than the
// tolerance from its chord), until nothing moves (at most kCornerRounds).
// kPairReach chosen on the generated logs (1, 2 and 3 tried),
// docs/benchmarks.md "Timed streams: neighbouring corners moved together".
constexpr std::ptrdiff_t kPairReach = 2;

void settle_pairs(const std::vector<Point>& pts, int axes, double tolerance, std::vector<std::size_t>& v) {
    // The three stretches' sum (stopped at `limit`, then `cut`) and, when
    // not cut, the largest squared distance of their points.
    struct Cost {
        double sum = 0, worst = -1;
        bool cut = false;
    };
    auto cost = [&](std::size_t a, std::size_t p, std::size_t q, std::size_t c, double limit) {
        const Deviation x = deviation(pts, axes, a, p, 0, limit);
        const Deviation y = x.cut ? x : deviation(pts, axes, p, q, x.sum, limit);
        const Deviation z = y.cut ? y : deviation(pts, axes, q, c, x.sum + y.sum, limit);
        return Cost{x.sum + y.sum + z.sum, std::max({x.worst, y.worst, z.worst}), z.cut};
    };
    // (a, p, q, c) of the searches that left both corners in place
    std::set<std::array<std::size_t, 4>> settled;
    for (int round = 0; round < kCornerRounds; ++round) {
        bool moved = false;
        for (std::size_t i = 1; i + 2 < v.size(); ++i) {
            const std::array<std::size_t, 4> key{v[i - 1], v[i], v[i + 1], v[i + 2]};
            if (settled.contains(key)) continue;
            const auto [a, p, q, c] = key;
            double limit = cost(a, p, q, c, std::numeric_limits<double>::infinity()).sum - 1e-9;
            std::size_t bp = p, bq = q;
            for (std::ptrdiff_t dp = -kPairReach; dp <= kPairReach; ++dp)
                for (std::ptrdiff_t dq = -kPairReach; dq <= kPairReach; ++dq) {
                    const auto np = static_cast<std::ptrdiff_t>(p) + dp, nq = static_cast<std::ptrdiff_t>(q) + dq;
                    if ((dp == 0 && dq == 0) || np <= static_cast<std::ptrdiff_t>(a) || nq <= np ||
                        nq >= static_cast<std::ptrdiff_t>(c))
                        continue;
                    const Cost x = cost(a, static_cast<std::size_t>(np), static_cast<std::size_t>(nq), c, limit);
                    if (!x.cut && x.sum < limit && x.worst <= tolerance * tolerance) {
                        limit = x.sum - 1e-9;
                        bp = static_cast<std::size_t>(np);
                        bq = static_cast<std::size_t>(nq);
                    }
                }
            if (bp == p && bq == q) {
                settled.insert(key);
            } else {
                v[i] = bp;
                v[i + 1] = bq;
                moved = true;
            }
        }
        if (!moved) return;
    }
}

}  // namespace

std::vector<TimedMove> timed_moves(const TimedPath& tp, double tick_seconds, double tolerance) {
    std::vector<TimedMove> out;
    const Chain& path = tp.path;
    const int axes = path.axes;
    const std::vector<Point> pts = chain_points(path);
    if (pts.size() < 2) return out;
    std::vector<std::size_t> corners = douglas_peucker(pts, axes, tolerance);
    settle_corners(pts, axes, tolerance, corners);
    settle_pairs(pts, axes, tolerance, corners);
    for (std::size_t j = 1; j < corners.size(); ++j) {
        const std::size_t a = corners[j - 1], b = corners[j];
        TimedMove m;
        m.first = a;
        m.last = b - 1;  // point b is after step b - 1
        m.first_tick = tp.ticks[m.first];
        m.last_tick = tp.ticks[m.last];
        int lead = 0;
        double len2 = 0;
        for (int i = 0; i < axes; ++i) {
            const auto u = static_cast<std::size_t>(i);
            m.delta[u] = pts[b][u] - pts[a][u];
            len2 += static_cast<double>(m.delta[u]) * static_cast<double>(m.delta[u]);
            if (std::llabs(m.delta[u]) > std::llabs(m.delta[static_cast<std::size_t>(lead)])) lead = i;
        }
        m.length = std::sqrt(len2);
        std::vector<std::uint64_t> lead_ticks;
        for (std::size_t k = m.first; k <= m.last; ++k)
            if (step_axis(path.steps[k], lead) != 0) lead_ticks.push_back(tp.ticks[k]);
        m.speeds = move_speeds(lead_ticks, m.length, tick_seconds);
        out.push_back(m);
    }
    return out;
}

TimedReading read_timed(const Chain& timed_chain, double tick_seconds, double tolerance) {
    TimedReading r;
    r.path = timed_path(timed_chain);
    r.moves = timed_moves(r.path, tick_seconds, tolerance);
    std::vector<AxisMotion> all = estimate_axis_motion(timed_chain, tick_seconds);
    r.axes.assign(all.begin() + (all.empty() ? 0 : 1), all.end());
    return r;
}

}  // namespace stepzip
