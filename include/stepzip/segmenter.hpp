// stepzip — reverse interpolation: steps -> segments.
//
// Roles (STYLE.md): Segment is the result; a SegmentRecognizer grows one
// segment online (extend / can_extend); GreedySegmenter, OptimalSegmenter and
// PatentSegmenter cut a whole chain. This header is the stable entry point.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "stepzip/error.hpp"
#include "stepzip/interpolate/segment.hpp"
#include "stepzip/profile.hpp"
#include "stepzip/segment.hpp"
#include "stepzip/step.hpp"

namespace stepzip {

/// How a chain is cut. The numeric values are not stored in files.
enum class SegmenterKind : std::uint8_t {
    greedy = 0,   ///< longest exact segment at each point; O(1) amortized per step
    optimal = 1,  ///< fewest exact segments (shortest path over exact segments)
    patent = 2,   ///< SU 1089551 approximation mode (Fig. 5), then made exact
};

std::string_view segmenter_name(SegmenterKind k) noexcept;
std::optional<SegmenterKind> parse_segmenter(std::string_view name) noexcept;

/// What the patent segmenter observed (zero for the other segmenters).
struct SegmentStats {
    std::uint64_t patent_segments = 0;  ///< segments the approximation mode read out
    std::uint64_t patent_exact = 0;     ///< of those, reproduced exactly as read out
    std::int64_t patent_max_deviation = 0;  ///< largest Chebyshev distance, in steps, between
                                            ///< the input path and the forward path of a read-out
                                            ///< segment, compared tick by tick
    SegmentStats& operator+=(const SegmentStats& o) noexcept {
        patent_segments += o.patent_segments;
        patent_exact += o.patent_exact;
        if (o.patent_max_deviation > patent_max_deviation)
            patent_max_deviation = o.patent_max_deviation;
        return *this;
    }
};

/// Checks that profile `p` can represent `steps` on `axes` axes: the axis
/// count is supported and, for a 4-connected profile, every step moves one
/// axis. Errors: Errc::invalid_argument (axes), Errc::connectivity naming the
/// 1-based index of the first offending step.
Result<void> profile_accepts(Profile p, std::span<const Step> steps, int axes);

/// Reverse interpolation of one chain's steps under profile `p`.
/// Appends to `out` segments such that expanding them in order with
/// expand_segment(p, ...) gives exactly `steps`, and every one of them passes
/// check_segment(). Each segment's phase is the valid phase nearest to the
/// profile's default (the lower one on a tie), so a stream made by the
/// profile's own interpolator costs no phase.
/// Errors: as profile_accepts(). Thread-safe (no shared state).
/// Does not promise a particular cut beyond the segmenter's stated goal.
Result<void> segment_steps(std::span<const Step> steps, int axes, Profile p, SegmenterKind kind,
                           std::vector<Segment>& out, SegmentStats* stats = nullptr);

/// SU 1089551 approximation mode exactly as the patent's Fig. 5, on a
/// two-axis 4-connected first-quadrant-normalized chain: counters count up
/// from 0, F = 0; an x-step belongs to the segment if F <= 0, a y-step if
/// F >= 0; x-step: F += Y, y-step: F -= X (accumulated counters). A step
/// that violates the rule still updates the counters and ends the segment.
/// Appends each segment's per-axis totals (signs restored) to `ends` and,
/// when given, F after every step to `trace`.
/// Errors: Errc::connectivity for a diagonal step, Errc::invalid_argument
/// for more than two axes.
Result<void> patent_approximate(std::span<const Step> steps, std::vector<Point>& ends,
                                std::vector<std::int64_t>* trace = nullptr);

}  // namespace stepzip
