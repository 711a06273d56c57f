// Two-letter word recognition: the dual, convex-hull form of the arithmetic
// DSS recognition (Debled-Rennesson & Reveillès 1995). See recognizer.hpp.
#include "stepzip/segment/recognizer.hpp"

namespace stepzip {

namespace {
__extension__ typedef __int128 i128;

// Cross product of (b - a) and (c - a).
template <class P>
i128 cross(const P& a, const P& b, const P& c) {
    return i128(b.p - a.p) * (c.q - a.q) - i128(b.q - a.q) * (c.p - a.p);
}
// n1/d1 < n2/d2 for positive denominators.
bool less(std::int64_t n1, std::int64_t d1, std::int64_t n2, std::int64_t d2) {
    return i128(n1) * d2 < i128(n2) * d1;
}
}  // namespace

void WordRecognizer::reset() noexcept {
    zeros_hull_.clear();
    ones_hull_.clear();
    lo_ = {};
    hi_ = {};
    p_ = q_ = 0;
    alive_ = true;
}

bool WordRecognizer::extend(int letter) {
    if (!alive_) return false;
    const Pt c{p_, q_};
    if (letter == 0) {
        // New upper bound on the slope: the smallest slope from an earlier
        // "before 1" position strictly to the left of c (tangent to the upper
        // hull of those positions, found by binary search on a unimodal chain).
        std::size_t m = ones_hull_.size();
        if (m > 0 && ones_hull_[m - 1].p == c.p) --m;
        if (m > 0) {
            auto num = [&](std::size_t k) { return c.q - ones_hull_[k].q; };
            auto den = [&](std::size_t k) { return c.p - ones_hull_[k].p; };
            std::size_t lo = 0, hi = m - 1;
            while (lo < hi) {
                const std::size_t mid = (lo + hi) / 2;
                if (less(num(mid + 1), den(mid + 1), num(mid), den(mid))) lo = mid + 1;
                else hi = mid;
            }
            if (!hi_.set || less(num(lo), den(lo), hi_.n, hi_.d)) hi_ = {num(lo), den(lo), true};
        }
        while (zeros_hull_.size() >= 2 &&
               cross(zeros_hull_[zeros_hull_.size() - 2], zeros_hull_.back(), c) <= 0)
            zeros_hull_.pop_back();
        zeros_hull_.push_back(c);
        ++p_;
    } else {
        // New lower bound: the largest slope from an earlier "before 0"
        // position (all strictly to the left of c) to c.
        const std::size_t m = zeros_hull_.size();
        if (m > 0) {
            auto num = [&](std::size_t k) { return c.q - zeros_hull_[k].q; };
            auto den = [&](std::size_t k) { return c.p - zeros_hull_[k].p; };
            std::size_t lo = 0, hi = m - 1;
            while (lo < hi) {
                const std::size_t mid = (lo + hi) / 2;
                if (less(num(mid), den(mid), num(mid + 1), den(mid + 1))) lo = mid + 1;
                else hi = mid;
            }
            if (!lo_.set || less(lo_.n, lo_.d, num(lo), den(lo))) lo_ = {num(lo), den(lo), true};
        }
        if (!ones_hull_.empty() && ones_hull_.back().p == c.p) ones_hull_.pop_back();
        while (ones_hull_.size() >= 2 &&
               cross(ones_hull_[ones_hull_.size() - 2], ones_hull_.back(), c) >= 0)
            ones_hull_.pop_back();
        ones_hull_.push_back(c);
        ++q_;
    }
    if (lo_.set && hi_.set && !less(lo_.n, lo_.d, hi_.n, hi_.d)) alive_ = false;
    return alive_;
}

bool WordRecognizer::valid() const noexcept {
    if (!alive_) return false;
    if (p_ == 0 || q_ == 0) return true;
    // slope q/p strictly inside (lo, hi)
    if (lo_.set && !less(lo_.n, lo_.d, q_, p_)) return false;
    if (hi_.set && !less(q_, p_, hi_.n, hi_.d)) return false;
    return true;
}

}  // namespace stepzip
