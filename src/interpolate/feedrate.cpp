// The feed-rate block and the synchronization buffer (seed 000 "БЛОК ЗА
// ЗАДАВАНЕ НА СКОРОСТТА", seed 002).
#include "stepzip/interpolate/feedrate.hpp"

#include <cmath>
#include <string>

namespace stepzip {

double axis_factor(int axes, AxisFactor mode) noexcept {
    if (axes <= 1) return 1.0;
    const double exact = std::sqrt(static_cast<double>(axes));
    if (mode == AxisFactor::exact) return exact;
    return std::round(exact * 100.0) / 100.0;  // 1.41, 1.73, 2.00, 2.24, 2.45
}

Result<std::vector<double>> feed_times(const std::vector<Step>& steps, int axes, double v,
                                       AxisFactor mode) {
    if (!(v > 0) || !std::isfinite(v))
        return make_error(Errc::invalid_argument, "feed_times: feed rate must be positive");
    if (axes < 1 || axes > kMaxAxes)
        return make_error(Errc::invalid_argument, "feed_times: axes must be 1..6");
    const double dt = 1.0 / v;
    std::vector<double> t;
    t.reserve(steps.size());
    double now = dt;
    for (std::size_t i = 0; i < steps.size(); ++i) {
        if (!step_valid(steps[i], axes))
            return make_error(Errc::invalid_argument,
                              "feed_times: step " + std::to_string(i) + " is not a valid step");
        t.push_back(now);
        now += dt * axis_factor(step_weight(steps[i]), mode);
    }
    return t;
}

double dda_period(std::int64_t dx, std::int64_t dy, double v, int p) noexcept {
    if (!(v > 0)) return 0.0;
    const double len = std::hypot(static_cast<double>(dx), static_cast<double>(dy));
    return len / (v * std::ldexp(1.0, p));
}

std::vector<double> dda_times(const DdaTrace& trace, double period) {
    std::vector<double> t;
    t.reserve(trace.step_cycle.size());
    for (std::uint64_t c : trace.step_cycle) t.push_back(static_cast<double>(c) * period);
    return t;
}

Result<SyncResult> simulate_sync_buffer(const std::vector<double>& drive_times,
                                        double compute_time, std::size_t capacity) {
    if (capacity == 0)
        return make_error(Errc::invalid_argument, "simulate_sync_buffer: capacity 0");
    if (!(compute_time >= 0) || !std::isfinite(compute_time))
        return make_error(Errc::invalid_argument,
                          "simulate_sync_buffer: compute time must be finite and >= 0");
    for (std::size_t i = 0; i < drive_times.size(); ++i)
        if (!std::isfinite(drive_times[i]) || drive_times[i] < 0 ||
            (i > 0 && drive_times[i] < drive_times[i - 1]))
            return make_error(Errc::invalid_argument,
                              "simulate_sync_buffer: drive time " + std::to_string(i) +
                                  " is negative, not finite or decreasing");
    const std::size_t n = drive_times.size();
    SyncResult r;
    r.issued.resize(n);
    r.computed.resize(n);
    double done = 0, issued_prev = 0, ideal_prev = 0;
    std::size_t taken = 0;  // steps issued by the time of the current completion
    for (std::size_t i = 0; i < n; ++i) {
        double start = done;
        if (i >= capacity && r.issued[i - capacity] > start) {
            r.interpolator_stall += r.issued[i - capacity] - start;  // buffer full: СТОП
            start = r.issued[i - capacity];
        }
        done = start + compute_time;
        r.computed[i] = done;
        const double interval = drive_times[i] - ideal_prev;
        ideal_prev = drive_times[i];
        const double tick = issued_prev + interval;
        if (done > tick) ++r.underruns;
        r.issued[i] = done > tick ? done : tick;
        issued_prev = r.issued[i];
        // Steps waiting just after step i was computed.
        while (taken < i && r.issued[taken] <= done) ++taken;
        const std::size_t fill = i + 1 - taken;
        if (fill > r.max_fill) r.max_fill = fill;
    }
    return r;
}

}  // namespace stepzip
