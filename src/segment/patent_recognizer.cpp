// One segment grown step by step under the `patent` profile. See recognizer.hpp.
#include <algorithm>
#include <cstdlib>
#include <span>

#include "stepzip/segment/recognizer.hpp"

namespace stepzip {

void PatentRecognizer::reset() noexcept {
    ystep_.clear();
    xs_before_.clear();
    c_.clear();
    delta_ = {};
    synced_xs_ = 0;
    synced_c_ = 0;
    last_lo_ = last_hi_ = -1;
}

bool PatentRecognizer::can_extend(Step s) const noexcept {
    if (length() >= kPatentMaxSegment || !step_moves_one_axis(s)) return false;
    const int dx = step_axis(s, 0), dy = step_axis(s, 1);
    if (dx != 0) return delta_[0] == 0 || (delta_[0] > 0) == (dx > 0);
    return delta_[1] == 0 || (delta_[1] > 0) == (dy > 0);
}

bool PatentRecognizer::extend(Step s) {
    const int dx = step_axis(s, 0), dy = step_axis(s, 1);
    ystep_.push_back(dx == 0 ? 1 : 0);
    delta_[0] += dx;
    delta_[1] += dy;
    return length() < kPatentMaxSegment;
}

std::int64_t PatentRecognizer::read(std::span<const Step> steps) {
    reset();
    // can_extend() and extend() over the run of steps, in one loop: the
    // step codes of +x, -x, +y, -y (0 for an axis not seen yet)
    const std::size_t cap = std::min<std::size_t>(steps.size(), kPatentMaxSegment);
    const Step x_pos = make_step2(1, 0), x_neg = make_step2(-1, 0), y_pos = make_step2(0, 1), y_neg = make_step2(0, -1);
    Step x_seen = 0, y_seen = 0;
    std::size_t n = 0;
    for (; n < cap; ++n) {
        const Step s = steps[n];
        if (s == x_pos || s == x_neg) {
            if (x_seen != 0 && x_seen != s) break;
            x_seen = s;
        } else if (s == y_pos || s == y_neg) {
            if (y_seen != 0 && y_seen != s) break;
            y_seen = s;
        } else {
            break;
        }
    }
    ystep_.resize(n);
    std::int64_t xs = 0;
    for (std::size_t k = 0; k < n; ++k) {
        const bool x = steps[k] == x_seen;
        ystep_[k] = x ? 0 : 1;
        xs += x;
    }
    delta_[0] = x_seen == x_neg ? -xs : xs;
    delta_[1] = y_seen == y_neg ? xs - static_cast<std::int64_t>(n) : static_cast<std::int64_t>(n) - xs;
    return static_cast<std::int64_t>(n);
}

// The per-step terms of the steps read since the last call, in one loop
// (read() and extend() store the steps only).
void PatentRecognizer::sync() const {
    for (std::size_t k = xs_before_.size(); k < ystep_.size(); ++k) {
        const std::int64_t j = static_cast<std::int64_t>(k) - synced_xs_;
        xs_before_.push_back(synced_xs_);
        c_.push_back(synced_c_);
        // a y-step takes the remaining X - i, an x-step adds the remaining Y - j
        if (ystep_[k] != 0) {
            synced_c_ += synced_xs_;
        } else {
            synced_c_ -= j;
            ++synced_xs_;
        }
    }
}

bool PatentRecognizer::valid() const {
    if (length() == 0) return false;
    sync();
    return exact(length(), std::llabs(delta_[0]));
}

// Forward mode with remaining counters x, y and adder F: F < 0 and x > 0:
// x-step, F += y; else y-step, F -= x. With f the adder's change since the
// start, a free x-step needs F0 < -f and a free y-step F0 >= -f. Before step
// k, after i x-steps and j y-steps, f = i*b - j*a + c_k for totals (a, b):
// each x-step t added b - j_t, each y-step took a - i_t.
bool PatentRecognizer::exact(std::int64_t m, std::int64_t xs) const noexcept {
    const std::int64_t a = xs, b = m - xs;
    if (a == 0 || b == 0) return true;
    const PhaseRange r = phase_range(Profile::patent, a, b);
    // -f before step k, and whether step k is free (both counters left;
    // i and j only grow, so the free steps are a prefix)
    auto bound = [&](std::int64_t k) {
        const std::int64_t i = xs_before_[static_cast<std::size_t>(k)];
        return (k - i) * a - i * b - c_[static_cast<std::size_t>(k)];
    };
    auto is_free = [&](std::int64_t k) {
        const std::int64_t i = xs_before_[static_cast<std::size_t>(k)];
        return k < m && i < a && k - i < b;
    };
    // The pair that contradicted last (-1: the phase range's side), first:
    // a subset of the constraints that contradicts rejects the candidate.
    if ((last_lo_ >= 0 || last_hi_ >= 0) && (last_lo_ < 0 || is_free(last_lo_)) && (last_hi_ < 0 || is_free(last_hi_)) &&
        std::max(r.lo, last_lo_ < 0 ? r.lo : bound(last_lo_)) >= std::min(r.hi, last_hi_ < 0 ? r.hi : bound(last_hi_)))
        return false;
    std::int64_t lo = r.lo, hi = r.hi, at_lo = -1, at_hi = -1;
    for (std::int64_t k = 0; k < m && is_free(k); ++k) {
        const std::int64_t v = bound(k);
        if (ystep_[static_cast<std::size_t>(k)] == 0) {
            if (v < hi) hi = v, at_hi = k;
        } else if (v > lo) {
            lo = v, at_lo = k;
        }
        if (lo >= hi) {
            last_lo_ = at_lo;
            last_hi_ = at_hi;
            return false;
        }
    }
    return true;
}

std::int64_t PatentRecognizer::longest_valid() const {
    const std::int64_t n = length();
    if (n == 0) return 0;
    sync();
    std::int64_t xs = std::llabs(delta_[0]);  // x-steps of the prefix of m steps
    for (std::int64_t m = n; m > 1; --m) {
        if (exact(m, xs)) return m;
        xs -= ystep_[static_cast<std::size_t>(m - 1)] == 0;
    }
    return 1;
}

}  // namespace stepzip
