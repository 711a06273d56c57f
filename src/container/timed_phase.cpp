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

bool time_leads(const Segment& seg, int axes) {
    if (seg.delta[0] <= 0 || seg.delta[0] > kMaxSegmentTotal) return false;
    for (int i = 1; i < axes; ++i)
        if (std::llabs(seg.delta[static_cast<std::size_t>(i)]) > seg.delta[0]) return false;
    return true;
}

namespace {
__extension__ typedef __int128 i128;
// floor(n / d) for d > 0.
i128 floor_div(i128 n, i128 d) { return n >= 0 ? n / d : -((-n + d - 1) / d); }
// An axis resting longer than this many ticks is forgotten (magnitudes stay below 2^62).
constexpr std::int64_t kMaxRest = std::int64_t{1} << 26;
}  // namespace

void TimedRates::reset() {
    for (auto& a : axis_) a = AxisRate{};
}

std::int64_t TimedRates::predict(Profile p, const Segment& seg, int axes, int j) const {
    if (!time_leads(seg, axes)) {  // not a timed segment (a corrupt block): no prediction
        const auto ab = phase_arguments(p, seg, axes, j);
        return ab ? default_phase(p, ab->first, ab->second) : 0;
    }
    const std::int64_t l = seg.delta[0];
    const std::int64_t s = std::llabs(seg.delta[static_cast<std::size_t>(j + 1)]);
    const PhaseRange r = phase_range(p, l, s);
    if (r.hi - r.lo == 1) return r.lo;
    const AxisRate& a = axis_[static_cast<std::size_t>(j)];
    if (!a.known) return default_phase(p, l, s);
    // First move one period after the last, the period pooled over the
    // segment the axis last moved in and this one: at t = num/den + (lp + l) /
    // (sp + s) ticks from the segment's start; its phase is s · t, rounded
    // half up (FORMAT.md "Timed block").
    const i128 num = i128{s} * a.num * (a.sp + s) + i128{s} * (a.lp + l) * a.den;
    const i128 den = i128{a.den} * (a.sp + s);
    const i128 f = floor_div(2 * num + den, 2 * den);
    return static_cast<std::int64_t>(std::clamp<i128>(f, r.lo, r.hi - 1));
}

void TimedRates::advance(Profile, const Segment& seg, int axes) {
    if (!time_leads(seg, axes)) {
        reset();
        return;
    }
    const std::int64_t l = seg.delta[0];
    for (int j = 0; j + 1 < axes; ++j) {
        AxisRate& a = axis_[static_cast<std::size_t>(j)];
        const std::int64_t s = std::llabs(seg.delta[static_cast<std::size_t>(j + 1)]);
        if (s > 0) {
            // The last of s moves of a line of phase f: at (f - l) / s.
            const std::int64_t f = s < l ? seg.phase[static_cast<std::size_t>(j)] : 0;
            a = AxisRate{true, f - l, s, l, s};
        } else if (a.known) {
            a.num -= l * a.den;
            if (-a.num > kMaxRest * a.den) a = AxisRate{};
        }
    }
}

void align_timed_phases(Profile p, int axes, std::vector<Segment>& segs) {
    if (!leading_axis_profile(p)) return;
    TimedPhase tp;
    align_phases(p, axes, segs, tp);
}

}  // namespace stepzip::stz
