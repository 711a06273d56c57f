// Phase prediction for timed chains (docs/FORMAT.md "Timed phases"): in a
// frame of input format timed, axis 0 is time, and a segment is a stretch
// of constant step rate. Where an axis's next step falls in a new segment
// follows from when it last stepped and the new rate, so the segment
// model codes each phase as its difference from that prediction, and the
// encoder picks, among the phases that draw the same steps, the one
// nearest the prediction. Internal to src/container.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "stepzip/profile.hpp"
#include "stepzip/interpolate/segment.hpp"
#include "stepzip/segment.hpp"

namespace stepzip::stz {

/// Which phase prediction a segment-model coder uses: none (the profile's
/// default), the time since each axis moved (block types 3 and 6 of a timed
/// frame), or TimedRates (the timed block, block type 7 subtype 0).
enum class TimedPrediction : unsigned char { none, since, rates };

/// State of the prediction along one chain: steps since each axis last
/// moved. Not thread-safe (one per coder).
class TimedPhase {
public:
    /// Nothing known (a chain start).
    void reset() { since_.fill(-1); }
    /// The predicted phase of evaluation function j of `seg` (totals set),
    /// inside the segment's phase range; the profile's default phase when
    /// nothing is known or the profile is not a leading-axis one.
    std::int64_t predict(Profile p, const Segment& seg, int axes, int j) const;
    /// After `seg` (expanded under `p`).
    void advance(Profile p, const Segment& seg, int axes);

private:
    std::array<std::int64_t, kMaxAxes> since_{-1, -1, -1, -1, -1, -1};  // -1: unknown
    std::vector<Step> scratch_;
};

/// Whether time (axis 0) leads `seg`, moving forward, within the segment limits.
bool time_leads(const Segment& seg, int axes);

/// The timed block's phase prediction (docs/FORMAT.md "Timed block"): an
/// axis's first move in a segment falls one period after its last move,
/// which is known to a fraction of a tick from that segment's phase; the
/// period is pooled over that segment and this one (their ticks over their
/// steps). Time must lead every
/// segment (axis 0). Not thread-safe (one per coder).
class TimedRates {
public:
    void reset();
    std::int64_t predict(Profile p, const Segment& seg, int axes, int j) const;
    void advance(Profile p, const Segment& seg, int axes);

private:
    // Per minor axis: the continuous time of its last move relative to the
    // start of the next segment, num / den ticks (-1: the last tick before
    // it), and the period lp / sp (ticks per step) of the segment it moved in.
    struct AxisRate {
        bool known = false;
        std::int64_t num = 0, den = 1, lp = 1, sp = 1;
    };
    std::array<AxisRate, kMaxAxes - 1> axis_{};
};

/// Encoder: re-picks the phases of every segment of a chain cut, in order,
/// to the valid phase nearest the prediction (the steps drawn stay the same).
void align_timed_phases(Profile p, int axes, std::vector<Segment>& segs);

/// The same for any predictor with reset(), predict(p, seg, axes, j) and
/// advance(p, seg, axes) (the segment model's TimedPhase, the timed block's
/// rate predictor). Complexity: O(L · axes · log L) per segment.
template <class Predictor>
void align_phases(Profile p, int axes, std::vector<Segment>& segs, Predictor& pred) {
    pred.reset();
    std::vector<Step> want, got;
    auto draws_same = [&](const Segment& s) {
        got.clear();
        expand_segment(p, s, axes, got);
        return got == want;
    };
    for (Segment& seg : segs) {
        want.clear();
        expand_segment(p, seg, axes, want);
        for (int j = 0; j < axes - 1; ++j) {
            const auto ab = phase_arguments(p, seg, axes, j);
            if (!ab) break;
            const PhaseRange r = phase_range(p, ab->first, ab->second);
            if (r.hi - r.lo == 1) continue;
            const std::int64_t guess = pred.predict(p, seg, axes, j);
            std::int64_t good = seg.phase[j], bad = guess;
            Segment trial = seg;
            trial.phase[j] = guess;
            if (draws_same(trial)) {
                seg.phase[j] = guess;
                continue;
            }
            // The valid phases form an interval around the current one: the
            // boundary on the prediction's side, by bisection.
            while (bad - good > 1 || good - bad > 1) {
                const std::int64_t mid = good + (bad - good) / 2;
                trial.phase[j] = mid;
                (draws_same(trial) ? good : bad) = mid;
            }
            seg.phase[j] = good;
        }
        pred.advance(p, seg, axes);
    }
}

}  // namespace stepzip::stz
