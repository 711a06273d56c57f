#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../src/container/cut_cache.hpp"
#include "../src/segment/accepted_cut.hpp"
#include "stepzip/document.hpp"
#include "stepzip/segment/block_cut.hpp"

using namespace stepzip;
using stz::CutCache;

namespace {

std::vector<Chain> corpus_chains(const char* name) {
    std::ifstream f(std::filesystem::path(STEPZIP_SOURCE_DIR) / "corpora" / name, std::ios::binary);
    std::stringstream ss;
    ss << f.rdbuf();
    auto r = read_chains(InputFormat::freeman, ss.str());
    EXPECT_TRUE(r.ok());
    return r ? std::move(*r) : std::vector<Chain>{};
}

// The chains twice over, the second copies moved elsewhere: every chain of
// the second half repeats one of the first.
std::vector<Chain> twice(std::vector<Chain> chains) {
    const std::size_t n = chains.size();
    for (std::size_t i = 0; i < n; ++i) {
        Chain c = chains[i];
        c.start[0] += 1000;
        chains.push_back(std::move(c));
    }
    return chains;
}

}  // namespace

TEST(CutCache, CachedCutsEqualTheCutsMade) {
    for (const char* name : {"glyphs/dejavu-8.fc", "plotter/hershey-grbl.fc"}) {
        const std::vector<Chain> chains = twice(corpus_chains(name));
        ASSERT_FALSE(chains.empty());
        for (const Profile p : {Profile::eval8, Profile::grbl})
            for (const BlockCut kind : {BlockCut::greedy, BlockCut::default_phase}) {
                SCOPED_TRACE(std::string(name) + " " + std::string(profile_name(p)));
                std::vector<std::vector<Segment>> made, cached;
                ASSERT_TRUE(cut_block(chains, 2, p, kind, made).ok());
                CutCache cache(std::size_t{64} << 20);
                ASSERT_TRUE(stz::cut_block_cached(chains, 2, p, kind, cached, &cache).ok());
                EXPECT_EQ(cached, made);
                EXPECT_GT(cache.size(), 0u);
                // A second block of the same chains takes every cut long
                // enough from the cache: the same again.
                std::vector<std::vector<Segment>> again;
                ASSERT_TRUE(stz::cut_block_cached(chains, 2, p, kind, again, &cache).ok());
                EXPECT_EQ(again, made);
            }
    }
}

TEST(CutCache, FindsOnlyTheSameStepsUnderTheSameKey) {
    CutCache cache(1u << 20);
    const std::vector<Step> a(40, Step{1}), b(40, Step{4});
    const std::vector<Segment> cut{Segment{{40, 0}, {}}};
    const std::uint64_t h = CutCache::hash(a, BlockCut::greedy, Profile::eval8, 2);
    cache.insert(h, a, BlockCut::greedy, Profile::eval8, 2, cut);
    std::vector<Segment> out;
    EXPECT_TRUE(cache.find(h, a, BlockCut::greedy, Profile::eval8, 2, out));
    EXPECT_EQ(out, cut);
    // A hash that collides with other steps, another kind, profile or axes: not found.
    EXPECT_FALSE(cache.find(h, b, BlockCut::greedy, Profile::eval8, 2, out));
    EXPECT_FALSE(cache.find(h, a, BlockCut::default_phase, Profile::eval8, 2, out));
    EXPECT_FALSE(cache.find(h, a, BlockCut::greedy, Profile::grbl, 2, out));
    EXPECT_FALSE(cache.find(h, a, BlockCut::greedy, Profile::eval8, 3, out));
    EXPECT_NE(h, CutCache::hash(a, BlockCut::default_phase, Profile::eval8, 2));
}

