// Two-letter word recognition, a letter at a time: the dual, convex-hull form
// of the arithmetic DSS recognition (Debled-Rennesson & Reveillès 1995) on the
// kernel of dss.hpp, in 128-bit arithmetic. See recognizer.hpp.
#include "dss.hpp"
#include "stepzip/segment/recognizer.hpp"

namespace stepzip {

namespace {
// 128-bit products: a word may grow past 2^30 letters here.
__extension__ typedef __int128 i128;
bool less(std::int64_t n1, std::int64_t d1, std::int64_t n2, std::int64_t d2) {
    return detail::dss::less<i128>(n1, d1, n2, d2);
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
    std::int64_t n, d;
    if (letter == 0) {
        // New upper bound: the smallest slope from an earlier "before 1"
        // position strictly to the left of c.
        if (detail::dss::min_slope_to<i128>(ones_hull_, c, n, d) && (!hi_.set || less(n, d, hi_.n, hi_.d)))
            hi_ = {n, d, true};
        detail::dss::push_lower<i128>(zeros_hull_, c);
        ++p_;
    } else {
        // New lower bound: the largest slope from an earlier "before 0"
        // position (all strictly to the left of c) to c.
        if (detail::dss::max_slope_to<i128>(zeros_hull_, c, n, d) && (!lo_.set || less(lo_.n, lo_.d, n, d)))
            lo_ = {n, d, true};
        detail::dss::push_upper<i128>(ones_hull_, c);
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
