// Greedy cut of two-axis chains under a linear profile (not installed).
//
// On two axes every linear profile reduces to one two-letter word: under
// eval4 letter 0 is an x-step and letter 1 a y-step; under the 8-connected
// profiles letter 1 is a diagonal and letter 0 a step on one axis (the
// leading axis moves on every tick, so its own word is all ones). A segment
// holds at most two distinct step values, one per letter, and they must be
// compatible (one sign per axis; for the 8-connected profiles the axis step
// is a projection of the diagonal). TwoAxisGreedy reads runs of identical
// steps into the kernel's run state (dss.hpp, as RunWord; no per-axis loops,
// no profile switches) and decides each run with multiplications only; a
// division is needed only on the run where the word stops being a digital
// straight segment or where the run's last step is not a valid end. A word
// whose first kShortLetters letters are balanced starts from the state after
// their leading runs, made once per such word (the same reading, tabled). Its
// answers are those of RunSegment and of the letter-by-letter
// SegmentRecognizer (tests/recognizer_test.cpp, tests/segmenter_two_axis_test.cpp).
// Invariant: longest() returns RunSegment's (and SegmentRecognizer's) longest
// exact prefix. Complexity: O(log h) per run, h = hull vertices; fit() is
// O(runs).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "dss.hpp"
#include "stepzip/profile.hpp"
#include "stepzip/segment.hpp"
#include "stepzip/step.hpp"

namespace stepzip::detail {

class TwoAxisGreedy {
public:
    /// Precondition: p is not Profile::patent.
    explicit TwoAxisGreedy(Profile p);
    /// Length of the longest exact segment at steps[0] (>= 1; 0 for empty
    /// input). The steps must be valid for the profile on two axes.
    std::int64_t longest(std::span<const Step> steps);
    /// fit_segment(p, steps.first(m), 2), for m = longest(steps) called just
    /// before on the same steps (it reuses the runs that call read).
    /// nullopt only if the prefix is not one exact segment.
    std::optional<Segment> fit(std::int64_t m) const;

private:
    // A run of k letters `letter`: returns how many keep the word a DSS and
    // sets `best` to the largest valid prefix length of the run (0: none),
    // with multiplications only unless the run is cut.
    std::int64_t read_run(int letter, std::int64_t k, std::int64_t& best) const noexcept;
    // Reads a whole run of k letters `letter` (its step already admitted)
    // after `length` letters: records it, moves `best` and best_count_ to
    // the longest valid prefix; false when the word stops in it.
    bool take_run(int letter, std::int64_t k, std::int64_t& length, std::int64_t& best);
    // Starts the run reading at letter 0 (first letter `first`).
    void start_runs(int first);
    struct Resume;
    static const std::vector<Resume>& resume_table();


    Profile profile_;
    bool eight_;
    dss::RunState st_;  // hulls and slope bounds, as RunWord's (dss.hpp)
    // The runs read by the last longest(): letter of the first run, run
    // lengths (letters alternate), the step value of each letter.
    int first_letter_ = 0;
    std::vector<std::int64_t> runs_;
    Step value_[2] = {0, 0};
    std::int64_t best_count_[2] = {0, 0};  // letters of the longest valid prefix
    // The last longest() was decided by the short-word table: its letters.
    bool short_ = false;
    unsigned short_bits_ = 0;
};

// The state after a word's leading runs (all but its last), kept for the
// balanced words of kShortLetters letters (two_axis.cpp).
struct TwoAxisGreedy::Resume {
    dss::RunState st;
    int first_letter = 0;
    std::vector<std::int64_t> runs;
    std::int64_t best = 0, best_count[2] = {0, 0}, length = 0;
};

}  // namespace stepzip::detail