TEST(CutCache, KeepsWithinItsBudgetOldestOut) {
    const std::size_t budget = 4096;
    CutCache cache(budget);
    const std::vector<Segment> cut{Segment{{64, 0}, {}}};
    std::vector<std::vector<Step>> chains;
    for (unsigned i = 0; i < 64; ++i) {
        std::vector<Step> s(64, Step{1});
        s[i] = 5;  // a diagonal somewhere: 64 different chains
        chains.push_back(s);
        cache.insert(CutCache::hash(s, BlockCut::greedy, Profile::eval8, 2), s, BlockCut::greedy, Profile::eval8,
                     2, cut);
        EXPECT_LE(cache.size(), budget);
    }
    std::vector<Segment> out;
    const auto& first = chains.front();
    const auto& last = chains.back();
    EXPECT_FALSE(cache.find(CutCache::hash(first, BlockCut::greedy, Profile::eval8, 2), first, BlockCut::greedy,
                            Profile::eval8, 2, out));
    EXPECT_TRUE(cache.find(CutCache::hash(last, BlockCut::greedy, Profile::eval8, 2), last, BlockCut::greedy,
                           Profile::eval8, 2, out));
    // A chain larger than a quarter of the budget is not kept.
    const std::vector<Step> big(budget, Step{1});
    const std::uint64_t h = CutCache::hash(big, BlockCut::greedy, Profile::eval8, 2);
    cache.insert(h, big, BlockCut::greedy, Profile::eval8, 2, cut);
    EXPECT_FALSE(cache.find(h, big, BlockCut::greedy, Profile::eval8, 2, out));
}

TEST(CutCache, ErrorsAsCutBlock) {
    // Under eval4 a diagonal step cannot be drawn: the same error, naming the same chain.
    std::vector<Chain> chains(3);
    for (Chain& c : chains) c.steps.assign(40, Step{1});
    chains[2].steps[7] = 5;
    std::vector<std::vector<Segment>> a, b;
    const auto ra = cut_block(chains, 2, Profile::eval4, BlockCut::greedy, a, nullptr, 10);
    CutCache cache(1u << 20);
    const auto rb = stz::cut_block_cached(chains, 2, Profile::eval4, BlockCut::greedy, b, &cache, nullptr, 10);
    ASSERT_FALSE(ra.ok());
    ASSERT_FALSE(rb.ok());
    EXPECT_EQ(ra.error().code, rb.error().code);
    EXPECT_EQ(ra.error().message, rb.error().message);
}

// The frame's block strategy checks a block's steps once (representable())
// and then cuts it without checking again: the cuts of checked chains, by
// every kind, are those of cut_block(), through the cache too.
TEST(CutCache, CutsOfCheckedChainsEqualCutBlock) {
    struct Case {
        const char* name;
        Profile p;
    };
    for (const Case& t : {Case{"glyphs/dejavu-8.fc", Profile::eval8}, Case{"plotter/hershey-grbl.fc", Profile::grbl},
                          Case{"glyphs/dejavu-4.fc", Profile::eval4}, Case{"glyphs/dejavu-4.fc", Profile::patent}}) {
        std::vector<Chain> chains = corpus_chains(t.name);
        if (chains.size() > 200) chains.resize(200);
        ASSERT_FALSE(chains.empty());
        for (const Chain& c : chains) ASSERT_TRUE(profile_accepts(t.p, c.steps, 2).ok());
        for (const BlockCut kind : {BlockCut::greedy, BlockCut::optimal, BlockCut::patent, BlockCut::default_phase}) {
            if ((kind == BlockCut::patent) != (t.p == Profile::patent)) continue;
            SCOPED_TRACE(std::string(t.name) + " " + std::string(profile_name(t.p)) + " kind " +
                         std::to_string(static_cast<int>(kind)));
            std::vector<std::vector<Segment>> checked, accepted, cached;
            SegmentStats s1, s2;
            ASSERT_TRUE(cut_block(chains, 2, t.p, kind, checked, &s1).ok());
            ASSERT_TRUE(cut_accepted_block(chains, 2, t.p, kind, accepted, &s2).ok());
            EXPECT_EQ(accepted, checked);
            EXPECT_EQ(s2.patent_segments, s1.patent_segments);
            CutCache cache(std::size_t{64} << 20);
            ASSERT_TRUE(stz::cut_block_cached(chains, 2, t.p, kind, cached, &cache, nullptr, 0, true).ok());
            EXPECT_EQ(cached, checked);
        }
    }
}
