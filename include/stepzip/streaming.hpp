// stepzip — streaming (online) reverse interpolation: steps in, one at a time
// or in spans, each segment out as soon as it is final.
//
// This is the patent's intended use (SU 1089551, seed 001: the approximation
// mode runs while the digitizer traces) with the greedy cut of segmenter.hpp:
// at each point the longest exact segment. A segment is final when a held
// step shows that no longer exact segment can start where it starts: the
// step breaks a hard limit (a sign change, a resting leading axis,
// kMaxSegmentTotal; for `patent` also kPatentMaxSegment), or the recognizer
// (segment/recognizer.hpp) reports the word is no longer a prefix of any
// digital straight segment. The recognizer may keep a word alive about one
// period of the line past its last exact prefix, so a segment can come out a
// few steps after its last step; it comes out at the same step at which the
// batch greedy segmenter stops reading. Until then its steps are held back.
//
// The hold-back bound. Greedy needs unbounded look-ahead on a long straight
// line, so the caller chooses `max_held`, the largest number of steps the
// segmenter may hold after any push() returns. When the held steps reach
// that count without the segment becoming final, the longest exact prefix of
// the held steps is forced out as a segment (a "forced cut"). Guarantees:
//  - after every push() returns, held() <= max_held();
//  - every emitted segment is exact (check_segment() passes and expanding it
//    under the profile gives its steps), and expanding the emitted segments
//    in order, after finish(), gives exactly the pushed steps;
//  - while no forced cut happens (forced_cuts() == 0) the segments are the
//    same, phases included, as segment_steps(..., SegmenterKind::greedy) on
//    the whole chain;
//  - a forced cut only splits where the batch cut would have a longer
//    segment; the output stays exact, it may hold a few more segments.
// Memory: O(max_held) steps. Complexity: as the greedy segmenter, O(log h)
// amortized per step for the linear profiles; for `patent`, whose candidates
// are checked in O(length), O(kPatentMaxSegment) per step in the worst case.
// Thread-safety: one object per stream; distinct objects share nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "stepzip/error.hpp"
#include "stepzip/profile.hpp"
#include "stepzip/segment.hpp"
#include "stepzip/segment/recognizer.hpp"
#include "stepzip/step.hpp"

namespace stepzip {

/// Default hold-back bound: 2^16 steps (128 KiB of held steps).
inline constexpr std::size_t kStreamingDefaultHold = std::size_t{1} << 16;

/// Online greedy segmenter for one chain at a time.
class StreamingSegmenter {
public:
    /// A segmenter for `axes`-axis chains under profile `p` that holds back at
    /// most `max_held` steps (>= 1). Invalid arguments (axes outside
    /// [2, profile_max_axes(p)], max_held 0) are reported by the first push()
    /// as Errc::invalid_argument; check them earlier with valid().
    StreamingSegmenter(Profile p, int axes, std::size_t max_held = kStreamingDefaultHold);

    /// True when the constructor's arguments are usable.
    bool valid() const noexcept;

    /// Appends one step. Segments that became final are appended to `out`
    /// (zero or more; at most one per held step).
    /// Errors (the step is then not taken, the state is unchanged):
    /// Errc::invalid_argument for a step not valid on axes() axes or bad
    /// constructor arguments, Errc::connectivity for a diagonal step under a
    /// 4-connected profile; messages name the 1-based index of the step in
    /// the chain.
    Result<void> push(Step s, std::vector<Segment>& out);

    /// Appends the steps of `steps` in order, as repeated push(). On an error
    /// the steps before the offending one have been taken.
    Result<void> push(std::span<const Step> steps, std::vector<Segment>& out);

    /// Ends the chain: appends the segments of every held step to `out`, then
    /// resets for the next chain (counters and forced_cuts() included).
    void finish(std::vector<Segment>& out);

    /// Steps received but not yet emitted in a segment.
    std::size_t held() const noexcept { return held_.size(); }
    /// The hold-back bound given to the constructor.
    std::size_t max_held() const noexcept { return max_held_; }
    /// Steps pushed into the current chain.
    std::uint64_t pushed() const noexcept { return pushed_; }
    /// Segments emitted only because the bound was reached, in the current chain.
    std::uint64_t forced_cuts() const noexcept { return forced_; }
    Profile profile() const noexcept { return profile_; }
    int axes() const noexcept { return axes_; }

private:
    // Reads held steps and emits every segment that is final; `flush` also
    // emits what is left (finish).
    void drain(std::vector<Segment>& out, bool flush);
    // Emits the longest exact prefix of the held steps (within the scanned ones).
    void cut(std::vector<Segment>& out);
    // Forgets the scanned steps (the recognizer starts a new segment).
    void restart() noexcept;

    Profile profile_;
    int axes_;
    std::size_t max_held_;
    std::vector<Step> held_;
    std::optional<ProfileRecognizer> rec_;  // set when valid()
    std::size_t scanned_ = 0;  // held steps read into rec_
    bool broken_ = false;      // the next held step cannot extend the segment
    std::uint64_t pushed_ = 0;
    std::uint64_t forced_ = 0;
};

}  // namespace stepzip
