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
#include "stepzip/segment.hpp"

namespace stepzip::stz {

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

/// Encoder: re-picks the phases of every segment of a chain cut, in order,
/// to the valid phase nearest the prediction (the steps drawn stay the same).
void align_timed_phases(Profile p, int axes, std::vector<Segment>& segs);

}  // namespace stepzip::stz
