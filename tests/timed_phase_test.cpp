// Phase prediction of timed chains (docs/FORMAT.md "Timed phases").
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../src/container/modeled_block.hpp"
#include "../src/container/timed_phase.hpp"
#include "stepzip/document.hpp"
#include "stepzip/segmenter.hpp"

namespace stepzip::stz {
namespace {

Block timed_block(const char* name) {
    std::ifstream f(std::string(STEPZIP_SOURCE_DIR) + "/corpora/timed/" + name, std::ios::binary);
    std::ostringstream s;
    s << f.rdbuf();
    BlockReader r(InputFormat::timed, name);
    EXPECT_TRUE(r.feed(s.str(), true).ok());
    Block b;
    EXPECT_TRUE(r.next(b));
    return b;
}

std::vector<Step> expand_all(Profile p, int axes, const std::vector<Segment>& segs) {
    std::vector<Step> out;
    for (const Segment& s : segs) expand_segment(p, s, axes, out);
    return out;
}

TEST(TimedPhase, PredictsTheFirstStepFromTheLastOne) {
    // An axis that stepped 2 steps before the segment (a = 1 step without a
    // move after it), at a new rate of 1 move in 5: next move at step 3.
    TimedPhase tp;
    tp.reset();
    Segment before;
    before.delta = {2, 1, 0};
    before.phase[0] = -1;  // eval8: moves on the first step
    tp.advance(Profile::eval8, before, 3);
    Segment seg;
    seg.delta = {10, 2, 0};
    const std::int64_t ph = tp.predict(Profile::eval8, seg, 3, 0);
    std::vector<Step> steps;
    seg.phase[0] = ph;
    expand_segment(Profile::eval8, seg, 3, steps);
    ASSERT_EQ(steps.size(), 10u);
    int first = -1;
    for (int k = 0; k < 10 && first < 0; ++k)
        if (step_axis(steps[static_cast<std::size_t>(k)], 1) != 0) first = k;
    EXPECT_EQ(first, 3);
    // Nothing known after a reset: the profile's default.
    tp.reset();
    EXPECT_EQ(tp.predict(Profile::grbl, seg, 3, 0), default_phase(Profile::grbl, 10, 2));
}

TEST(TimedPhase, AlignmentKeepsTheStepsAndMovesPhasesTowardThePrediction) {
    for (const char* name : {"trapezoid-2axis.steps", "trapezoid-3axis.steps"}) {
        const Block b = timed_block(name);
        ASSERT_EQ(b.chains.size(), 1u);
        std::vector<Segment> segs;
        ASSERT_TRUE(segment_steps(b.chains[0].steps, b.axes, Profile::eval8, SegmenterKind::greedy, segs).ok());
        std::vector<Segment> aligned = segs;
        align_timed_phases(Profile::eval8, b.axes, aligned);
        ASSERT_EQ(aligned.size(), segs.size());
        EXPECT_EQ(expand_all(Profile::eval8, b.axes, aligned), b.chains[0].steps) << name;
        // Distance of each phase from its prediction, before and after.
        TimedPhase before, after;
        before.reset();
        after.reset();
        std::uint64_t dist_before = 0, dist_after = 0, exact = 0, phases = 0;
        for (std::size_t k = 0; k < segs.size(); ++k) {
            EXPECT_EQ(segs[k].delta, aligned[k].delta);
            for (int j = 0; j < b.axes - 1; ++j) {
                const auto ab = phase_arguments(Profile::eval8, segs[k], b.axes, j);
                const PhaseRange r = phase_range(Profile::eval8, ab->first, ab->second);
                if (r.hi - r.lo == 1) continue;
                ++phases;
                dist_before += static_cast<std::uint64_t>(
                    std::llabs(segs[k].phase[j] - before.predict(Profile::eval8, segs[k], b.axes, j)));
                const std::int64_t d = aligned[k].phase[j] - after.predict(Profile::eval8, aligned[k], b.axes, j);
                dist_after += static_cast<std::uint64_t>(std::llabs(d));
                exact += d == 0;
            }
            before.advance(Profile::eval8, segs[k], b.axes);
            after.advance(Profile::eval8, aligned[k], b.axes);
        }
        ASSERT_GT(phases, 1000u) << name;
        EXPECT_LT(dist_after, dist_before) << name;
        EXPECT_GT(exact * 5, phases) << name << ": predicted exactly " << exact << " of " << phases;
    }
}

TEST(TimedPhase, SegmentModelDecodesOnlyWithTheSameMode) {
    const Block b = timed_block("trapezoid-2axis.steps");
    std::vector<std::vector<Segment>> cut(1);
    ASSERT_TRUE(segment_steps(b.chains[0].steps, b.axes, Profile::eval8, SegmenterKind::greedy, cut[0]).ok());
    align_timed_phases(Profile::eval8, b.axes, cut[0]);
    const std::string timed = write_segment_model(b, Profile::eval8, cut, nullptr, true);
    const std::string plain = write_segment_model(b, Profile::eval8, cut, nullptr, false);
    EXPECT_LT(timed.size(), plain.size());
    Block out;
    BlockCounts counts;
    ASSERT_TRUE(read_segment_model(timed, Profile::eval8, b.axes, true, out, counts, "t", nullptr, nullptr, true).ok());
    EXPECT_EQ(out.chains, b.chains);
    EXPECT_EQ(out.layout, b.layout);
    // Read without the prediction, the same payload does not give the chains.
    Block wrong;
    BlockCounts c2;
    const auto r = read_segment_model(timed, Profile::eval8, b.axes, true, wrong, c2, "t", nullptr, nullptr, false);
    EXPECT_TRUE(!r.ok() || wrong.chains != b.chains);
}

}  // namespace
}  // namespace stepzip::stz
