// The recognizer the drivers cut with (not installed).
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "run_word.hpp"
#include "stepzip/segment/recognizer.hpp"
#include "stepzip/segment/segmenters.hpp"
#include "two_axis.hpp"

namespace stepzip::detail {

/// Picks, once per profile and axis count, the recognizer that answers the
/// greedy and optimal drivers' two questions, so that the drivers never look
/// at the profile: TwoAxisGreedy (linear profiles on two axes, longest cut),
/// RunSegment (linear profiles, run by run: longest cut on more axes, every
/// exact end for the optimal driver), PatentRecognizer (the `patent` profile).
/// Not thread-safe (an object per thread).
class ProfileCut {
public:
    /// Precondition: 2 <= axes <= profile_max_axes(p).
    ProfileCut(Profile p, int axes);

    /// Length of the longest exact segment at steps[0] (>= 1; 0 for no steps).
    std::int64_t longest(std::span<const Step> steps);
    /// fit_segment(p, steps.first(m), axes), for m = longest(steps) called
    /// just before on the same steps.
    std::optional<Segment> fit(std::span<const Step> steps, std::int64_t m) const;

    /// Ends the optimal driver examines per start (kOptimalWindow, or
    /// kPatentOptimalWindow for `patent`, whose candidates cost O(length)).
    std::int64_t window() const noexcept;
    /// Makes ends() read `steps` (the whole chain, kept by reference).
    void prepare(std::span<const Step> steps);
    /// Calls f(lo, hi) for intervals of lengths m in [lo, hi] such that the
    /// prepared steps [s, s + m) form one exact segment, s + m <= lim; every
    /// such m is in one interval. Complexity: linear profiles O(log h) per
    /// run read (reading stops where the word breaks); patent O(m) per m.
    template <class F>
    void ends(std::size_t s, std::size_t lim, F&& f);

private:
    std::int64_t longest_other(std::span<const Step> steps);

    Profile profile_;
    int axes_;
    std::optional<TwoAxisGreedy> two_;  // linear profiles on two axes
    std::optional<RunSegment> runs_;    // linear profiles
    std::optional<PatentRecognizer> patent_;
    std::span<const Step> steps_;       // prepared for ends()
    std::vector<std::uint32_t> run_end_;  // end of the run of identical steps at each position
};

// The two-axis path first: it is the hot one, and these two calls stay inline
// in the drivers' loops.
inline std::int64_t ProfileCut::longest(std::span<const Step> steps) {
    if (two_ && !steps.empty()) return two_->longest(steps);
    return longest_other(steps);
}

inline std::optional<Segment> ProfileCut::fit(std::span<const Step> steps, std::int64_t m) const {
    if (two_) return two_->fit(steps, m);
    return fit_segment(profile_, steps.first(static_cast<std::size_t>(m)), axes_);
}

template <class F>
void ProfileCut::ends(std::size_t s, std::size_t lim, F&& f) {
    if (patent_) {
        PatentRecognizer& rec = *patent_;
        rec.reset();
        for (std::size_t pos = s; pos < lim && rec.can_extend(steps_[pos]); ++pos) {
            rec.extend(steps_[pos]);
            if (rec.valid()) f(rec.length(), rec.length());
        }
        return;
    }
    // Run by run: each run contributes an interval of ends.
    RunSegment& rec = *runs_;
    rec.reset();
    for (std::size_t pos = s; pos < lim;) {
        const std::size_t e = std::min<std::size_t>(run_end_[pos], lim);
        const auto k = static_cast<std::int64_t>(e - pos);
        const auto r = rec.probe(steps_[pos], k);
        if (r.lo <= r.hi) {
            const auto base = static_cast<std::int64_t>(pos - s);
            f(base + r.lo, base + r.hi);
        }
        if (r.alive < k) break;
        rec.commit(steps_[pos], k);
        pos = e;
    }
}

}  // namespace stepzip::detail

namespace stepzip {

/// Times a segmenter fell back to a shorter cut because a recognizer claimed
/// a prefix that no segment fits. The output stays exact, so only this count
/// shows such a recognizer bug in a release build; the tests require zero.
void count_segmenter_fallback() noexcept;
std::uint64_t segmenter_fallbacks() noexcept;

}  // namespace stepzip
