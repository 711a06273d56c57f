// stepzip — the drivers that cut a whole chain into exact segments.
//
// All three produce segments that expand, in order, to exactly the input
// steps under the profile, each passing check_segment(), with each phase the
// valid one nearest the profile default. segment_steps() (segmenter.hpp) is
// the usual entry point; these classes are for callers that want the stages.
// Input preconditions: profile_accepts(p, steps, axes) succeeded.
// Thread-safety: an object per thread; distinct objects share nothing.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "stepzip/profile.hpp"
#include "stepzip/segment.hpp"
#include "stepzip/segment/recognizer.hpp"
#include "stepzip/segmenter.hpp"
#include "stepzip/step.hpp"

namespace stepzip {

/// Ends examined per start by the optimal segmenter beyond which only the
/// greedy cut's own segments are offered (see OptimalSegmenter).
inline constexpr std::int64_t kOptimalWindow = 1024;
/// The same window for the `patent` profile (each candidate costs O(length)).
inline constexpr std::int64_t kPatentOptimalWindow = 64;

/// Greedy: at each point the longest exact segment.
/// Linear profiles: SegmentRecognizer runs until the word stops being a
/// digital straight segment (validity is not monotone in the length, so it
/// keeps going past invalid prefixes), then cuts at the longest valid prefix.
/// Two axes: segments of up to 12 steps are decided by a table made once
/// of exact words, longer ones run by run with multiplications only.
/// Complexity: O(log h) per run read; a step is read again only when it lies
/// past the cut but inside the broken DSS (about one period of the line).
/// `patent` profile (PatentRecognizer, recognizer.hpp): the steps within the
/// hard limits are read, then candidates from the longest (at most
/// kPatentMaxSegment) down, each checked in O(length) with an early exit on
/// the first contradiction. The driver itself does not look at the profile.
class GreedySegmenter {
public:
    GreedySegmenter(Profile p, int axes) : profile_(p), axes_(axes) {}
    /// Appends the segments of `steps` to `out`.
    void run(std::span<const Step> steps, std::vector<Segment>& out) const;
    /// Length of the longest exact segment starting at steps[0] (>= 1 for
    /// non-empty input).
    std::int64_t longest(std::span<const Step> steps) const;

private:
    Profile profile_;
    int axes_;
};

/// Optimal: fewest exact segments, by a shortest path over the DAG whose
/// edges are exact segments. For each start the recognizer enumerates the
/// valid ends until the DSS breaks or kOptimalWindow ticks pass
/// (kPatentOptimalWindow for `patent`); the greedy cut's segments are added as
/// edges too, so the result never has more segments than greedy and is the
/// exact minimum whenever no exact segment is longer than the window.
/// Complexity: O(n · min(W, DSS length) · log h) time, O(n) memory.
class OptimalSegmenter {
public:
    OptimalSegmenter(Profile p, int axes) : profile_(p), axes_(axes) {}
    void run(std::span<const Step> steps, std::vector<Segment>& out) const;

private:
    Profile profile_;
    int axes_;
};

/// Patent SU 1089551 approximation mode (Fig. 5, see patent_approximate()),
/// then made exact under the container's profile: each read-out piece that is
/// not one exact segment is cut greedily inside the piece. Stats: a piece is
/// counted exact when its read-out totals at the profile's default phase
/// expand to exactly its steps; the deviation is measured at that phase.
/// Errors: Errc::unsupported for a chain the approximation mode cannot read
/// (more than two axes, or a diagonal step).
/// Complexity: O(n) for the mode plus greedy inside the pieces.
class PatentSegmenter {
public:
    PatentSegmenter(Profile p, int axes) : profile_(p), axes_(axes) {}
    Result<void> run(std::span<const Step> steps, std::vector<Segment>& out,
                     SegmentStats* stats) const;

private:
    Profile profile_;
    int axes_;
};

}  // namespace stepzip
