// The tick block (docs/FORMAT.md 1.13, block type 7 subtype 2; 5 with the
// planner model, 1.16) and the interrupt block (1.14, subtypes 1 and 6): round trips
// of blocks on every axis count (chains, empty chains, reversals, layouts,
// idle stretches), of whole frames cut into many blocks at every tier, what
// a constant rate costs, and its corrupt cases named by payload byte.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "../src/common/bytes.hpp"
#include "../src/container/block_codec.hpp"
#include "../src/container/timed_tick.hpp"
#include "stepzip/container.hpp"
#include "stepzip/document.hpp"
#include "support/block_records.hpp"
#include "support/files.hpp"
#include "support/proved.hpp"

namespace stepzip {
namespace {

// A timed chain on `axes` axes (axis 0 time): stretches of constant rate
// per axis, rests, reversals; the rates and lengths vary with the seed.
Chain timed_chain(std::mt19937& rng, int axes, std::size_t ticks, Point start) {
    Chain c;
    c.axes = axes;
    c.start = start;
    std::vector<double> rate(static_cast<std::size_t>(axes)), acc(static_cast<std::size_t>(axes));
    std::vector<int> dir(static_cast<std::size_t>(axes), 1);
    while (c.steps.size() < ticks) {
        // A stretch: every axis a rate in (0, 1] or a rest, maybe a reversal.
        const std::size_t len = 20 + rng() % 400;
        for (int a = 1; a < axes; ++a) {
            const auto ua = static_cast<std::size_t>(a);
            rate[ua] = rng() % 4 == 0 ? 0.0 : 1.0 / (1 + rng() % 12) + (rng() % 100) * 1e-4;
            if (rng() % 5 == 0) dir[ua] = -dir[ua];
        }
        for (std::size_t t = 0; t < len && c.steps.size() < ticks; ++t) {
            int d[kMaxAxes] = {1};
            for (int a = 1; a < axes; ++a) {
                const auto ua = static_cast<std::size_t>(a);
                acc[ua] += rate[ua];
                if (acc[ua] >= 1) {
                    acc[ua] -= 1;
                    d[a] = dir[ua];
                }
            }
            c.steps.push_back(make_step(d, axes));
        }
    }
    return c;
}

using stz::TickCoding;
constexpr TickCoding kCodings[] = {TickCoding::plain, TickCoding::mixed, TickCoding::mixed_sure};

// The coding byte for `coding` and `flags`: the flags that go with the coding (tick_flags()),
// but the planner model and its slot lines, which the subtype and the model byte carry.
unsigned coding_byte(TickCoding coding, unsigned flags) {
    return static_cast<unsigned>(coding) | (flags & stz::tick_flags(coding) & ~(stz::kTickPlanner | stz::kTickSlots));
}

// The model byte of a block of `coding` and `flags` (`irq`: an interrupt
// block) with the planner model: 2 with slot lines (an interrupt block with
// a mixed coding), else 1.
unsigned model_byte(TickCoding coding, bool irq, unsigned flags) {
    return irq && coding != TickCoding::plain && (flags & stz::kTickSlots) ? 2u : 1u;
}

// The subtype of a tick block (`irq`: an interrupt block) of `flags`.
unsigned subtype_of(bool irq, unsigned flags) {
    if (flags & stz::kTickPlanner) return irq ? stz::kInterruptPlannerSubtype : stz::kTickPlannerSubtype;
    return irq ? stz::kInterruptSubtype : stz::kTickSubtype;
}

Block round_trip(const Block& in, TickCoding coding = TickCoding::plain, bool irq = false, unsigned flags = stz::kTickFlags) {
    const std::string payload =
        irq ? stz::write_interrupt_block(in, coding, flags) : stz::write_tick_block(in, coding, flags);
    EXPECT_FALSE(payload.empty());
    EXPECT_EQ(static_cast<unsigned char>(payload[0]), subtype_of(irq, flags));
    EXPECT_EQ(static_cast<unsigned char>(payload[1]), coding_byte(coding, flags));
    if (flags & stz::kTickPlanner) EXPECT_EQ(static_cast<unsigned char>(payload[2]), model_byte(coding, irq, flags));
    Block out;
    stz::BlockCounts counts;
    auto r = stz::read_tick_block(payload, in.axes, true, out, counts, "test");
    EXPECT_TRUE(r.ok()) << r.error().message;
    std::uint64_t steps = 0;
    for (const Chain& c : in.chains) steps += c.steps.size();
    EXPECT_EQ(counts.chains, in.chains.size());
    EXPECT_EQ(counts.steps, steps);
    EXPECT_EQ(counts.segments, 0u);
    return out;
}

// The payload size of `b` as a tick block (`irq`: an interrupt block) of
// `coding` and `flags`.
std::size_t coded_size(const Block& b, TickCoding coding, bool irq, unsigned flags) {
    return (irq ? stz::write_interrupt_block(b, coding, flags) : stz::write_tick_block(b, coding, flags)).size();
}

TEST(TickBlock, BlocksOnEveryAxisCountRoundTrip) {
    std::mt19937 rng(7);
    for (int axes = 2; axes <= kMaxAxes; ++axes)
        for (int variant = 0; variant < 3; ++variant) {
            Block b;
            b.axes = axes;
            Point start{};
            start[0] = 1000 * variant;
            start[1] = -37;
            b.chains.push_back(timed_chain(rng, axes, 3000 + 1000 * static_cast<std::size_t>(variant), start));
            if (variant >= 1) {
                b.chains.push_back(Chain{axes, b.chains.back().end(), {}});  // an empty chain
                Point far = b.chains.back().start;
                far[1] += 123456;
                b.chains.push_back(timed_chain(rng, axes, 1500, far));
            }
            if (variant == 2) b.layout = std::string("\x01\x05\x02\x07\x01", 5);  // opaque to the block
            for (const bool irq : {false, true})
                for (const unsigned flags : {0u, stz::kTickRestart, stz::kTickGuess, stz::kTickGuided,
                                             stz::kTickRestart | stz::kTickGuided, stz::kTickMatch,
                                             stz::kTickGuess | stz::kTickMatch, stz::kTickRefine, stz::kTickPlanner,
                                             stz::kTickPlanner | stz::kTickGuess, stz::kTickPlanner | stz::kTickSlots,
                                             stz::kTickFlags, stz::kTickFlags & ~stz::kTickSlots,
                                             stz::kTickFlags & ~stz::kTickPlanner})
                    for (const TickCoding coding : kCodings) {
                        const Block out = round_trip(b, coding, irq, flags);
                        EXPECT_EQ(out.chains, b.chains) << "axes " << axes << " variant " << variant << " coding "
                                                        << static_cast<unsigned>(coding) << " irq " << irq
                                                        << " flags " << flags;
                        EXPECT_EQ(out.layout, b.layout);
                        EXPECT_EQ(out.axes, axes);
                    }
        }
}

// A thread's contexts are reused by its next block, reset and sized to that
// block's axes: a block codes to the same bytes after blocks of more and of
// fewer axes (plain and mixed), and each decodes.
TEST(TickBlock, ContextsReusedAcrossBlocksCodeEveryBlockAsAFreshOne) {
    std::mt19937 rng(11);
    std::vector<Block> blocks;
    for (int axes : {3, kMaxAxes, 2, 4}) {
        Block b;
        b.axes = axes;
        b.chains.push_back(timed_chain(rng, axes, 4000, Point{}));
        blocks.push_back(std::move(b));
    }
    for (const TickCoding coding : kCodings) {
        std::vector<std::string> first;
        for (const Block& b : blocks) first.push_back(stz::write_tick_block(b, coding));
        for (std::size_t round = 0; round < 2; ++round)
            for (std::size_t i = blocks.size(); i-- > 0;) {  // in the other order
                EXPECT_EQ(stz::write_tick_block(blocks[i], coding), first[i])
                    << "block " << i << " coding " << static_cast<unsigned>(coding);
                EXPECT_EQ(round_trip(blocks[i], coding).chains, blocks[i].chains);
            }
    }
}

// A stepper interrupt's steps: each axis steps at floor(T) of a time T
// advanced by a period that changes every 250 ticks by a small amount
// (a ramp, then a cruise, then a ramp down), the axes' periods in a fixed
// ratio.
Block ramp_block() {
    Block b;
    b.axes = 3;
    Chain c;
    c.axes = 3;
    double period = 40.0, next_x = 3.3, next_y = 7.9;
    for (std::size_t t = 0; t < 60000; ++t) {
        if (t % 250 == 0) period += t < 20000 ? -0.35 : t < 40000 ? 0.0 : 0.35;
        int d[kMaxAxes] = {1, 0, 0};
        if (static_cast<double>(t) >= next_x) {
            d[1] = 1;
            next_x += period / 4;
        }
        if (static_cast<double>(t) >= next_y) {
            d[2] = -1;
            next_y += period * 0.7;
        }
        c.steps.push_back(make_step(d, 3));
    }
    b.chains.push_back(std::move(c));
    return b;
}

// A line that breaks where the rate changed restarts at its last step (the
// flag kTickRestart) instead of keeping the old rate's letters: both
// decode, and the restarting lines code the ramp smaller, plain and mixed
// (here 1-2 %; 4-11 % on the timed streams of docs/benchmarks.md).
TEST(TickBlock, LinesThatRestartAtTheirLastStepCodeARampSmaller) {
    const Block b = ramp_block();
    for (const TickCoding coding : {TickCoding::plain, TickCoding::mixed_sure}) {
        EXPECT_EQ(round_trip(b, coding, false, stz::kTickRestart).chains, b.chains);
        EXPECT_EQ(round_trip(b, coding, true, stz::kTickRestart).chains, b.chains);
        const std::size_t keep = stz::write_tick_block(b, coding, 0).size();
        const std::size_t restart = stz::write_tick_block(b, coding, stz::kTickRestart).size();
        EXPECT_LT(restart, keep) << "coding " << static_cast<unsigned>(coding);
    }
}

// The guess flag: after a break a line guesses its rate from the two lines
// before (the ramp's rate changes by a constant step) and mixed contexts
// take the letter that rate gives next; an interrupt block's follower also
// where its Bresenham line crosses to its next step. Both blocks decode and
// code the ramp at least 3 % smaller with it, under both mixed codings.
TEST(TickBlock, LinesThatGuessTheirRateCodeARampSmaller) {
    const Block b = ramp_block();
    for (const TickCoding coding : {TickCoding::mixed, TickCoding::mixed_sure})
        for (const bool irq : {false, true}) {
            EXPECT_EQ(round_trip(b, coding, irq, stz::kTickFlags).chains, b.chains);
            const auto size = [&](unsigned flags) { return coded_size(b, coding, irq, flags); };
            // 5.8-6.3 % here (without the guess's information: 0 or larger).
            EXPECT_LT(size(stz::kTickRestart | stz::kTickGuess) * 100, size(stz::kTickRestart) * 97)
                << "coding " << static_cast<unsigned>(coding) << " irq " << irq;
        }
    // On the plain coding the flag is not written: the same bytes.
    EXPECT_EQ(stz::write_tick_block(b, TickCoding::plain, stz::kTickRestart | stz::kTickGuess),
              stz::write_tick_block(b, TickCoding::plain, stz::kTickRestart));
}

// The planner model (kTickPlanner, docs/FORMAT.md 1.16) with the mixed
// codings: each axis's segment clock starts the line the next stepper
// segment would run, whose letter and probability go to the contexts, the
// mixers' direct input and coding 2's map of the sure decisions. On the
// ramp of fixed-time segments both blocks decode and code it at least 12 %
// smaller (14.5-16 % here; without the clock 10-11.5 %, without the direct
// input 1-2 %). On the plain coding only the leader changes, which on the
// ramp (whose axes keep their order) costs the model byte alone.
TEST(TickBlock, PlannerModelCodesASegmentRampSmaller) {
    const Block b = ramp_block();
    for (const TickCoding coding : {TickCoding::mixed, TickCoding::mixed_sure})
        for (const bool irq : {false, true}) {
            EXPECT_EQ(round_trip(b, coding, irq, stz::kTickFlags).chains, b.chains);
            const auto size = [&](unsigned flags) { return coded_size(b, coding, irq, flags); };
            const std::size_t with = size(stz::kTickFlags), without = size(stz::kTickFlags & ~stz::kTickPlanner);
            EXPECT_LT(with * 100, without * 88) << "coding " << static_cast<unsigned>(coding) << " irq " << irq << ": "
                                                << with << " against " << without;
        }
    EXPECT_EQ(stz::write_tick_block(b, TickCoding::plain, stz::kTickFlags).size(),
              stz::write_tick_block(b, TickCoding::plain, stz::kTickFlags & ~stz::kTickPlanner).size() + 1);
}

// The planner model's leader (every coding): the axis of the shortest mean
// of its last four intervals, not the one whose last interval was the
// shortest, so that on a near-diagonal move the leader and its followers'
// Bresenham lines do not swap every few steps. The plain coding of the
// no-AMASS log of corpora/timed is at least 8 % smaller with it (11.7 %
// for the tick block and 14.5 % for the interrupt block here).
TEST(TickBlock, PlannerLeaderCodesANearDiagonalLogSmaller) {
    auto chains = read_chains(InputFormat::timed, test::corpus("timed/heldout-noamass.steps"));
    ASSERT_TRUE(chains.ok()) << chains.error().message;
    Block b;
    b.axes = chains->front().axes;
    b.chains = std::move(*chains);
    for (const bool irq : {false, true}) {
        EXPECT_EQ(round_trip(b, TickCoding::plain, irq, stz::kTickFlags).chains, b.chains);
        const auto size = [&](unsigned flags) { return coded_size(b, TickCoding::plain, irq, flags); };
        const std::size_t with = size(stz::kTickFlags), without = size(stz::kTickFlags & ~stz::kTickPlanner);
        EXPECT_LT(with * 100, without * 92) << "irq " << irq << ": " << with << " against " << without;
    }
}

// The guided flag: the guessed letter, the admitted sets and the step
// against the rate's trend choose the mixers' weight sets and a second
// map's row, and the block's mixers and maps learn faster. Both blocks
// decode and code the ramp at least 5 % smaller with it, under both mixed
// codings (9-10 % here; by the faster rates alone, without guide(), 0-0.5 %).
TEST(TickBlock, GuidedMixingCodesARampSmaller) {
    const Block b = ramp_block();
    for (const TickCoding coding : {TickCoding::mixed, TickCoding::mixed_sure})
        for (const bool irq : {false, true}) {
            const auto size = [&](unsigned flags) { return coded_size(b, coding, irq, flags); };
            const std::size_t guided = size(stz::kTickRestart | stz::kTickGuess | stz::kTickGuided),
                              unguided = size(stz::kTickRestart | stz::kTickGuess);
            EXPECT_LT(guided * 100, unguided * 95) << "coding " << static_cast<unsigned>(coding) << " irq " << irq
                                                    << ": " << guided << " against " << unguided;
        }
    EXPECT_EQ(stz::write_tick_block(b, TickCoding::plain, stz::kTickRestart | stz::kTickGuided),
              stz::write_tick_block(b, TickCoding::plain, stz::kTickRestart));
}

// The match flag (the mixed codings) and the refine flag (the plain one):
// a log that repeats itself (a job run twice; here 20 000 ticks whose axes
// step after random intervals of 2-20 ticks, twice in one chain) is found
// in the block's earlier ticks and each repeated tick predicted by the one
// that followed there. Both blocks decode under every coding, and the
// repeat costs under half of what it costs without the flag (without it
// 415-1059 bytes, the first time 2.1 KB); each flag is written with its
// codings only.
// 20 000 ticks whose two axes step after random intervals of 2-20 ticks.
Chain random_intervals() {
    std::mt19937 rng(29);
    Chain c;
    c.axes = 3;
    std::array<int, 3> next{0, 2, 5};
    for (int t = 0; t < 20000; ++t) {
        int d[kMaxAxes] = {1};
        for (int a = 1; a < 3; ++a)
            if (t == next[static_cast<std::size_t>(a)]) {
                d[a] = a == 1 ? 1 : -1;
                next[static_cast<std::size_t>(a)] += 2 + static_cast<int>(rng() % 19);
            }
        c.steps.push_back(make_step(d, 3));
    }
    return c;
}

TEST(TickBlock, MatchFlagCodesARepeatedLogForLittle) {
    const Chain c = random_intervals();
    Block once;
    once.axes = 3;
    once.chains.push_back(c);
    Block twice = once;
    twice.chains[0].steps.insert(twice.chains[0].steps.end(), c.steps.begin(), c.steps.end());
    constexpr unsigned kWithout = stz::kTickRestart | stz::kTickGuess | stz::kTickGuided;
    for (const TickCoding coding : kCodings)
        for (const bool irq : {false, true}) {
            EXPECT_EQ(round_trip(twice, coding, irq, stz::kTickFlags).chains, twice.chains);
            const auto size = [&](const Block& b, unsigned flags) {
                return (irq ? stz::write_interrupt_block(b, coding, flags) : stz::write_tick_block(b, coding, flags)).size();
            };
            const std::size_t repeat = size(twice, stz::kTickFlags) - size(once, stz::kTickFlags);
            const std::size_t repeat_without = size(twice, kWithout) - size(once, kWithout);
            EXPECT_LT(repeat * 2, repeat_without) << "coding " << static_cast<unsigned>(coding) << " irq " << irq
                                                  << ": " << repeat << " bytes against " << repeat_without
                                                  << ", once " << size(once, stz::kTickFlags);
        }
    // The match flag is not written on the plain coding, the refine flag
    // on a mixed one.
    EXPECT_EQ(stz::write_tick_block(twice, TickCoding::plain, stz::kTickRestart | stz::kTickMatch),
              stz::write_tick_block(twice, TickCoding::plain, stz::kTickRestart));
    EXPECT_EQ(stz::write_tick_block(twice, TickCoding::mixed, stz::kTickFlags),
              stz::write_tick_block(twice, TickCoding::mixed, stz::kTickFlags & ~stz::kTickRefine));
}

// The window bit: the same log in a block of its own after a block that
// holds it (a job run again farther back than a block). Coded from the
// window's ticks the copy costs under a third of what the block costs
// alone, under every coding; it decodes with its window, and is refused at
// its coding byte without one. The writer drops the bit where it cannot
// apply: no ticks in the window, no match or refine flag.
TEST(TickBlock, WindowBitFindsARepeatInTheBlockBefore) {
    Block once;
    once.axes = 3;
    once.chains.push_back(random_intervals());
    auto before = std::make_shared<stz::WindowBlock>();
    before->ticks = stz::tick_masks(once);
    ASSERT_EQ(before->ticks.size(), once.chains[0].steps.size());
    const stz::WindowView window{before};
    const stz::WindowView no_ticks{std::make_shared<stz::WindowBlock>()};
    constexpr unsigned kWith = stz::kTickFlags | stz::kTickWindow;
    for (const TickCoding coding : kCodings)
        for (const bool irq : {false, true}) {
            const unsigned match = coding == TickCoding::plain ? stz::kTickRefine : stz::kTickMatch;
            const auto write = [&](unsigned flags, const stz::WindowView* w) {
                return irq ? stz::write_interrupt_block(once, coding, flags, w) : stz::write_tick_block(once, coding, flags, w);
            };
            const std::string with = write(kWith, &window), alone = write(stz::kTickFlags, nullptr);
            ASSERT_FALSE(with.empty());
            EXPECT_EQ(static_cast<unsigned char>(with[1]), coding_byte(coding, kWith));
            EXPECT_LT(with.size() * 3, alone.size()) << "coding " << static_cast<unsigned>(coding) << " irq " << irq
                                                     << ": " << with.size() << " bytes against " << alone.size();
            Block out;
            stz::BlockCounts counts;
            auto r = stz::read_tick_block(with, 3, true, out, counts, "P", &window);
            ASSERT_TRUE(r.ok()) << r.error().message;
            EXPECT_EQ(out.chains, once.chains);
            Block lost;
            auto refused = stz::read_tick_block(with, 3, true, lost, counts, "P");
            ASSERT_FALSE(refused.ok());
            EXPECT_EQ(refused.error().code, Errc::corrupt);
            EXPECT_EQ(refused.error().message, "P byte 1: the match reads the window of a block not flagged window");
            EXPECT_EQ(write(kWith, &no_ticks), alone);
            EXPECT_EQ(write(kWith, nullptr), alone);
            EXPECT_EQ(write(kWith & ~match, &window), write(stz::kTickFlags & ~match, nullptr));
        }
}

TEST(TickBlock, EmptyBlockAndIdleChainRoundTrip) {
    Block empty;
    empty.axes = 3;
    for (const TickCoding coding : kCodings) EXPECT_TRUE(round_trip(empty, coding).chains.empty());
    Block idle;
    idle.axes = 3;
    idle.chains.push_back(Chain{3, Point{}, std::vector<Step>(50000, make_step2(1, 0))});
    for (const TickCoding coding : kCodings) EXPECT_EQ(round_trip(idle, coding).chains, idle.chains);
}

TEST(TickBlock, StepThatDoesNotAdvanceTimeIsNotATickBlock) {
    Block b;
    b.axes = 3;
    int d[kMaxAxes] = {0, 1, 0};
    b.chains.push_back(Chain{3, Point{}, {make_step2(1, 1), make_step(d, 3)}});
    EXPECT_TRUE(stz::write_tick_block(b).empty());
}

// A constant rate costs almost nothing: its line admits one letter on
// nearly every tick.
TEST(TickBlock, ConstantRateCostsAlmostNothing) {
    for (double rate : {1.0 / 7, 0.3183, 0.05}) {
        Block b;
        b.axes = 3;
        Chain c{3, Point{}, {}};
        double acc = 0.5;
        for (int t = 0; t < 200000; ++t) {
            acc += rate;
            int d[kMaxAxes] = {1, 0, 0};
            if (acc >= 1) {
                acc -= 1;
                d[1] = 1;
            }
            c.steps.push_back(make_step(d, 3));
        }
        b.chains.push_back(std::move(c));
        const std::string payload = stz::write_tick_block(b);
        // 200000 ticks, thousands of steps: under a bit per 1000 ticks.
        EXPECT_LT(payload.size(), 150u) << "rate " << rate;
        EXPECT_EQ(round_trip(b).chains, b.chains);
    }
}

// A controller-like log: the leading axis at a rate that ramps every
// `seg` ticks, the other by Bresenham on its steps, DIR set ahead.
std::string controller_log(std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::string log;
    for (int move = 0; move < 6; ++move) {
        const long major = 300 + static_cast<long>(rng() % 900), minor = static_cast<long>(rng() % 300);
        const unsigned dirs = (rng() % 2 ? 2u : 0u) | (rng() % 2 ? 8u : 0u);
        log.append(5, static_cast<char>(dirs));
        double rate = 0.01, acc = 0;
        long done = 0, err = major / 2;
        while (done < major) {
            rate = std::min(0.3, rate + 0.004);
            for (int t = 0; t < 120 && done < major; ++t) {
                acc += rate;
                unsigned tick = dirs;
                if (acc >= 1) {
                    acc -= 1;
                    ++done;
                    tick |= 1u;
                    err -= minor;
                    if (err < 0) {
                        err += major;
                        tick |= 4u;
                    }
                }
                log.push_back(static_cast<char>(tick));
            }
        }
    }
    const auto first = log.find_first_of(std::string("\x01\x03\x04\x06\x05\x07\x0c\x0d\x0e\x0f\x09\x0b", 12));
    return log.substr(first);
}

// Tick blocks (and interrupt blocks, or only the subtype `only` when
// given, 1 or 2, with the planner model or not; of any coding, or only
// `coding` when given) of a one-frame version-2 file: its block records
// walked with the library's varint reader.
std::size_t tick_blocks(const std::string& frame, int only = -1, int coding = -1) {
    std::size_t n = 0;
    for (const test::BlockRecord& r : test::block_records(frame)) {
        if (r.payload.empty()) continue;
        const unsigned sub = static_cast<unsigned char>(r.payload[0]);
        const unsigned base = !stz::is_tick_subtype(sub)           ? sub
                              : stz::is_interrupt_subtype(sub) ? stz::kInterruptSubtype
                                                               : stz::kTickSubtype;
        if (r.type == stz::kExtended && (only < 0 ? stz::is_tick_subtype(sub) : base == static_cast<unsigned>(only)) &&
            (coding < 0 || (r.payload.size() > 1 && static_cast<unsigned char>(r.payload[1]) == static_cast<unsigned>(coding))))
            ++n;
    }
    return n;
}

// Mixed predictions (coding 1, the strong levels) learn a controller's
// patterns that the plain contexts do not see.
TEST(TickBlock, MixedCodingIsSmallerOnAControllerLog) {
    std::mt19937 rng(11);
    Block b;
    b.axes = 3;
    b.chains.push_back(timed_chain(rng, 3, 60000, Point{}));
    EXPECT_LT(stz::write_tick_block(b, TickCoding::mixed).size(), stz::write_tick_block(b, TickCoding::plain).size());
}

// Coding 2 (the strong levels) codes the sure decisions in their contexts
// alone: it differs from coding 1 (on a log most ticks are sure), and stays
// far below the plain coding and within 3 % of coding 1.
TEST(TickBlock, SureDecisionsCodedPlainStayNearTheMixedCoding) {
    std::mt19937 rng(11);
    Block b;
    b.axes = 3;
    b.chains.push_back(timed_chain(rng, 3, 60000, Point{}));
    const std::string plain = stz::write_tick_block(b, TickCoding::plain);
    const std::string mixed = stz::write_tick_block(b, TickCoding::mixed);
    const std::string sure = stz::write_tick_block(b, TickCoding::mixed_sure);
    EXPECT_NE(sure.substr(2), mixed.substr(2));
    EXPECT_LT(sure.size() * 100, mixed.size() * 103) << sure.size() << " vs " << mixed.size();
    EXPECT_LT(sure.size() * 100, plain.size() * 95) << sure.size() << " vs " << plain.size();
    EXPECT_EQ(round_trip(b, TickCoding::mixed_sure).chains, b.chains);
}

// Steps whose intervals jitter in a repeating pattern around a rate that
// ramps (an interrupt period sampled at a coarser tick): no straight line
// holds them, the mixed coding's interval contexts see them (more than
// eight intervals per axis, the pattern's shape repeating).
TEST(TickBlock, JitteredIntervalsRoundTripAndMixedCodingLearnsThem) {
    Block b;
    b.axes = 3;
    Chain c;
    c.axes = 3;
    const int jitter[] = {0, -1, 1, 0, 1, -1};
    std::size_t k = 0, next_x = 0, next_y = 3;
    for (std::size_t t = 0; t < 40000; ++t) {
        int d[kMaxAxes] = {1, 0, 0};
        if (t == next_x) {
            d[1] = 1;
            const std::size_t base = 12 + (t / 5000) % 6;  // the rate changes every 5000 ticks
            next_x = t + static_cast<std::size_t>(static_cast<int>(base) + jitter[k++ % 6]);
        }
        if (t == next_y) {
            d[2] = -1;
            next_y = t + 29 + (t / 1000) % 2;
        }
        c.steps.push_back(make_step(d, 3));
    }
    b.chains.push_back(std::move(c));
    for (const TickCoding coding : kCodings)
        EXPECT_EQ(round_trip(b, coding).chains, b.chains) << "coding " << static_cast<unsigned>(coding);
    EXPECT_LT(stz::write_tick_block(b, TickCoding::mixed).size(), stz::write_tick_block(b, TickCoding::plain).size());
}

TEST(TickBlock, FramesCutIntoManyBlocksRoundTripAtEveryTier) {
    for (std::uint32_t seed : {1u, 2u}) {
        const std::string log = controller_log(seed);
        ASSERT_GT(log.size(), 20000u);
        for (int level : {1, 3, 10, 19}) {
            CompressOptions opt;
            opt.format = InputFormat::timed;
            opt.level = level;
            opt.allow_raw = false;
            opt.block_steps = 1u << 13;  // chains continue across blocks
            auto z = compress(log, opt);
            ASSERT_TRUE(z.ok()) << z.error().message;
            EXPECT_GT(tick_blocks(*z), 1u) << "seed " << seed << " level " << level;
            // Plain contexts at -L 1 and 2, the mixed coding 2 from 3; lines
            // restarting, guessing their rate where mixed, and a match (from
            // the window's ticks after the first block).
            const auto coding = static_cast<int>(level >= 3 ? coding_byte(TickCoding::mixed_sure, stz::kTickFlags)
                                                            : coding_byte(TickCoding::plain, stz::kTickFlags));
            const std::size_t windowed = tick_blocks(*z, -1, coding | static_cast<int>(stz::kTickWindow));
            EXPECT_EQ(tick_blocks(*z, -1, coding) + windowed, tick_blocks(*z)) << "seed " << seed << " level " << level;
            auto back = decompress(*z);
            ASSERT_TRUE(back.ok()) << back.error().message;
            EXPECT_EQ(*back, log) << "seed " << seed << " level " << level;
        }
    }
}

// A job run again farther back than a block (a long capture): a log whose
// second half repeats the first (random_intervals() as STEP/DIR bytes),
// cut into blocks of half its ticks. The second block's match reads the
// first block's ticks (the frame's window; coding byte 126 from -L 3, 196
// at -L 1), and the frame is under 70 % of the same frame without a
// window. Both decode.
TEST(TickBlock, JobRunAgainInTheNextBlockIsFoundThroughTheWindow) {
    std::string log;
    for (const Step s : random_intervals().steps)  // STEP x = 1, DIR x = 2, STEP y = 4, DIR y = 8
        log.push_back(static_cast<char>((step_axis(s, 1) ? 1 : 0) | 2 | (step_axis(s, 2) ? 4 : 0)));
    log = log.substr(log.find_first_of("\x01\x03\x05\x07"));
    const std::string twice = log + log;
    for (int level : {1, 3}) {
        CompressOptions opt;
        opt.format = InputFormat::timed;
        opt.level = level;
        opt.allow_raw = false;
        opt.block_steps = log.size();  // a tick a byte
        auto z = compress(twice, opt);
        ASSERT_TRUE(z.ok()) << z.error().message;
        EXPECT_EQ(tick_blocks(*z), 2u);
        const int windowed = static_cast<int>(coding_byte(level >= 3 ? TickCoding::mixed_sure : TickCoding::plain,
                                                          stz::kTickFlags | stz::kTickWindow));
        EXPECT_EQ(tick_blocks(*z, -1, windowed), 1u) << "level " << level;
        auto back = decompress(*z);
        ASSERT_TRUE(back.ok()) << back.error().message;
        EXPECT_EQ(*back, twice);
        opt.window_log = 0;
        auto alone = compress(twice, opt);
        ASSERT_TRUE(alone.ok()) << alone.error().message;
        EXPECT_LT(z->size() * 10, alone->size() * 7) << "level " << level << ": " << z->size() << " bytes against "
                                                     << alone->size();
    }
}

// A block that becomes a raw one (random STEP/DIR bytes: the CM raw block
// wins) adds no ticks to the window, though the first pass of the blocks
// after it read them: the job after it, coded again from the window as the
// decoder sees it, still reads the job before (coding byte 126), and the
// frame decodes.
TEST(TickBlock, RawBlockInTheWindowAddsNoTicks) {
    std::string job;
    for (const Step s : random_intervals().steps)
        job.push_back(static_cast<char>((step_axis(s, 1) ? 1 : 0) | 2 | (step_axis(s, 2) ? 4 : 0)));
    std::mt19937 rng(8);
    std::string noise;
    for (std::size_t t = 0; t < job.size(); ++t) noise.push_back(static_cast<char>(rng() % 16));
    const std::string log = job + noise + job;
    CompressOptions opt;
    opt.format = InputFormat::timed;
    opt.block_steps = job.size();
    auto z = compress(log, opt);
    ASSERT_TRUE(z.ok()) << z.error().message;
    const auto blocks = test::block_records(*z);
    ASSERT_EQ(blocks.size(), 3u);
    ASSERT_FALSE(blocks[1].payload.empty());
    EXPECT_TRUE(blocks[1].type == stz::kRaw || static_cast<unsigned char>(blocks[1].payload[0]) == 3u);  // CM raw
    const int windowed = static_cast<int>(coding_byte(TickCoding::mixed_sure, stz::kTickFlags | stz::kTickWindow));
    EXPECT_EQ(tick_blocks(*z, -1, windowed), 1u);
    auto back = decompress(*z);
    ASSERT_TRUE(back.ok()) << back.error().message;
    EXPECT_EQ(*back, log);
}

TEST(TickBlock, UnknownCodingShortStreamAndTrailingBytesAreCorruptAtTheirByte) {
    std::mt19937 rng(3);
    Block b;
    b.axes = 3;
    b.chains.push_back(timed_chain(rng, 3, 4000, Point{}));
    const std::string payload = stz::write_tick_block(b);
    Block out;
    stz::BlockCounts counts;
    for (const bool irq : {false, true}) {  // the interrupt block's header reads the same
        // Coding 3, the plain coding with the guess, guided or match flag, a
        // mixed one with the refine flag, the window flag without the match
        // and refine flags.
        for (const unsigned byte : {3u, stz::kTickGuess, stz::kTickRestart | stz::kTickGuess, stz::kTickGuided,
                                    stz::kTickRestart | stz::kTickGuided, stz::kTickMatch,
                                    stz::kTickRestart | stz::kTickMatch, stz::kTickWindow | 2u,
                                    stz::kTickWindow | stz::kTickRestart | stz::kTickGuided | 1u,
                                    stz::kTickWindow | stz::kTickMatch | stz::kTickRestart, stz::kTickRefine | 2u,
                                    (stz::kTickFlags & 0xFFu) | 1u, stz::kTickWindow | stz::kTickRestart,
                                    stz::kTickRefine | stz::kTickMatch | stz::kTickRestart}) {
            std::string bad = irq ? stz::write_interrupt_block(b) : payload;
            bad[1] = static_cast<char>(byte);
            auto coding = stz::read_tick_block(bad, 3, true, out, counts, "P");
            ASSERT_FALSE(coding.ok()) << byte;
            EXPECT_EQ(coding.error().code, Errc::corrupt);
            EXPECT_EQ(coding.error().message,
                      irq ? "P byte 1: unknown coding of an interrupt block" : "P byte 1: unknown coding of a tick block");
        }
    }
    // Subtypes 5 and 6: the model byte of a block of each coding set to a
    // model that it does not take (2, slot lines, goes only with an
    // interrupt block of a mixed coding).
    for (const bool irq : {false, true})
        for (const TickCoding coding : {TickCoding::plain, TickCoding::mixed_sure}) {
            const std::string planned =
                irq ? stz::write_interrupt_block(b, coding) : stz::write_tick_block(b, coding);
            const bool slots = irq && coding != TickCoding::plain;
            ASSERT_EQ(static_cast<unsigned char>(planned[0]),
                      irq ? stz::kInterruptPlannerSubtype : stz::kTickPlannerSubtype);
            ASSERT_EQ(planned[2], slots ? 2 : 1);
            for (const int model : {0, slots ? 3 : 2, 255}) {
                std::string bad = planned;
                bad[2] = static_cast<char>(model);
                auto r = stz::read_tick_block(bad, 3, true, out, counts, "P");
                ASSERT_FALSE(r.ok()) << model;
                EXPECT_EQ(r.error().code, Errc::corrupt);
                EXPECT_EQ(r.error().message, irq ? "P byte 2: unknown model of an interrupt block"
                                                 : "P byte 2: unknown model of a tick block");
            }
        }
    auto longer = stz::read_tick_block(payload + std::string(3, '\0'), 3, true, out, counts, "P");
    ASSERT_FALSE(longer.ok());
    EXPECT_EQ(longer.error().code, Errc::corrupt);
    for (std::size_t cut : {std::size_t{1}, std::size_t{3}, payload.size() / 2, payload.size() - 1}) {
        auto r = stz::read_tick_block(std::string_view(payload).substr(0, cut), 3, true, out, counts, "P");
        ASSERT_FALSE(r.ok()) << "cut at " << cut;
        EXPECT_TRUE(r.error().code == Errc::corrupt) << r.error().message;
        EXPECT_NE(r.error().message.find("P byte "), std::string::npos) << r.error().message;
    }
}

TEST(TickBlock, EveryPayloadByteFlipDecodesToSomethingOrIsRejected) {
    std::mt19937 rng(5);
    Block b;
    b.axes = 3;
    b.chains.push_back(timed_chain(rng, 3, 1500, Point{}));
    int rejected = 0;
    for (const TickCoding coding : kCodings) {
        const std::string payload = stz::write_tick_block(b, coding);
        for (std::size_t k = 0; k < payload.size(); ++k)
            for (int bit = 0; bit < 8; bit += 3) {
                std::string bad = payload;
                bad[k] = static_cast<char>(static_cast<unsigned char>(bad[k]) ^ (1u << bit));
                Block out;
                stz::BlockCounts counts;
                auto r = stz::read_tick_block(bad, 3, true, out, counts, "P");
                if (!r.ok()) {
                    EXPECT_TRUE(r.error().code == Errc::corrupt || r.error().code == Errc::limit) << r.error().message;
                    ++rejected;
                } else {
                    for (const Chain& c : out.chains)
                        for (Step s : c.steps) EXPECT_EQ(step_axis(s, 0), 1);  // every decoded tick advances time
                }
            }
    }
    EXPECT_GT(rejected, 0);
}

// Random payloads behind a valid subtype and coding: every one is decoded or
// rejected as corrupt or over a limit, naming where.
TEST(TickBlock, RandomPayloadsAreDecodedOrRejectedWithTheirByte) {
    std::mt19937 rng(13);
    int rejected = 0;
    for (int trial = 0; trial < 800; ++trial) {
        std::string payload = {static_cast<char>(stz::kTickSubtype), static_cast<char>(trial % 2)};
        const std::size_t n = 1 + rng() % 120;
        for (std::size_t i = 0; i < n; ++i) payload.push_back(static_cast<char>(rng() % 256));
        if (trial % 3 == 0) payload[2] = 1;  // one chain: the stream is reached more often
        if (trial % 3 == 0 && payload.size() > 5) payload.replace(3, 3, std::string("\x40\x00\x00", 3));
        Block out;
        stz::BlockCounts counts;
        auto r = stz::read_tick_block(payload, 3 + trial % 3, true, out, counts, "P");
        if (!r.ok()) {
            EXPECT_TRUE(r.error().code == Errc::corrupt || r.error().code == Errc::limit) << r.error().message;
            // A payload byte, or the layout field (as every modeled block names it).
            EXPECT_TRUE(r.error().message.rfind("P byte ", 0) == 0 || r.error().message.rfind("P layout", 0) == 0)
                << r.error().message;
            ++rejected;
        }
    }
    EXPECT_GT(rejected, 500);
}

// A log of a stepper interrupt with step smoothing: the interrupt runs
// 2^level times per step of the leading axis at a period in CPU cycles (640
// to a tick) that ramps per segment; the other axes step by Bresenham on
// the interrupts, so between the leader's steps as often as on them. (`moves`
// moves; std::mt19937's sequence is the same on every platform.)
std::string interrupt_log(std::uint32_t seed, int level, int moves = 30) {
    std::mt19937 rng(seed);
    std::string log;
    std::int64_t cycle = 0;
    for (int move = 0; move < moves; ++move) {
        const std::int64_t major = 200 + static_cast<std::int64_t>(rng() % 600);
        const std::int64_t minor = static_cast<std::int64_t>(rng() % static_cast<std::uint32_t>(major / 2));
        const std::int64_t thr = major << 3, inc_major = major << (3 - level), inc_minor = minor << (3 - level);
        std::int64_t cm = thr / 2, cn = thr / 2, done = 0;
        std::int64_t period = 9000 >> level;  // cycles between interrupts
        while (done < major) {
            period = std::max<std::int64_t>(period - 40, 500);
            for (int i = 0; i < 40 << level && done < major; ++i) {  // one segment
                cycle += period;
                unsigned tick = 0;
                cm += inc_major;
                if (cm > thr) {
                    cm -= thr;
                    tick |= 1u;
                    ++done;
                }
                cn += inc_minor;
                if (cn > thr) {
                    cn -= thr;
                    tick |= 4u;
                }
                const auto t = static_cast<std::size_t>(cycle / 640);
                if (log.size() <= t) log.resize(t + 1, '\0');
                log[t] = static_cast<char>(static_cast<unsigned char>(log[t]) | tick);
            }
        }
    }
    return log.substr(log.find_first_not_of('\0'));
}

Block log_block(const std::string& log) {
    Block b;
    b.axes = 3;
    Chain c{3, Point{}, {}};
    for (const char ch : log) {
        const auto v = static_cast<unsigned char>(ch);
        int d[kMaxAxes] = {1, (v & 1u) ? 1 : 0, (v & 4u) ? 1 : 0};
        c.steps.push_back(make_step(d, 3));
    }
    b.chains.push_back(std::move(c));
    return b;
}

// The interrupt block (subtype 1) follows the other axis per leader step,
// where a smoothed interrupt places it between the leader's steps: smaller
// than the tick block, which follows it only on the leader's ticks (by 2-4 %
// here); at level 0 (no smoothing) the two stay close.
TEST(InterruptBlock, SmallerThanTheTickBlockUnderStepSmoothing) {
    for (int level : {1, 2, 3}) {
        const Block b = log_block(interrupt_log(21, level));
        for (const TickCoding coding : kCodings) {
            EXPECT_EQ(round_trip(b, coding, true).chains, b.chains) << "level " << level;
            const std::size_t irq = stz::write_interrupt_block(b, coding).size();
            const std::size_t tick = stz::write_tick_block(b, coding).size();
            EXPECT_LT(irq, tick) << "level " << level << " coding " << static_cast<unsigned>(coding) << ": " << irq
                                 << " vs " << tick;
        }
    }
    const Block b0 = log_block(interrupt_log(21, 0));
    const std::size_t irq = stz::write_interrupt_block(b0).size(), tick = stz::write_tick_block(b0).size();
    EXPECT_LT(irq * 100, tick * 110) << irq << " vs " << tick;
}

// Slot lines (kTickSlots, docs/FORMAT.md 1.17): on a log whose other axis
// steps by Bresenham on the interrupts, each level's grid of 2^L slots per
// leader interval places its steps where its line is exact. The interrupt
// block decodes and, under both mixed codings, codes the log of every
// smoothing level at least 6 % smaller with them (10-31 % here); a tick
// block and the plain coding do not take them (the same bytes).
TEST(InterruptBlock, SlotLinesCodeASmoothedLogSmaller) {
    for (int level : {1, 2, 3}) {
        const Block b = log_block(interrupt_log(23, level));
        for (const TickCoding coding : {TickCoding::mixed, TickCoding::mixed_sure}) {
            EXPECT_EQ(round_trip(b, coding, true).chains, b.chains) << "level " << level;
            const std::size_t with = coded_size(b, coding, true, stz::kTickFlags),
                              without = coded_size(b, coding, true, stz::kTickFlags & ~stz::kTickSlots);
            EXPECT_LT(with * 100, without * 94) << "level " << level << " coding " << static_cast<unsigned>(coding)
                                                << ": " << with << " against " << without;
            EXPECT_EQ(stz::write_tick_block(b, coding, stz::kTickFlags),
                      stz::write_tick_block(b, coding, stz::kTickFlags & ~stz::kTickSlots));
        }
        EXPECT_EQ(stz::write_interrupt_block(b, TickCoding::plain, stz::kTickFlags),
                  stz::write_interrupt_block(b, TickCoding::plain, stz::kTickFlags & ~stz::kTickSlots));
    }
}

// Slot lines where the axes do not step on a common interrupt (the ramp:
// each axis at its own times): the slot lines' probability goes to the
// mixers beside the axis's own, so the interrupt block stays within 1 % of
// its size without them (0.2 % larger here; 7-8 % when the slot
// probability replaced the own one as the direct input).
TEST(InterruptBlock, SlotLinesCostLittleWhereAxesStepApart) {
    const Block b = ramp_block();
    for (const TickCoding coding : {TickCoding::mixed, TickCoding::mixed_sure}) {
        const std::size_t with = coded_size(b, coding, true, stz::kTickFlags),
                          without = coded_size(b, coding, true, stz::kTickFlags & ~stz::kTickSlots);
        EXPECT_LT(with * 100, without * 101) << "coding " << static_cast<unsigned>(coding) << ": " << with
                                             << " against " << without;
    }
}

// The encoder keeps the interrupt block where it is the smallest, and the
// frame decodes to the log.
TEST(InterruptBlock, EncoderPicksItOnASmoothedLogAndTheFrameRoundTrips) {
    const std::string log = interrupt_log(22, 2);
    for (int level : {3, 19}) {
        CompressOptions opt;
        opt.format = InputFormat::timed;
        opt.level = level;
        auto z = compress(log, opt);
        ASSERT_TRUE(z.ok()) << z.error().message;
        EXPECT_GE(tick_blocks(*z, stz::kInterruptSubtype), 1u) << "level " << level;
        auto back = decompress(*z);
        ASSERT_TRUE(back.ok()) << back.error().message;
        EXPECT_EQ(*back, log) << "level " << level;
    }
}

// tests/golden-generated/interrupt_large.steps.stz decodes to the log it
// was made from, interrupt_log(31, 2, 360) (2 126 682 ticks, kept out of
// the repository): one interrupt block with the planner model of at least
// 2^21 ticks, whose hashed tables hold 2^21 entries (docs/FORMAT.md 1.16).
// It pins the decoder of such blocks, as tests/golden/ does for smaller ones.
TEST(InterruptBlock, LargeBlockGoldenFileDecodesToItsGeneratedLog) {
    const std::string log = interrupt_log(31, 2, 360);
    ASSERT_GE(log.size(), std::size_t{1} << 21);
    const std::string frame = test::slurp(std::filesystem::path(STEPZIP_SOURCE_DIR) / "tests" / "golden-generated" /
                                          "interrupt_large.steps.stz");
    const auto records = test::block_records(frame);
    ASSERT_EQ(records.size(), 1u);
    ASSERT_EQ(records[0].type, stz::kExtended);
    EXPECT_EQ(static_cast<unsigned char>(records[0].payload[0]), stz::kInterruptPlannerSubtype);
    auto back = decompress(frame);
    ASSERT_TRUE(back.ok()) << back.error().message;
    EXPECT_TRUE(*back == log);
}

// The mixed codings take the interrupt block unless its plain prefix is
// over 1/32 larger than the tick block's (the guided mixing's crossing
// contexts favour it). On the no-AMASS log of corpora/timed the plain
// interrupt block is larger (2.7 %), the mixed one smaller (2.4 %): -L 3
// writes it, the bytes -L 19 keeps after coding both whole. (Where the
// default's choice loses, -L 19 keeps the other: tests/cli/timed.sh.)
TEST(InterruptBlock, MixedCodingsTakeTheInterruptBlockWithinAMargin) {
    const std::string log = test::corpus("timed/heldout-noamass.steps");
    std::string payload[2];
    for (int i = 0; i < 2; ++i) {
        CompressOptions opt;
        opt.format = InputFormat::timed;
        opt.level = i == 0 ? 3 : 19;
        const std::string z = test::compress_proved(log, opt);
        ASSERT_FALSE(z.empty()) << opt.level;
        const auto records = test::block_records(z);
        ASSERT_EQ(records.size(), 1u);
        ASSERT_EQ(records[0].type, stz::kExtended);
        payload[i] = std::string(records[0].payload);
        EXPECT_EQ(static_cast<unsigned char>(payload[i][0]), stz::kInterruptPlannerSubtype) << opt.level;
    }
    EXPECT_EQ(payload[0], payload[1]);
    // The plain codings (the check's) have the tick block smaller.
    auto chains = read_chains(InputFormat::timed, log);
    ASSERT_TRUE(chains.ok()) << chains.error().message;
    ASSERT_FALSE(chains->empty());
    Block b;
    b.axes = chains->front().axes;
    b.chains = std::move(*chains);
    const std::size_t tick = stz::write_tick_block(b).size(), irq = stz::write_interrupt_block(b).size();
    EXPECT_LT(tick, irq);
    EXPECT_LE(irq * 32, tick * 33);
}

}  // namespace
}  // namespace stepzip

