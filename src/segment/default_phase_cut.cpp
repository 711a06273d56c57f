// The default-phase segmenter: a cut of a chain for the container's segment
// model (docs/FORMAT.md, encoder behaviour), greedy, but preferring a segment that the profile's own
// interpolator draws at its default phase. A stream drawn by a controller
// (GRBL, Marlin, the seeds' interpolators) is cut at its original vector
// ends, so its segments repeat and cost no phase; the free-phase greedy cut
// may run a few steps past a vector end and shift every later cut.
// Complexity, two axes: O(log n) per run of identical steps for the
// recognizer (two_axis.hpp), O(L) per segment start for the letter
// positions, and O(1) per candidate length plus O(S) for the one that is
// taken (the default-phase pattern's letters are found by division, see
// emit_two_letter in src/interpolate/linear.cpp). More axes: O(64 · L) per
// segment (the patterns are expanded). Encoder only; the decoder does not
// depend on the cut.
#include <algorithm>
#include <optional>

#include "default_phase_cut.hpp"
#include "run_word.hpp"
#include "stepzip/interpolate/segment.hpp"
#include "stepzip/segment/recognizer.hpp"
#include "stepzip/segmenter.hpp"
#include "two_axis.hpp"

namespace stepzip {

namespace {

constexpr std::int64_t kBackoff = 64;  // how far below the greedy length to look

// The segment taken where `run` (of `valid` steps) is the longest exact
// segment: the longest one drawn at the default phase (`is_default(k, seg)`
// for its first k steps) at most kBackoff shorter and at least half as long,
// else the whole run fitted; its length, 0 when nothing fits.
template <class IsDefault>
std::size_t take_segment(Profile p, std::span<const Step> run, int axes, IsDefault is_default, Segment& seg) {
    const std::size_t valid = run.size();
    const std::size_t floor = valid > static_cast<std::size_t>(kBackoff) ? valid - kBackoff : 1;
    for (std::size_t k = valid; k >= floor && k * 2 >= valid; --k)
        if (is_default(k, seg)) return k;
    auto fit = fit_segment(p, run, axes);
    if (!fit) return 0;
    seg = *fit;
    return valid;
}

bool default_exact(Profile p, std::span<const Step> run, int axes, std::vector<Step>& scratch,
                   Segment& seg) {
    Point delta{};
    for (Step s : run) apply_step(delta, s, axes);
    seg = default_segment(p, delta, axes);
    if (!check_segment(p, seg, axes)) return false;
    scratch.clear();
    expand_segment(p, seg, axes, scratch);
    return scratch.size() == run.size() && std::equal(scratch.begin(), scratch.end(), run.begin());
}

// Two axes: the window's letters (ticks where each axis moves) and the
// test whether a prefix is the profile's default-phase pattern.
class TwoAxisWindow {
public:
    TwoAxisWindow(Profile p) : p_(p), eight_(profile_eight_connected(p)) {}

    // Written through raw pointers into vectors sized for every tick (no
    // growth check per step); count_[a] of them hold axis a's ticks.
    void load(std::span<const Step> w) {
        const std::size_t n = w.size();
        std::size_t cnt[2] = {0, 0};
        std::int64_t* at[2];
        for (int a = 0; a < 2; ++a) {
            if (ticks_[a].size() < n) ticks_[a].resize(n);
            at[a] = ticks_[a].data();
            sign_[a] = 1;
        }
        for (std::size_t t = 0; t < n; ++t) {
            const unsigned s = w[t];
            at[0][cnt[0]] = static_cast<std::int64_t>(t);
            at[1][cnt[1]] = static_cast<std::int64_t>(t);
            cnt[0] += s & 1u;
            cnt[1] += (s >> 2) & 1u;
        }
        for (int a = 0; a < 2; ++a) {
            count_[a] = cnt[a];
            if (cnt[a] != 0) sign_[a] = step_axis(w[static_cast<std::size_t>(at[a][cnt[a] - 1])], a);
        }
    }

