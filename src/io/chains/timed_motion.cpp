// stepzip — axis rates and accelerations read out of a timed chain
// (include/stepzip/timed.hpp).
#include <algorithm>
#include <array>
#include <cmath>

#include "stepzip/timed.hpp"

namespace stepzip {

namespace {

constexpr std::size_t kWindow = 128;
constexpr double kMaxRms = 0.6;
constexpr double kQuantile = 0.9;

// Least-squares parabola k = c0 + c1·u + c2·u² through (u_j, j); false when singular.
bool fit_parabola(const std::array<double, kWindow>& u, std::array<double, 3>& c, double& rms) {
    double m[3][4] = {};
    for (std::size_t j = 0; j < kWindow; ++j) {
        const double p[3] = {1.0, u[j], u[j] * u[j]};
        for (int r = 0; r < 3; ++r) {
            for (int k = 0; k < 3; ++k) m[r][k] += p[r] * p[k];
            m[r][3] += p[r] * static_cast<double>(j);
        }
    }
    for (int col = 0; col < 3; ++col) {  // Gauss-Jordan with partial pivoting
        int piv = col;
        for (int r = col + 1; r < 3; ++r)
            if (std::fabs(m[r][col]) > std::fabs(m[piv][col])) piv = r;
        if (std::fabs(m[piv][col]) < 1e-300) return false;
        for (int k = 0; k < 4; ++k) std::swap(m[col][k], m[piv][k]);
        for (int r = 0; r < 3; ++r) {
            if (r == col) continue;
            const double f = m[r][col] / m[col][col];
            for (int k = col; k < 4; ++k) m[r][k] -= f * m[col][k];
        }
    }
    for (int r = 0; r < 3; ++r) c[static_cast<std::size_t>(r)] = m[r][3] / m[r][r];
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
