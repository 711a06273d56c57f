// Phase prediction for timed chains; see timed_phase.hpp.
// Complexity: predict O(1); advance O(L · axes) (the segment is expanded);
// align_timed_phases O(L · axes · log L) per segment.
#include "timed_phase.hpp"

#include <algorithm>
#include <cstdlib>

#include "stepzip/container.hpp"

namespace stepzip::stz {

namespace {

bool leading_axis_profile(Profile p) {
    return p == Profile::eval8 || p == Profile::grbl || p == Profile::marlin;
}

// Axis of evaluation function j of a leading-axis segment: the j-th axis other than the lead.
int minor_axis(int lead, int j) { return j < lead ? j : j + 1; }

}  // namespace

std::int64_t TimedPhase::predict(Profile p, const Segment& seg, int axes, int j) const {
    const auto ab = phase_arguments(p, seg, axes, j);
    if (!ab) return 0;
    const std::int64_t l = ab->first, s = ab->second;
    const std::int64_t def = default_phase(p, l, s);
    const int lead = leading_axis(seg.delta, axes);
    if (!leading_axis_profile(p) || s <= 0 || s >= l) return def;
    const std::int64_t a = since_[static_cast<std::size_t>(minor_axis(lead, j))];
    if (a < 0) return def;
    // The axis last moved a + 1 steps before the segment's first one; at the
    // new rate (s moves in l steps) it moves next l / s steps after that.
    // The first move falls on step k1 (0-based) when floor(F0 / s) + 1 == k1
    // (F0 >= 0), or at once when F0 < 0: the middle of that phase interval.
    // k1 = round(l / s - 1 - a) in integers: floor((2l - 2s(1 + a) + s) / 2s).
    const std::int64_t num = 2 * l - 2 * s * (1 + a) + s;
    const std::int64_t den = 2 * s;
    const std::int64_t k = num >= 0 ? num / den : -((-num + den - 1) / den);
    const std::int64_t k1 = std::clamp<std::int64_t>(k, 0, l - 1);
    const std::int64_t pred = k1 == 0 ? -(s + 1) / 2 : s * (k1 - 1) + s / 2;
    const PhaseRange r = phase_range(p, l, s);
    return std::clamp(pred, r.lo, r.hi - 1);
}

void TimedPhase::advance(Profile p, const Segment& seg, int axes) {
    // A segment longer than a block is corrupt (its reader says so next);
    // it is not expanded here.
    if (static_cast<std::uint64_t>(std::llabs(seg.delta[static_cast<std::size_t>(leading_axis(seg.delta, axes))])) >
        kMaxBlockSteps) {
        reset();
        return;
    }
    scratch_.clear();
    expand_segment(p, seg, axes, scratch_);
    const auto n = static_cast<std::int64_t>(scratch_.size());
    for (int i = 0; i < axes; ++i) {
        std::int64_t m = n - 1;
        while (m >= 0 && step_axis(scratch_[static_cast<std::size_t>(m)], i) == 0) --m;
        auto& a = since_[static_cast<std::size_t>(i)];
        if (m >= 0) a = n - 1 - m;
        else if (a >= 0) a += n;
    }
}

void align_timed_phases(Profile p, int axes, std::vector<Segment>& segs) {
    if (!leading_axis_profile(p)) return;
    TimedPhase tp;
    tp.reset();
    std::vector<Step> want, got;
    auto draws_same = [&](Segment s) {
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
            const std::int64_t pred = tp.predict(p, seg, axes, j);
            std::int64_t good = seg.phase[j], bad = pred;
            Segment trial = seg;
            trial.phase[j] = pred;
            if (draws_same(trial)) {
                seg.phase[j] = pred;
                continue;
            }
            // The valid phases form an interval around the current one: the
            // boundary on the prediction's side, by bisection.
            while (std::llabs(bad - good) > 1) {
                const std::int64_t mid = good + (bad - good) / 2;
                trial.phase[j] = mid;
                (draws_same(trial) ? good : bad) = mid;
            }
            seg.phase[j] = good;
        }
        tp.advance(p, seg, axes);
    }
}

}  // namespace stepzip::stz
