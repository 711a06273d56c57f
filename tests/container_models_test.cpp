// The context models of the modeled blocks (docs/FORMAT.md "Segment model",
// "Step model"): each decodes back to exactly the chains it coded — random
// chains under every profile, corpus data, empty chains — and a damaged
// payload is rejected without reading past it; the default-phase cut is
// exact; on deterministic data the segment model beats the record layout on
// controller lines and the step model beats the segment model on a random walk.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "../src/segment/default_phase_cut.hpp"
#include "../src/container/block_codec.hpp"
#include "../src/container/modeled_block.hpp"
#include "stepzip/container.hpp"
#include "stepzip/segmenter.hpp"
#include "support/files.hpp"

namespace stepzip::stz {
namespace {

Block random_block(std::uint64_t seed, int count, bool four, int axes = 2) {
    std::mt19937_64 rng(seed);
    Block b;
    b.axes = axes;
    for (int i = 0; i < count; ++i) {
        Chain c;
        c.axes = axes;
        for (int a = 0; a < axes; ++a) c.start[a] = static_cast<std::int64_t>(rng() % 2000) - 1000;
        const int n = static_cast<int>(rng() % 150);
        Step cur = 0;
        for (int k = 0; k < n; ++k) {
            if (cur == 0 || rng() % 5 == 0) {
                do {
                    int d[kMaxAxes] = {};
                    if (four) d[rng() % axes] = rng() % 2 ? 1 : -1;
                    else
                        for (int a = 0; a < axes; ++a) d[a] = static_cast<int>(rng() % 3) - 1;
                    cur = make_step(d, axes);
                } while (cur == 0);
            }
            c.steps.push_back(cur);
        }
        b.chains.push_back(std::move(c));
        if (i % 3 == 0) b.chains.push_back(b.chains.back());  // repeated chains feed the match model
    }
    b.layout = "layout bytes: opaque to the container";
    return b;
}

std::vector<std::vector<Segment>> cut(const Block& b, Profile p, SegmenterKind k) {
    std::vector<std::vector<Segment>> segs(b.chains.size());
    for (std::size_t i = 0; i < b.chains.size(); ++i) {
        auto r = segment_steps(b.chains[i].steps, b.axes, p, k, segs[i]);
        EXPECT_TRUE(r.ok());
    }
    return segs;
}

void expect_segment_model_round_trip(const Block& b, Profile p,
                                     const std::vector<std::vector<Segment>>& segs, const char* what) {
    const std::string payload = write_segment_model(b, p, segs);
    Block back;
    BlockCounts counts;
    auto r = read_segment_model(payload, p, b.axes, true, back, counts, "test");
    ASSERT_TRUE(r.ok()) << what << ": " << r.error().message;
    EXPECT_EQ(back.chains, b.chains) << what;
    EXPECT_EQ(back.layout, b.layout) << what;
    EXPECT_EQ(counts.chains, b.chains.size()) << what;
    std::uint64_t nseg = 0;
    for (const auto& s : segs) nseg += s.size();
    EXPECT_EQ(counts.segments, nseg) << what;
}

void expect_step_model_round_trip(const Block& b, const char* what) {
    const std::string payload = write_step_model(b);
    ASSERT_FALSE(payload.empty()) << what;
    Block back;
    BlockCounts counts;
    auto r = read_step_model(payload, b.axes, true, back, counts, "test");
    ASSERT_TRUE(r.ok()) << what << ": " << r.error().message;
    EXPECT_EQ(back.chains, b.chains) << what;
    EXPECT_EQ(back.layout, b.layout) << what;
    EXPECT_EQ(counts.segments, 0u) << what;
}

TEST(SegmentModel, RoundTripsEveryProfileAndSegmenter) {
    for (Profile p : kAllProfiles)
        for (SegmenterKind k : {SegmenterKind::greedy, SegmenterKind::optimal, SegmenterKind::patent}) {
            const bool eight = profile_eight_connected(p);
            if (k == SegmenterKind::patent && eight) continue;  // patent reads 4-connected only
            const Block b = random_block(static_cast<std::uint64_t>(p) * 7 + static_cast<std::uint64_t>(k), 30, !eight);
            expect_segment_model_round_trip(b, p, cut(b, p, k), std::string(profile_name(p)).c_str());
        }
}

TEST(SegmentModel, RoundTripsSeveralAxes) {
    for (int axes : {3, 4, 6})
        for (Profile p : {Profile::eval8, Profile::grbl, Profile::marlin}) {
            const Block b = random_block(100 + static_cast<std::uint64_t>(axes), 20, false, axes);
            expect_segment_model_round_trip(b, p, cut(b, p, SegmenterKind::greedy), "n-d");
        }
}

TEST(SegmentModel, EmptyBlocksAndEmptyChains) {
    Block empty;
    expect_segment_model_round_trip(empty, Profile::eval8, {}, "empty");
    Block b;
    b.chains.resize(3);
    b.chains[1].start = {5, -7};
    expect_segment_model_round_trip(b, Profile::eval8, cut(b, Profile::eval8, SegmenterKind::greedy), "no steps");
}

TEST(AlignedCut, IsExactAndFindsControllerVectors) {
    std::mt19937_64 rng(3);
    for (Profile p : {Profile::eval4, Profile::eval8, Profile::grbl, Profile::marlin}) {
        Chain c;
        int vectors = 0;
        for (int i = 0; i < 60; ++i) {
            Point d{};
            d[0] = static_cast<std::int64_t>(rng() % 90) - 45;
            d[1] = static_cast<std::int64_t>(rng() % 90) - 45;
            if (d[0] == 0 && d[1] == 0) continue;
            expand_segment(p, default_segment(p, d, 2), 2, c.steps);
            ++vectors;
        }
        std::vector<Segment> segs;
        ASSERT_TRUE(cut_preferring_default(c.steps, 2, p, segs));
        std::vector<Step> again;
        std::size_t at_default = 0;
        for (const Segment& s : segs) {
            ASSERT_TRUE(check_segment(p, s, 2).ok());
            expand_segment(p, s, 2, again);
            at_default += s == default_segment(p, s.delta, 2);
        }
        EXPECT_EQ(again, c.steps) << profile_name(p);
        // Nearly every cut is a vector drawn at the default phase (a vector
        // that continues the previous one's line may merge with it).
        EXPECT_LE(segs.size(), static_cast<std::size_t>(vectors) * 12 / 10) << profile_name(p);
        EXPECT_GE(at_default * 10, segs.size() * 8) << profile_name(p);
    }
    std::vector<Segment> segs;
    EXPECT_FALSE(cut_preferring_default(std::vector<Step>{freeman_to_step(0)}, 2, Profile::patent, segs));
}

TEST(StepModel, RoundTripsFourAndEightConnectedChains) {
    expect_step_model_round_trip(random_block(1, 40, false), "8-connected");
    expect_step_model_round_trip(random_block(2, 40, true), "4-connected");
    Block b;
    b.chains.resize(2);
    expect_step_model_round_trip(b, "no steps");
    EXPECT_TRUE(write_step_model(random_block(3, 5, false, 3)).empty());
}

using test::slurp;

// The first block of a corpus file (at most `steps` steps).
Block corpus_block(const char* rel, std::size_t steps) {
    const auto path = std::filesystem::path(STEPZIP_SOURCE_DIR) / "corpora" / rel;
    BlockReader reader(InputFormat::freeman, rel, steps);
    EXPECT_TRUE(reader.feed(slurp(path), true).ok());
    Block b;
    EXPECT_TRUE(reader.next(b));
    return b;
}

TEST(Models, RoundTripOnCorpusData) {
    for (const char* f : {"glyphs/dejavu-8.fc", "glyphs/dejavu-4.fc", "plotter/hershey-grbl.fc",
                          "plotter/gnuplot-eval4.fc", "random/walk-8.fc"}) {
        const Block b = corpus_block(f, 60000);
        expect_step_model_round_trip(b, f);
        const Profile p = b.chains.empty() || std::all_of(b.chains.begin(), b.chains.end(), [](const Chain& c) {
                              return c.four_connected();
                          })
                              ? Profile::eval4
                              : Profile::grbl;
        expect_segment_model_round_trip(b, p, cut(b, p, SegmenterKind::greedy), f);
        std::vector<std::vector<Segment>> aligned(b.chains.size());
        bool ok = true;
        for (std::size_t i = 0; i < b.chains.size(); ++i)
            ok = ok && cut_preferring_default(b.chains[i].steps, 2, p, aligned[i]);
        ASSERT_TRUE(ok) << f;
        expect_segment_model_round_trip(b, p, aligned, f);
    }
}

TEST(Models, DamagedPayloadsAreRejectedOrDecodeWithinBounds) {
    const Block b = random_block(21, 8, false);
    const auto segs = cut(b, Profile::eval8, SegmenterKind::greedy);
    const std::string seg_payload = write_segment_model(b, Profile::eval8, segs);
    const std::string step_payload = write_step_model(b);
    for (int which = 0; which < 2; ++which) {
        const std::string& good = which == 0 ? seg_payload : step_payload;
        auto decode = [&](std::string_view bytes) {
            Block out;
            BlockCounts counts;
            return which == 0 ? read_segment_model(bytes, Profile::eval8, 2, true, out, counts, "t")
                              : read_step_model(bytes, 2, true, out, counts, "t");
        };
        for (std::size_t n = 0; n < good.size(); ++n) {
            auto r = decode(std::string_view(good).substr(0, n));
            EXPECT_FALSE(r.ok()) << which << " length " << n;
            if (!r.ok())
                EXPECT_TRUE(r.error().code == Errc::corrupt || r.error().code == Errc::limit)
                    << r.error().message;
        }
        // Single-byte damage. The payload has no checksum of its own (the
        // block checksum guards it), so damage may decode; what it decodes
        // to is compared with the original: damage inside the verbatim
        // layout changes exactly the layout, damage elsewhere never changes
        // the layout, and chains that differ from the original must still be
        // a consistent block (counts as declared, re-encoding decodes to
        // the same chains), never garbage.
        const std::size_t layout_at = good.find(b.layout);
        ASSERT_NE(layout_at, std::string::npos) << "the short layout is stored verbatim";
        std::mt19937_64 rng(which + 1);
        int decoded = 0, changed = 0;
        for (int t = 0; t < 2000; ++t) {
            std::string bad = good;
            const std::size_t at = rng() % bad.size();
            bad[at] ^= static_cast<char>(1 + rng() % 255);
            Block out;
            BlockCounts counts;
            auto r = which == 0 ? read_segment_model(bad, Profile::eval8, 2, true, out, counts, "t")
                                : read_step_model(bad, 2, true, out, counts, "t");
            if (!r.ok()) {
                EXPECT_TRUE(r.error().code == Errc::corrupt || r.error().code == Errc::limit)
                    << r.error().message;
                continue;
            }
            ++decoded;
            const bool in_layout = at >= layout_at && at < layout_at + b.layout.size();
            if (in_layout) {
                EXPECT_EQ(out.chains, b.chains) << which << " byte " << at;
                EXPECT_EQ(out.layout, bad.substr(layout_at, b.layout.size())) << which << " byte " << at;
                continue;
            }
            EXPECT_EQ(out.layout, b.layout) << which << " byte " << at;
            if (out.chains == b.chains) continue;
            ++changed;
            std::uint64_t steps = 0;
            for (const Chain& c : out.chains) steps += c.steps.size();
            EXPECT_EQ(counts.chains, out.chains.size()) << which << " byte " << at;
            EXPECT_EQ(counts.steps, steps) << which << " byte " << at;
            Block again;
            BlockCounts again_counts;
            if (which == 0) {
                const std::string re = write_segment_model(out, Profile::eval8, cut(out, Profile::eval8, SegmenterKind::greedy));
                ASSERT_TRUE(read_segment_model(re, Profile::eval8, 2, true, again, again_counts, "t").ok());
            } else {
                const std::string re = write_step_model(out);
                ASSERT_TRUE(read_step_model(re, 2, true, again, again_counts, "t").ok());
            }
            EXPECT_EQ(again.chains, out.chains) << which << " byte " << at;
        }
        // Both outcomes are exercised: some damage decodes (in the layout at
        // least), and stream damage is mostly rejected.
        EXPECT_GT(decoded, 0) << which;
        EXPECT_LT(changed, 2000 / 10) << which;
    }
}

TEST(Models, SizeOrderingOnDeterministicData) {
    // Controller lines: the segment model beats segment records + zstd.
    std::mt19937_64 rng(8);
    Block lines;
    lines.chains.resize(1);
    for (int i = 0; i < 300; ++i) {
        Point d{};
        d[0] = static_cast<std::int64_t>(rng() % 60) - 30;
        d[1] = static_cast<std::int64_t>(rng() % 60) - 30;
        if (d[0] == 0 && d[1] == 0) continue;
        expand_segment(Profile::grbl, default_segment(Profile::grbl, d, 2), 2, lines.chains[0].steps);
    }
    const auto segs = cut(lines, Profile::grbl, SegmenterKind::greedy);
    const std::string records = make_block_record(kChains, 0, write_chain_payload(lines, Profile::grbl, segs), 19);
    EXPECT_LT(write_segment_model(lines, Profile::grbl, segs).size(), records.size());

    // A uniform random walk: the step model beats the segment model.
    Block walk;
    walk.chains.resize(1);
    for (int i = 0; i < 20000; ++i) walk.chains[0].steps.push_back(freeman_to_step(static_cast<int>(rng() % 8)));
    const auto wsegs = cut(walk, Profile::eval8, SegmenterKind::greedy);
    const std::size_t step_size = write_step_model(walk).size();
    EXPECT_LT(step_size, write_segment_model(walk, Profile::eval8, wsegs).size());
    EXPECT_LT(step_size * 8, 20000u * 31 / 10);  // near the 3 bits/step floor
}

}  // namespace
}  // namespace stepzip::stz
