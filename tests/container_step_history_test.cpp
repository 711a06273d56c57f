// The step models' history (src/container/step_history.hpp): a history
// stacked on the frame's (the encoder's second pass and proof) answers every
// match look-up and chain-start query as the history rebuilt from the
// window alone does (docs/FORMAT.md 1.8), also after the frame's history
// dropped a dead prefix, and with window blocks that are not in the frame's
// history yet (the blocks of the same batch).
#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <vector>

#include "../src/container/step_history.hpp"

namespace stepzip::stz {
namespace {

// Chains of Freeman codes with motifs that recur (so that matches are
// found), each ended by kEndSymbol, and a start delta per chain.
std::shared_ptr<WindowBlock> random_block(std::mt19937_64& rng, int chains) {
    static const std::vector<std::vector<std::uint8_t>> motifs = {
        {0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 1, 2, 2, 3}, {6, 6, 5, 6, 6, 5, 4, 4, 4, 3}, {2, 2, 2, 2, 1, 0, 7, 6, 6, 6}};
    auto out = std::make_shared<WindowBlock>();
    WindowBlock& b = *out;
    for (int c = 0; c < chains; ++c) {
        const int parts = 1 + static_cast<int>(rng() % 6);
        for (int p = 0; p < parts; ++p) {
            if (rng() % 3 == 0) {
                const int n = 1 + static_cast<int>(rng() % 20);
                for (int k = 0; k < n; ++k) b.symbols.push_back(static_cast<std::uint8_t>(rng() % 8));
            } else {
                const auto& m = motifs[rng() % motifs.size()];
                b.symbols.insert(b.symbols.end(), m.begin(), m.end());
            }
        }
        b.symbols.push_back(kEndSymbol);
        b.starts.push_back(Point{static_cast<std::int64_t>(rng() % 64) - 32, static_cast<std::int64_t>(rng() % 64) - 32});
    }
    b.weight = b.symbols.size();
    return out;
}

// Appends `syms` to both histories through a StepMatch each, comparing at
// every symbol the match's prediction and length and the chain start it
// points at.
void expect_same_answers(StepHistory& rebuilt, StepHistory& stacked, const std::vector<std::uint8_t>& syms) {
    StepMatch a, b;
    std::size_t predicted = 0;
    for (std::size_t i = 0; i < syms.size(); ++i) {
        ASSERT_EQ(a.predicted(rebuilt), b.predicted(stacked)) << "symbol " << i;
        ASSERT_EQ(a.len, b.len) << "symbol " << i;
        if (a.ptr >= 0) {
            ++predicted;
            const Point* pa = rebuilt.start_at(static_cast<std::uint32_t>(a.ptr));
            const Point* pb = stacked.start_at(static_cast<std::uint32_t>(b.ptr));
            ASSERT_EQ(pa != nullptr, pb != nullptr) << "symbol " << i;
            if (pa) {
                EXPECT_EQ(*pa, *pb) << "symbol " << i;
            }
        }
        if (i > 0 && syms[i - 1] == kEndSymbol) {
            const Point d{static_cast<std::int64_t>(i), -static_cast<std::int64_t>(i)};
            rebuilt.note_start(d);
            stacked.note_start(d);
        }
        a.push(rebuilt, syms[i]);
        b.push(stacked, syms[i]);
    }
    EXPECT_GT(predicted, syms.size() / 4);  // the check saw matches
}

TEST(StepHistory, StackedOnTheFrameAnswersAsTheRebuiltWindow) {
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
        std::mt19937_64 rng(seed);
        std::vector<std::shared_ptr<WindowBlock>> blocks;
        for (int i = 0; i < 6; ++i) blocks.push_back(random_block(rng, 20 + static_cast<int>(rng() % 40)));
        // The frame holds blocks 0-4; the window is blocks `first`-5 (block 5
        // is of the same batch: not in the frame's history).
        StepHistory frame;
        for (int i = 0; i < 5; ++i) {
            blocks[static_cast<std::size_t>(i)]->first_symbol = frame.base + frame.size();
            frame.add(*blocks[static_cast<std::size_t>(i)]);
        }
        const std::size_t first = 1 + seed % 3;
        // A frame history that dropped its dead prefix (seeds 4-6).
        if (seed > 3) frame.begin_block(blocks[first]->first_symbol, 16);
        StepHistory rebuilt, stacked;
        for (std::size_t i = first; i < 6; ++i) rebuilt.add(*blocks[i]);
        stacked.stack_on(frame, blocks[first]->first_symbol);
        stacked.add(*blocks[5]);
        // New chains, then the symbols around the window's start again
        // (contexts that reach back past it must not be found).
        std::vector<std::uint8_t> next = random_block(rng, 60)->symbols, all;
        for (std::size_t i = 0; i < 5; ++i) all.insert(all.end(), blocks[i]->symbols.begin(), blocks[i]->symbols.end());
        const std::size_t w = static_cast<std::size_t>(blocks[first]->first_symbol);  // (the frame starts at 0)
        ASSERT_TRUE(w >= 11 && w + 30 <= all.size());
        next.insert(next.end(), all.begin() + static_cast<std::ptrdiff_t>(w - 11),
                    all.begin() + static_cast<std::ptrdiff_t>(w + 30));
        expect_same_answers(rebuilt, stacked, next);
    }
}

TEST(StepHistory, AStackedCoderStartsWhereTheFrameHistoryEnds) {
    std::mt19937_64 rng(11);
    StepHistory frame;
    WindowView window;
    for (int i = 0; i < 3; ++i) {
        auto b = random_block(rng, 30);
        b->first_symbol = frame.base + frame.size();
        frame.add(*b);
        b->history = &frame;
        window.push_back(b);
    }
    StepHistory fresh;
    EXPECT_EQ(stack_base(window, fresh), &frame);
    // Not the frame history's tail (a block after the window in it): rebuilt.
    const WindowView head(window.begin(), window.begin() + 2);
    EXPECT_EQ(stack_base(head, fresh), nullptr);
    // The window's later blocks need not be in it.
    WindowView more = window;
    more.push_back(random_block(rng, 5));
    EXPECT_EQ(stack_base(more, fresh), &frame);
    // Nothing of the frame in the window: rebuilt.
    EXPECT_EQ(stack_base(WindowView(more.end() - 1, more.end()), fresh), nullptr);
}

}  // namespace
}  // namespace stepzip::stz
