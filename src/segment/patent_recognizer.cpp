// One segment grown step by step under the `patent` profile. See recognizer.hpp.
#include <algorithm>
#include <cstdlib>

#include "stepzip/segment/recognizer.hpp"

namespace stepzip {

void PatentRecognizer::reset() noexcept {
    ystep_.clear();
    delta_ = {};
}

bool PatentRecognizer::can_extend(Step s) const noexcept {
    if (length() >= kPatentMaxSegment || step_weight(s) != 1) return false;
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

bool PatentRecognizer::valid() const noexcept {
    return length() > 0 && exact(length(), std::llabs(delta_[0]));
}

// Forward mode with remaining counters x, y and adder F: F < 0 and x > 0:
// x-step, F += y; else y-step, F -= x. With f the adder's change since the
// start, a free x-step needs F0 < -f and a free y-step F0 >= -f.
bool PatentRecognizer::exact(std::int64_t m, std::int64_t xs) const noexcept {
    const std::int64_t a = xs, b = m - xs;
    if (a == 0 || b == 0) return true;
    const PhaseRange r = phase_range(Profile::patent, a, b);
    std::int64_t x = a, y = b, f = 0, lo = r.lo, hi = r.hi;
    for (std::int64_t k = 0; k < m && x > 0 && y > 0; ++k) {
        if (ystep_[static_cast<std::size_t>(k)] == 0) {
            hi = std::min(hi, -f);
            --x;
            f += y;
        } else {
            lo = std::max(lo, -f);
            --y;
            f -= x;
        }
        if (lo >= hi) return false;
    }
    return true;
}

std::int64_t PatentRecognizer::longest_valid() const noexcept {
    const std::int64_t n = length();
    if (n == 0) return 0;
    std::int64_t xs = std::llabs(delta_[0]);  // x-steps of the prefix of m steps
    for (std::int64_t m = n; m > 1; --m) {
        if (exact(m, xs)) return m;
        xs -= ystep_[static_cast<std::size_t>(m - 1)] == 0;
    }
    return 1;
}

}  // namespace stepzip