    // The default-phase segment of the first k steps, if it draws them.
    bool default_exact(std::size_t k, Segment& seg) const {
        std::int64_t cnt[2];
        for (int a = 0; a < 2; ++a)
            cnt[a] = std::upper_bound(ticks_[a].data(), ticks_[a].data() + count_[a], static_cast<std::int64_t>(k) - 1) -
                     ticks_[a].data();
        Point delta{};
        for (int a = 0; a < 2; ++a) delta[a] = sign_[a] * cnt[a];
        seg = default_segment(p_, delta, 2);
        // Rule of emit_two_letter: n ticks, s `other` letters at the ticks of
        // the minor axis (8-connected: the non-leading axis; eval4: y).
        const int minor = eight_ ? (cnt[0] >= cnt[1] ? 1 : 0) : 1;
        const std::int64_t n = static_cast<std::int64_t>(k), s = cnt[minor];
        if (eight_ && cnt[1 - minor] != n) return false;  // the leading axis moves every tick
        if (!eight_ && cnt[0] + cnt[1] != n) return false;
        if (s == 0 || s == n) return true;
        const std::int64_t f0 = seg.phase[0];
        if (f0 < -s || f0 >= n - s) return false;
        const std::vector<std::int64_t>& at = ticks_[minor];
        auto tick = [&](std::int64_t j) { return (j * n + f0 + s) / s; };  // (j + 1)-th letter
        if (at[static_cast<std::size_t>(s - 1)] != tick(s - 1) || at[0] != tick(0) ||
            at[static_cast<std::size_t>(s / 2)] != tick(s / 2))
            return false;
        // The ticks between, without a division each: (j * n + f0 + s) / s
        // moves by n / s per letter, and by one more when the remainder
        // (f0 + s >= 0, so the quotients are floors) passes s.
        const std::int64_t step = n / s, extra = n % s;
        std::int64_t t = tick(0), rem = (f0 + s) % s;
        for (std::int64_t j = 1; j < s - 1; ++j) {
            t += step;
            rem += extra;
            if (rem >= s) {
                rem -= s;
                ++t;
            }
            if (at[static_cast<std::size_t>(j)] != t) return false;
        }
        return true;
    }

private:
    Profile p_;
    bool eight_;
    std::vector<std::int64_t> ticks_[2];  // the first count_[a] entries are axis a's ticks
    std::size_t count_[2] = {0, 0};
    int sign_[2];
};

bool cut_two_axes(std::span<const Step> steps, Profile p, std::vector<Segment>& out, bool accepted) {
    // The longest exact segment at each point: TwoAxisGreedy (the greedy
    // cut's recognizer, several times faster on short segments) where every
    // step is valid for the profile, its precondition; else RunSegment,
    // which answers 0 at an invalid step. Same answers (two_axis.hpp).
    std::optional<detail::TwoAxisGreedy> two;
    std::optional<detail::RunSegment> rec;
    if (accepted || profile_accepts(p, steps, 2)) two.emplace(p);
    else rec.emplace(p, 2);
    TwoAxisWindow win(p);
    std::size_t i = 0;
    while (i < steps.size()) {
        const auto valid = static_cast<std::size_t>(two ? two->longest(steps.subspan(i))
                                                        : detail::longest_exact_prefix(*rec, steps.subspan(i)));
        if (valid == 0) return false;
        win.load(steps.subspan(i, valid));
        Segment seg;
        const std::size_t take = take_segment(
            p, steps.subspan(i, valid), 2, [&](std::size_t k, Segment& s) { return win.default_exact(k, s); }, seg);
        if (take == 0) return false;
        out.push_back(seg);
        i += take;
    }
    return true;
}

}  // namespace

bool cut_preferring_default(std::span<const Step> steps, int axes, Profile p,
                            std::vector<Segment>& out, bool accepted) {
    if (p == Profile::patent) return false;
    if (axes == 2) return cut_two_axes(steps, p, out, accepted);
    return cut_preferring_default_reference(steps, axes, p, out);
}

bool cut_preferring_default_reference(std::span<const Step> steps, int axes, Profile p,
                                      std::vector<Segment>& out) {
    if (p == Profile::patent) return false;
    SegmentRecognizer rec(p, axes);
    std::vector<Step> scratch;
    std::size_t i = 0;
    while (i < steps.size()) {
        rec.reset();
        std::size_t m = 0, valid = 0;
        while (i + m < steps.size() && rec.can_extend(steps[i + m])) {
            const bool alive = rec.extend(steps[i + m]);
            ++m;
            if (rec.valid()) valid = m;
            if (!alive) break;
        }
        if (valid == 0) return false;
        Segment seg;
        const std::size_t take = take_segment(
            p, steps.subspan(i, valid), axes,
            [&](std::size_t k, Segment& s) { return default_exact(p, steps.subspan(i, k), axes, scratch, s); }, seg);
        if (take == 0) return false;
        out.push_back(seg);
        i += take;
    }
    return true;
}

}  // namespace stepzip
