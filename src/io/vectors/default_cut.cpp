// stepzip — the cut written as vectors: every segment at the profile's
// default phase, so that the profile's own interpolator, which knows nothing
// but the end points, redraws exactly the input steps.
//
// At each point the recognizer gives the longest exact segment (any phase);
// the cut takes the longest prefix of it that the default phase draws. Such
// a prefix always exists: one step is drawn by every phase. A prefix is
// checked by drawing it (O(length), for two axes after a test that stops at
// the first tick that differs); candidates are tried from the longest
// down and a prefix longer than kLongestVectorSegment is never considered,
// which bounds the work per segment to O(kLongestVectorSegment^2) in the
// worst case (a stream drawn at another phase); a stream the profile drew
// itself is usually cut at its first candidate. Complexity: O(n) for the
// recognizer plus the checks above.
#include <algorithm>
#include <cstdint>
#include <cstdlib>

#include "stepzip/segment/segmenters.hpp"
#include "stepzip/vectors.hpp"

namespace stepzip {

namespace {

// The default-phase segment of `run` (whose totals are `delta`) when it
// draws exactly `run`: the segment is expanded and compared.
bool default_draws(Profile p, std::span<const Step> run, const Point& delta, int axes,
                   std::vector<Step>& scratch, Segment& seg) {
    seg = default_segment(p, delta, axes);
    if (!check_segment(p, seg, axes)) return false;
    scratch.clear();
    expand_segment(p, seg, axes, scratch);
    return std::equal(scratch.begin(), scratch.end(), run.begin(), run.end());
}

// A fast necessary test for two axes and the linear profiles: the
// two-letter rule of recognizer.hpp (F >= 0: letter 0, F -= b; F < 0:
// letter 1, F += a) run from the default phase, stopping at the first tick
// that differs from `run`. A candidate drawn at another phase usually
// differs within one period of its slope, so most candidates cost far less
// than their length; the one accepted is confirmed by default_draws().
bool default_word_matches(Profile p, std::span<const Step> run, const Point& delta) {
    const bool eight = profile_eight_connected(p);
    const int lead = eight ? leading_axis(delta, 2) : 0;
    const std::int64_t u = std::abs(delta[0]), v = std::abs(delta[1]);
    const std::int64_t big = eight ? std::max(u, v) : u, small = eight ? std::min(u, v) : v;
    const std::int64_t a = eight ? big - small : big, b = small;
    const int sx = delta[0] < 0 ? -1 : 1, sy = delta[1] < 0 ? -1 : 1;
    Step letter_step[2];
    if (eight) {
        letter_step[0] = lead == 0 ? make_step2(sx, 0) : make_step2(0, sy);
        letter_step[1] = make_step2(sx, sy);
    } else {
        letter_step[0] = make_step2(sx, 0);
        letter_step[1] = make_step2(0, sy);
    }
    std::int64_t f = default_segment(p, delta, 2).phase[0];
    for (const Step s : run) {
        const int letter = b == 0 ? 0 : a == 0 ? 1 : f >= 0 ? 0 : 1;
        if (s != letter_step[letter]) return false;
        f += letter == 0 ? -b : a;
    }
    return true;
}

// The default-phase segments starting at one point of a chain.
class DefaultCandidates {
public:
    DefaultCandidates(std::span<const Step> steps, int axes, Profile p)
        : steps_(steps), axes_(axes), p_(p), greedy_(p, axes),
          word_(axes == 2 && p != Profile::patent) {}

    // Lengths of default-phase segments starting at steps[i], longest first:
    // at most `hits` of them, and none more than kLookBelow shorter than the
    // longest. Empty only at the end of the chain.
    const std::vector<std::size_t>& at(std::size_t i, std::size_t hits) {
        found_.clear();
        if (i >= steps_.size()) return found_;
        const auto window = steps_.subspan(
            i, std::min<std::size_t>(steps_.size() - i,
                                     static_cast<std::size_t>(kLongestVectorSegment)));
        const auto valid = static_cast<std::size_t>(greedy_.longest(window));
        prefix_.assign(1, Point{});
        for (std::size_t k = 0; k < valid; ++k) {
            Point d = prefix_.back();
            apply_step(d, window[k], axes_);
            prefix_.push_back(d);
        }
        Segment seg;
        for (std::size_t k = valid; k >= 1 && found_.size() < hits; --k) {
            if (!found_.empty() && k + kLookBelow < found_.front()) break;
            if ((!word_ || default_word_matches(p_, window.first(k), prefix_[k])) &&
                default_draws(p_, window.first(k), prefix_[k], axes_, scratch_, seg))
                found_.push_back(k);
        }
        return found_;
    }

    // The totals of the first k steps from the last at() call's start.
    const Point& delta(std::size_t k) const { return prefix_[k]; }

private:
    static constexpr std::size_t kLookBelow = 256;
    std::span<const Step> steps_;
    int axes_;
    Profile p_;
    GreedySegmenter greedy_;
    bool word_;
    std::vector<Point> prefix_;  // prefix_[k]: totals of the first k steps
    std::vector<Step> scratch_;
    std::vector<std::size_t> found_;
};

}  // namespace

Result<void> segment_default_phase(std::span<const Step> steps, int axes, Profile p,
                                   std::vector<Segment>& out, SegmenterKind kind) {
    if (auto r = profile_accepts(p, steps, axes); !r) return r;
    // Greedy with one segment of look-ahead: of the longest few
    // default-phase segments at a point, the one after which the next
    // default-phase segment reaches farthest (the longest on a tie). Plain
    // greedy may run a few steps past a polyline's vertex, and the rest of
    // the next line, drawn from its vertex, is then seldom one segment.
    // Greedy weighs the longest six; optimal every one (slower).
    const std::size_t choices = kind == SegmenterKind::optimal ? SIZE_MAX : 6;
    DefaultCandidates here(steps, axes, p), next(steps, axes, p);
    std::size_t i = 0;
    while (i < steps.size()) {
        const std::vector<std::size_t> hits = here.at(i, choices);
        if (hits.empty())  // cannot happen: a single step is drawn at every phase
            return make_error(Errc::mismatch,
                              "no default-phase segment at step " + std::to_string(i + 1));
        std::size_t take = hits.front(), reach = 0;
        if (hits.size() > 1)
            for (const std::size_t k : hits) {
                const auto& after = next.at(i + k, 1);
                const std::size_t r = k + (after.empty() ? 0 : after.front());
                if (r > reach) {
                    reach = r;
                    take = k;
                }
            }
        out.push_back(default_segment(p, here.delta(take), axes));
        i += take;
    }
    return {};
}

}  // namespace stepzip
