// The encoder's block strategy (docs/FORMAT.md section 4): which encodings a
// level tries for a block, with which cuts and thresholds, the profile and
// cut chosen on a sample of the first block, and the second pass that codes
// a modeled block again from the window.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "../segment/accepted_cut.hpp"
#include "arc_items.hpp"
#include "cut_cache.hpp"
#include "encoder.hpp"
#include "modeled_block.hpp"
#include "raw_cm.hpp"
#include "stepzip/segment/block_cut.hpp"
#include "table_block.hpp"
#include "timed_block.hpp"
#include "timed_phase.hpp"
#include "timed_tick.hpp"

namespace stepzip::stz {

namespace {

// Below kThoroughLevel: steps of the first block's sample that picks the
// profile and the cut under --profile auto.
constexpr std::uint64_t kSampleSteps = 1u << 15;
// From kThoroughLevel: steps of the first block's sample that ranks the profiles.
constexpr std::uint64_t kThoroughSampleSteps = 1u << 17;
// The thorough levels rank the profiles on kSampleSteps first and try on
// kThoroughSampleSteps those within 1/kRankMargin of the best there (on
// corpora/ the winner was always within 1/400 of the best on the small
// sample; the losers 2-40 % behind, but on 8-connected glyph contours where
// grbl, marlin and eval8 come within 1 %).
constexpr std::size_t kRankMargin = 50;
// Bytes added to that margin (a sample of a few hundred bytes tells little).
constexpr std::size_t kRankSlack = 32;
// Segments per 1000 steps below which the segment model always wins and
// above which the step model always wins (measured on corpora/: 8.6..52
// against 383..663); in between both are encoded.
constexpr std::uint64_t kSegmentModelOnly = 60, kStepModelOnly = 250;
// Step-model context order used below the thorough levels (within 1% of the
// best order on every corpus file).
constexpr int kFastStepOrder = 2;
// Below the thorough levels, blocks of fewer steps are also coded by the
// segment model (block_strategy: choose_block).
constexpr std::uint64_t kSmallBlockSteps = 1u << 16;
// From this level on, every block dense in segments (contours, random
// walks: more than kSegmentModelOnly per 1000 steps) also tries the step
// model, which is 15-30 % smaller there than a table block.
constexpr int kFastStepLevel = 3;
// From this level on, a timed frame's tick and interrupt blocks are coded
// with mixed predictions but for the sure decisions (tick coding 2).
constexpr int kMixedTickLevel = 3;

using Cut = std::vector<std::vector<Segment>>;

std::uint64_t segment_count(const Cut& cut) {
    std::uint64_t n = 0;
    for (const auto& v : cut) n += v.size();
    return n;
}
// Whether `segments` over `steps` are too dense for the segment model: the
// step model's ground (random walks).
bool too_dense(std::uint64_t segments, std::uint64_t steps) { return segments * 1000 > kStepModelOnly * steps; }

// A block of more than two axes reads as text, not as a machine's steps,
// when its axes reverse their direction more than once in kTextReversals
// moves (of at least kTextMinMoves): bytes of HP-GL, G-code or source text
// read as a STEP/DIR log reverse 0.25-0.36 times a move (corpora/plotter/
// gnuplot.hpgl, samples/plot.gcode, bench/hpgl_inputs.sh's files, this
// project's sources), the step logs of corpora/ and of docs/benchmarks.md
// read as steps at most 0.014 (engrave-4axis; the timed logs 0.0002-0.0024):
// a stepper turned back every few steps does not draw. Such a block is
// coded raw (zstd, or the CM raw block; not with --no-raw, which leaves
// only the chain encodings) without the chain encodings, which
// never won there and were half the compression's time (the profile trials,
// the cuts, the segment models; docs/benchmarks.md "Text read as steps").
// (Two-axis blocks keep them: a random walk's step model wins.)
constexpr std::uint64_t kTextReversals = 8;
constexpr std::uint64_t kTextMinMoves = 4096;

}  // namespace

bool reads_as_text(const Block& block) {
    if (block.axes <= 2) return false;
    std::uint64_t moves = 0, reversals = 0;
    for (const Chain& c : block.chains) {
        std::array<int, kMaxAxes> last{};
        for (const Step st : c.steps)
            for (int a = 0; a < block.axes; ++a) {
                const int d = step_axis(st, a);
                if (d == 0) continue;
                reversals += last[static_cast<std::size_t>(a)] == -d;
                last[static_cast<std::size_t>(a)] = d;
                ++moves;
            }
    }
    return moves >= kTextMinMoves && reversals * kTextReversals > moves;
}

// Order-2 against order-0 entropy of a two-axis block's steps (the symbol
// before the chain's first two steps is "none"): real chains have H2 at
// most 0.6 H0 (traced glyphs and icons 0.24-0.55, plots 0.16-0.59 on
// corpora/ and the several-MB inputs), random walks 0.999-1.000.
constexpr std::uint64_t kPlainStepsTenths = 9;  // H2 >= 9/10 H0: plain
constexpr std::uint64_t kPlainStepsMin = 1u << 14;

bool plain_steps(const Block& block) {
    if (block.axes != 2) return false;
    std::array<std::uint64_t, 16> c0{};
    std::vector<std::uint64_t> c2(17 * 17 * 16, 0);
    std::uint64_t n = 0;
    for (const Chain& c : block.chains) {
        unsigned a = 16, b = 16;  // (none)
        for (const Step st : c.steps) {
            const unsigned x = st & 15u;
            ++c0[x];
            ++c2[(a * 17 + b) * 16 + x];
            a = b;
            b = x;
        }
        n += c.steps.size();
    }
    if (n < kPlainStepsMin) return false;
    auto bits = [](std::uint64_t v, std::uint64_t total) {
        return v == 0 ? 0.0 : -static_cast<double>(v) * std::log2(static_cast<double>(v) / static_cast<double>(total));
    };
    double h0 = 0, h2 = 0;
    for (const std::uint64_t v : c0) h0 += bits(v, n);
    for (std::size_t ctx = 0; ctx < 17 * 17; ++ctx) {
        std::uint64_t t = 0;
        for (std::size_t x = 0; x < 16; ++x) t += c2[ctx * 16 + x];
        for (std::size_t x = 0; x < 16; ++x) h2 += bits(c2[ctx * 16 + x], t);
    }
    return h2 * 10 >= h0 * static_cast<double>(kPlainStepsTenths);
}

namespace {

// From kFastStepLevel, below the thorough levels: a block of
// kSmallBlockSteps or more that a table block codes is also coded by the
// segment model when its sample (kModelSampleSteps of whole chains spread
// over the block, their segments as cut) codes smaller by the segment model
// than by a table block; the segment model is kept when smaller than the
// table block. It decodes about 2.5 times slower than a table block; a
// margin of 1/32 (kept only when that much smaller) made -L 3 2.5-2.9 %
// larger on URW glyph contours once table blocks coded minor totals
// unpredicted, so the default level takes the smaller block
// (docs/benchmarks.md, "The default level against xz -9e").
constexpr std::uint64_t kModelSampleSteps = 1u << 15;

std::uint64_t step_count(const Block& block) {
    std::uint64_t n = 0;
    for (const Chain& c : block.chains) n += c.steps.size();
    return n;
}

// The first `limit` steps of `block` (whole chains, the last cut short),
// without its layout: a sample for estimates (block has more steps).
Block first_steps(const Block& block, std::uint64_t limit) {
    Block out;
    out.axes = block.axes;
    for (std::uint64_t steps = 0; steps < limit && out.chains.size() < block.chains.size();) {
        const Chain& c = block.chains[out.chains.size()];
        Chain piece;
        piece.axes = c.axes;
        piece.start = c.start;
        const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(limit - steps, c.steps.size()));
        piece.steps.assign(c.steps.begin(), c.steps.begin() + static_cast<std::ptrdiff_t>(n));
        steps += n;
        out.chains.push_back(std::move(piece));
    }
    return out;
}

// The step-model context order of the thorough levels: 0 (every order
// tried, the smallest kept) up to 2 * kMixSampleSteps steps; above, the
// order that codes the block's first kMixSampleSteps steps smallest (each
// order tried on the whole block was a tenth of -L 19's time on glyph
// contours; the same orders on every corpus file).
int thorough_step_order(const Block& block) {
    if (step_count(block) <= 2 * kMixSampleSteps) return 0;
    int order = 0;
    write_step_model(first_steps(block, kMixSampleSteps), 0, nullptr, &order);
    return order;
}

// The thorough levels make a zstd record (of the chain payload or of the
// block's bytes) at the level only when zstd at kZstdProbeLevel makes one
// under kZstdReach times the smallest record so far: on corpora/ the level
// 19 output is at most 1.8 times smaller than level 6's (trapezoid-2axis;
// 1.25-1.7 elsewhere) and takes 10-70 times as long.
// The chain payload (segments, no text) gains less from the level: at most
// 1.28 times (corpora/random/walk-4.fc; 1.00-1.13 on every other corpus
// file), so its reach is kChainZstdReach / 2.
constexpr int kZstdProbeLevel = 6;
constexpr std::size_t kZstdReach = 2;
constexpr std::size_t kChainZstdReach = 3;  // halves

bool zstd_may_win(std::string_view bytes, const std::string& best, bool chain_payload = false) {
    if (best.empty()) return true;
    const std::string probe = make_block_record(kRaw, 0, bytes, kZstdProbeLevel);
    if (chain_payload) return probe.empty() || 2 * probe.size() < kChainZstdReach * best.size();
    return probe.empty() || probe.size() < kZstdReach * best.size();
}

// raw_cm_may_win() (encoder.hpp): the CM raw block codes a block's bytes whole
// against a block `best` (a chain block, or zstd of the bytes) only where it
// may come out smaller: bytes of at most 2 kRawCmProbeBytes always; more,
// when its model codes kRawCmStretches stretches spread evenly over them
// (1/kRawCmProbeShare of them, at least kRawCmProbeBytes in all, one after
// the other) under a reach of `best` scaled to that share. Where the model
// learns (the stretches' second half costs it at least 1/kRawCmLearns less
// per byte than their first), the reach is kRawCmReach tenths: per byte the
// stretches cost it 1.27 times what the whole block's bytes do on
// corpora/plotter/gnuplot.hpgl (text: much to learn), 1.36-1.56 on contours
// and plots, and against a chain block the whole is kept only when 1/32
// under it, so stretches at 1.3 times `best` leave it no chance. Where it
// does not learn (random walks, step logs: the second half costs what the
// first does, or more) the stretches cost 1.003-1.005 times the whole on
// the random walks of corpora/ and the reach is 31/32: on those walks the
// whole came within 1 % of the step model and of zstd's Huffman-coded
// bytes, was never kept against the step model and was two thirds of -L 3's
// and -L 19's time (docs/benchmarks.md "The CM raw block on random walks").
// On 3-axis step logs read as steps the stretches came to 1.41-1.63 times
// `best` and the whole to 1.28-1.57.
constexpr std::size_t kRawCmProbeBytes = 32768;
constexpr std::size_t kRawCmProbeShare = 8;
constexpr std::size_t kRawCmStretches = 8;
constexpr std::size_t kRawCmReach = 13;  // tenths
constexpr std::size_t kRawCmLearns = 32;
// The whole is kept against a chain block only when 1/kRawCmMargin under it;
// where its model does not learn the stretches must be that far under `best`.
constexpr std::size_t kRawCmMargin = 32;

// The chains of `block` in eight stretches spread evenly over it, about
// `limit` steps in all: calls take(i, n) for each chain i of a stretch,
// where n (at least 1) is the number of steps the stretch still wants.
template <class Take>
void spread_stretches(const Block& block, std::uint64_t limit, Take take) {
    constexpr std::uint64_t kStretches = 8;
    const std::uint64_t total = step_count(block);
    std::uint64_t at = 0, next = 0, left = 0;
    const std::uint64_t each = std::max<std::uint64_t>(1, limit / kStretches);
    for (std::size_t i = 0; i < block.chains.size(); ++i) {
        const Chain& c = block.chains[i];
        if (left == 0 && at >= next && next < total) {
            left = each;
            next = std::max(next + total / kStretches, at + 1);
        }
        at += c.steps.size();
        if (left == 0) continue;
        take(i, left);
        left -= std::min<std::uint64_t>(left, c.steps.size());
    }
}

// About `limit` steps of `block` for estimates only: its stretches
// (spread_stretches), the last chain of each cut short, without its layout.
Block sample_of(const Block& block, std::uint64_t limit) {
    Block out;
    out.axes = block.axes;
    spread_stretches(block, limit, [&](std::size_t i, std::uint64_t left) {
        const Chain& c = block.chains[i];
        Chain piece;
        piece.axes = c.axes;
        piece.start = c.start;
        const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(left, c.steps.size()));
        piece.steps.assign(c.steps.begin(), c.steps.begin() + static_cast<std::ptrdiff_t>(n));
        out.chains.push_back(std::move(piece));
    });
    return out;
}

// The whole chains of `block`'s stretches (spread_stretches) with their
// segments in `cut`: a sample for estimates that needs no second cut.
void spread_chains(const Block& block, const Cut& cut, std::uint64_t limit, Block& out, Cut& out_cut) {
    out.axes = block.axes;
    spread_stretches(block, limit, [&](std::size_t i, std::uint64_t) {
        out.chains.push_back(block.chains[i]);
        out_cut.push_back(cut[i]);
    });
}

// The strong levels try the context-mixing step model (docs/FORMAT.md
// 1.11.4) on two-axis blocks against the mixed coding of the model the
// first pass chose, before zstd's blocks: on a block of more than
// kCmSampleSteps steps both code about kCmSampleSteps steps spread over it
// (no window): a segment-model block's whole chains (spread_chains(), with
// their cut), a step-model block's stretches (sample_of()); the step
// model is then coded from the window in the second pass
// (window_step_pass()) for the whole block. At -L 19 on corpora/ it made
// every glyph and traced file 8-33 % smaller and was taken on one plot
// file only (hershey-pages-grbl.fc, a step-model block before; 1 %).
constexpr std::uint64_t kCmSampleSteps = 1u << 16;
// A block of more than kCmSampleSteps steps that the context-mixing step
// model codes well below the segment model is known for one before its
// segments are cut (cm_step_model_first() below): on the block's whole
// chains spread over it (about kCmSampleSteps steps, cut greedily and at the
// default phase: the optimal segmenter's recut is most of the time there)
// the model must come out at least 1/kCmFirstMargin smaller than the mixed
// segment model of the cut whose plain model is smaller (chosen on
// glyphs-big.fc, urw-big-*.fc and pages-big-grbl.fc of docs/benchmarks.md;
// the greedy cut alone gave pages-big-grbl.fc to the model, 7.7 % larger).
// Such a block skips the segmenters, the other models and zstd (a third to
// a half of -L 19's time on glyph contours); others (plots, random walks,
// near ties) take the full choice. cm_step_model_may_win() asks the same
// margin of a segment-model block's sample.
constexpr std::size_t kCmFirstMargin = 16;

// Whether the model's `cm` bytes are at least 1/kCmFirstMargin below the
// mixed segment model's `segment` bytes.
bool cm_wins_by_margin(std::size_t cm, std::size_t segment) {
    return cm * kCmFirstMargin <= segment * (kCmFirstMargin - 1);
}

// The fast levels from kLightCmLevel try the light context-mixing step
// model (docs/FORMAT.md 1.11.3) on two-axis blocks that are coded by a model
// or a table block, the same way: on the block's sample against the first
// pass's coding of it, kept when at least 1/kLightCmGain smaller there (it
// decodes a few times slower than a table block: a block that gains less
// keeps the faster coding); docs/benchmarks.md "The light step model".
constexpr int kLightCmLevel = 2;
constexpr std::size_t kLightCmGain = 32;

// What light_cm_first() coded of a block's sample (0: not made); the later
// check takes the same sample and, for a table block without arcs, the same cut.
struct LightSample {
    std::size_t light = 0, table = 0, step = 0;
    std::uint64_t steps = 0;  ///< the sample's
};

bool light_wins(std::size_t light, std::size_t other) { return light * kLightCmGain < other * (kLightCmGain - 1); }

bool light_cm_may_win(BlockJob& job, const EncoderSettings& s, unsigned type, const std::string& best,
                      const LightSample& made) {
    const Block& block = job.block;
    if (s.thorough || s.level < kLightCmLevel || s.timed || block.axes != 2 || job.steps == 0 ||
        job.steps > kMaxBlockSteps || (type != kSegmentModel && type != kTable && type != kStepModel))
        return false;
    // (the whole block's coding is kept for cm_pass(), which takes it when
    // the window holds no steps)
    auto whole_wins = [&] {
        std::string model = write_light_cm_step_model(block);
        if (!light_wins(model.size() + 8, best.size())) return false;
        job.light_model = std::move(model);
        return true;
    };
    if (job.steps <= kCmSampleSteps) return whole_wins();
    Block sample;
    Cut cut;
    spread_chains(block, job.cut.empty() ? Cut(block.chains.size()) : job.cut, kCmSampleSteps, sample, cut);
    const std::size_t light = made.light != 0 ? made.light : write_light_cm_step_model(sample).size();
    std::size_t other = 0;
    if (type == kSegmentModel) other = write_segment_model(sample, s.profile, cut).size();
    else if (type == kTable && made.table != 0 && !s.arc_method) other = made.table;
    else if (type == kTable) other = write_table_block(sample, s.profile, cut, table_effort(s.level)).size();
    else other = made.step != 0 ? made.step : write_step_model(sample, kFastStepOrder).size();
    if (!light_wins(light, other)) return false;
    // A table block's matches reach across the whole block, the sample's
    // do not (the same glyphs at the same places: 0.875 on the sample, 1.01
    // on the whole block of pages-big-grbl.fc): against it the whole block.
    return type != kTable || whole_wins();
}

// The chains of `block`'s stretches (spread_stretches), the last of each
// cut short after the first of its segments in `cut` (lines under `p`) that
// reaches the steps the stretch still wants: a sample of about `limit`
// steps with its cut, where spread_chains() would take a long chain whole.
void spread_segments(const Block& block, const Cut& cut, Profile p, std::uint64_t limit, Block& out, Cut& out_cut) {
    out.axes = block.axes;
    const bool eight = profile_eight_connected(p);
    spread_stretches(block, limit, [&](std::size_t i, std::uint64_t left) {
        const Chain& c = block.chains[i];
        std::vector<Segment>& segs = out_cut.emplace_back();
        std::uint64_t n = 0;
        for (const Segment& seg : cut[i]) {
            if (n >= left) break;
            n += static_cast<std::uint64_t>(segment_length(seg.delta, block.axes, eight));
            segs.push_back(seg);
        }
        Chain piece;
        piece.axes = c.axes;
        piece.start = c.start;
        piece.steps.assign(c.steps.begin(), c.steps.begin() + static_cast<std::ptrdiff_t>(n));
        out.chains.push_back(std::move(piece));
    });
}

// Below kFastStepLevel a large block's table block is coded once, by the
// third pass (window_items_pass(), from the window when it holds items),
// where the only other coding the first pass would try is zstd of the bytes
// (tried when the table block comes under 5:1): when the table block of its
// sample (no window; the smaller share of matches makes it
// the larger) is at 5:1 or better (spread_segments(): a random walk's
// block is one chain). Before, the first pass coded the table
// block without the window and the third pass again with it (12-26 % of
// -L 1's instructions on several-MB inputs of many blocks), and the
// window's coding was the smaller on every block of those inputs
// (docs/benchmarks.md "Fast tier: each table block coded once").
// `plain`: the block is plain steps (choose_block()); `made`: what
// light_cm_first() coded of the sample (at kLightCmLevel: the light model
// must lose to the table block there, as light_cm_may_win() would find).
bool table_late_pays(const BlockJob& job, const EncoderSettings& s, const Cut& segs, bool plain,
                     const LightSample& made) {
    // (the frame's first block has no window: the first pass codes it once)
    const bool frame_start = job.first_chain == 0 && !job.block.continues;
    if (s.thorough || s.timed || s.window_log == 0 || s.arc_method || s.level >= kFastStepLevel || plain ||
        frame_start || job.steps < kSmallBlockSteps || job.steps > kMaxBlockSteps || job.bytes.size() > kMaxBlockBytes)
        return false;
    std::size_t table = made.table;
    std::uint64_t steps = made.steps;
    if (s.level >= kLightCmLevel && job.block.axes == 2) {
        if (job.steps <= kCmSampleSteps || made.light == 0 || table == 0 || light_wins(made.light, table)) return false;
    } else if (table == 0) {
        Block sample;
        Cut cut;
        spread_segments(job.block, segs, s.profile, kCmSampleSteps, sample, cut);
        table = write_table_block(sample, s.profile, cut, table_effort(s.level)).size();
        steps = step_count(sample);
    }
    // 5:1 of the sample's share of the block's bytes, by its steps
    return table * 5 * job.steps <= job.bytes.size() * steps;
}

// A step-model block of more than kMixSampleSteps steps is coded mixed only
// when its first chains (kMixSampleSteps steps, cut short, no window), or
// the sample of the context-mixing check when the first pass made one
// (cm_step_model_may_win()), are at least 1/kMixSampleGain smaller mixed
// than plain at order 1: on random
// walks mixing saves about 1 % (the block stays type 4) and the mixed
// encoding was a third of -L 19's time; on glyph contours it saves 10-25 %
// (chosen on corpora/random/walk-8.fc and corpora/glyphs/dejavu-8.fc).
constexpr std::size_t kMixSampleGain = 32;

// Whether mixed_pass() codes the step-model block `job` mixed.
bool mixed_pays(const BlockJob& job) {
    return job.mixed_pays >= 0 ? job.mixed_pays != 0 : mixed_step_model_pays(job.block);
}

// `sample_cm`: the model's size on the sample of a block over
// kCmSampleSteps when cm_step_model_first() made it, on the whole block of
// at most kCmSampleSteps when cm_small_first() made it (0: not made).
bool cm_step_model_may_win(BlockJob& job, const EncoderSettings& s, unsigned type, const std::string& best,
                           std::size_t sample_cm = 0) {
    const Block& block = job.block;
    if (s.level < kStrongLevel || s.timed || block.axes != 2 || job.steps == 0 || job.steps > kMaxBlockSteps)
        return false;
    const bool whole = job.steps <= kCmSampleSteps;
    if (type == kSegmentModel) {
        Block sample;
        Cut cut;
        if (!whole) spread_chains(block, job.cut, kCmSampleSteps, sample, cut);
        const Block& b = whole ? block : sample;
        const Cut& c = whole ? job.cut : cut;
        const std::size_t cm = sample_cm != 0 ? sample_cm : write_cm_step_model(b).size();
        const std::size_t segment = write_segment_model(b, s.profile, c, nullptr, false, true).size();
        // A sample of whole chains holds fewer of the block's repeats, which
        // the segment model's item matches gain more from: the model must
        // win by the margin of cm_step_model_first().
        if (!whole) return cm_wins_by_margin(cm, segment);
        return cm < segment;
    }
    if (type == kStepModel) {
        const Block sample = whole ? Block{} : sample_of(block, kCmSampleSteps);
        const Block& b = whole ? block : sample;
        const std::size_t cm = whole && sample_cm != 0 ? sample_cm : write_cm_step_model(b).size();
        const std::size_t mixed = write_mixed_step_model(b, 1).size();
        // Whether the mixed step model pays is decided on this sample too
        // (mixed_step_model_pays() codes another one, the block's first
        // kMixSampleSteps steps: a fifth of -L 19's time on a random walk).
        if (!whole) {
            const std::size_t plain = write_step_model(b, 1).size();
            job.mixed_pays = mixed * kMixSampleGain <= plain * (kMixSampleGain - 1);
        }
        return cm < mixed;
    }
    // A table block (arcs): on the whole block only. Not a raw block: the
    // window holds no steps of a block the first pass made raw
    // (compress.cpp), so it cannot become a step-model block.
    return type == kTable && whole && (sample_cm != 0 ? sample_cm : write_cm_step_model(block).size()) + 8 < best.size();
}

// Whether the segment model may code `block` (cut as `cut`) smaller than a
// table block: it does on the block's sample (spread_chains).
bool segment_model_may_pay(const Block& block, Profile p, const Cut& cut, const TableEffort& effort) {
    Block sample;
    Cut sample_cut;
    spread_chains(block, cut, kModelSampleSteps, sample, sample_cut);
    const std::size_t table = write_table_block(sample, p, sample_cut, effort).size();
    return write_segment_model(sample, p, sample_cut).size() < table;
}

// Segments every chain of `block` under `p` (cut_block()); errors name the
// source and the chain. Precondition: representable(block, p, block.axes),
// whose check of the steps is not made again (every caller has made it, on
// the block or on a block whose chains these are). The optimal segmenter reads up to
// kOptimalWindow steps from every start, which on long segments (plots)
// costs 15 times the rest of -L 19: it recuts only the chains whose greedy
// segments average under kOptimalMeanSteps steps; the others keep the
// greedy cut (chosen on corpora/plotter/gnuplot-grbl.fc, where all of the
// optimal cut's gain, 2.3 %, comes from such chains).
constexpr std::uint64_t kOptimalMeanSteps = 64;

Result<void> segment_block(const Block& block, Profile p, SegmenterKind kind, Cut& segs, SegmentStats& stats,
                           std::uint64_t first_chain, const std::string& source, CutCache* cache) {
    const bool optimal = kind == SegmenterKind::optimal;
    auto r = cut_block_cached(block.chains, block.axes, p, optimal ? BlockCut::greedy : block_cut_of(kind), segs,
                              cache, &stats, first_chain, true);
    if (!r) return make_error(r.error().code, source + ": " + r.error().message);
    if (!optimal) return {};
    // A two-axis block too dense for the segment model is left to the step model.
    if (block.axes == 2 && too_dense(segment_count(segs), step_count(block))) return {};
    Cut one;
    for (std::size_t i = 0; i < segs.size(); ++i) {
        if (segs[i].size() < 2 || block.chains[i].steps.size() >= kOptimalMeanSteps * segs[i].size()) continue;
        r = cut_accepted_block(std::span<const Chain>(&block.chains[i], 1), block.axes, p, BlockCut::optimal, one,
                               nullptr, first_chain + i);
        if (!r) return make_error(r.error().code, source + ": " + r.error().message);
        segs[i] = std::move(one[0]);
    }
    return {};
}

// The default-phase cut of every chain; false when a chain has none.
// Precondition: as segment_block()'s.
bool aligned_block_cut(const Block& block, Profile p, Cut& out, CutCache* cache) {
    return cut_block_cached(block.chains, block.axes, p, BlockCut::default_phase, out, cache, nullptr, 0, true).ok();
}

bool representable(const Block& block, Profile p, int axes) {
    if (block.axes != axes || block.axes > profile_max_axes(p)) return false;
    if (block.chains.size() > kMaxBlockChains) return false;
    std::uint64_t steps = 0;
    for (const Chain& c : block.chains) {
        steps += c.steps.size();
        if (!profile_accepts(p, c.steps, block.axes)) return false;
    }
    return steps <= kMaxBlockSteps;
}

// The segment-model cuts a level tries: the segmenter's; at the thorough
// levels also the greedy cut (when the segmenter is another: the fewest
// segments are not always the cheapest to code) and the default-phase cut.
// Below them, the default-phase cut alone when the sample chose it.
// `greedy_differs` (when given) tells whether the greedy cut was added.
std::vector<Cut> model_cuts(const Block& block, const EncoderSettings& s, Cut segs, bool segs_aligned,
                            bool* greedy_differs = nullptr) {
    if (greedy_differs) *greedy_differs = false;
    std::vector<Cut> cuts;
    if (!s.thorough) {
        Cut aligned;
        if (s.aligned_cut && !segs_aligned && aligned_block_cut(block, s.profile, aligned, s.cut_cache))
            cuts.push_back(std::move(aligned));
        else
            cuts.push_back(std::move(segs));
        return cuts;
    }
    if (s.segmenter != SegmenterKind::greedy && (s.segmenter != SegmenterKind::optimal || s.optimal_recut)) {
        Cut greedy;
        SegmentStats unused;
        // (the optimal cut keeps the greedy one where it is not better)
        if (segment_block(block, s.profile, SegmenterKind::greedy, greedy, unused, 0, s.source, s.cut_cache) && greedy != segs) {
            cuts.push_back(std::move(greedy));
            if (greedy_differs) *greedy_differs = true;
        }
    }
    Cut aligned;
    const bool have_aligned = aligned_block_cut(block, s.profile, aligned, s.cut_cache) && aligned != segs;
    cuts.insert(cuts.begin(), std::move(segs));
    if (have_aligned) cuts.push_back(std::move(aligned));
    return cuts;
}

// The smallest segment-model payload over `cuts` (the first on a tie);
// `which` is its index.
std::string smallest_segment_model(const Block& block, Profile p, std::vector<Cut>& cuts,
                                   std::size_t& which, bool timed) {
    std::string best;
    for (std::size_t i = 0; i < cuts.size(); ++i) {
        if (timed)
            for (auto& chain : cuts[i]) align_timed_phases(p, block.axes, chain);
        std::string alt = write_segment_model(block, p, cuts[i], nullptr, timed);
        if (best.empty() || alt.size() < best.size()) {
            best = std::move(alt);
            which = i;
        }
    }
    return best;
}

// Timed frames: the timed block (type 7 subtype 0) of each cut, taken when
// smaller than `best` (of type `type`). At the strong levels, where the
// mixed pass codes the chosen model again with mixed predictions once the
// window has been noted (and the phases of the cut can no longer change),
// the two are compared with mixed predictions (no window) instead.
void timed_choice(BlockJob& job, const EncoderSettings& s, const std::vector<Cut>& cuts, unsigned& type,
                  std::string& best) {
    const bool strong = s.level >= kStrongLevel;
    std::size_t bar = best.empty() ? SIZE_MAX : best.size();
    if (strong && type == kSegmentModel)
        bar = write_segment_model(job.block, s.profile, job.cut, nullptr, true, true).size();
    for (const Cut& cut : cuts) {
        Cut aligned = cut;
        const std::string timed = write_timed_block(job.block, s.profile, aligned);
        if (timed.empty() || timed.size() > kMaxBlockPayload) continue;
        std::string rec = make_stored_record(kExtended, job.flags, timed);
        const std::size_t size =
            strong && type == kSegmentModel ? write_timed_block(job.block, s.profile, aligned, nullptr, true).size()
                                            : rec.size();
        if (size >= bar) continue;
        bar = size;
        best = std::move(rec);
        type = kExtended;
        job.cut = std::move(aligned);
    }
}

// Timed frames: the plain codings of a block's first kTimedPrefix ticks
// (the whole block when smaller) decide (TimedCheck) whether the
// segment-based codings (the cuts, the segment model, the timed block) are
// made: when the plain segment model of the greedy cut (phases aligned)
// is smaller there than the smaller of the plain tick and interrupt
// blocks; and, at the strong levels, which of these two is coded with
// mixed predictions. On the eleven timed streams of docs/benchmarks.md
// ("Timed streams at -L 19: sure decisions") the segment model came to
// 1.16-1.70 times the tick blocks on such prefixes, and lost on every block.
// The prefix is whole ticks in a row: a few stretches of 2^12 ticks
// (sample_of()) hold too few steps, and the segment model, which learns
// faster, was the smaller on most of them.
constexpr std::uint64_t kTimedPrefix = std::uint64_t{1} << 18;
// The mixed codings favour the interrupt block: its guided mixing has the
// crossing contexts, which the tick block lacks, and on the eleven timed
// streams the whole interrupt block coded mixed came to 0.6-5.2 % less,
// against the tick block, than coded plain. So the mixed codings take the
// interrupt block unless its plain prefix is over 1/32 larger than the
// tick block's (docs/benchmarks.md "Timed streams: the interrupt block
// when mixed"; the plain codings keep the smaller plain one).
constexpr std::size_t kMixedIrqMargin = 32;

TimedCheck timed_check(const Block& block, const EncoderSettings& s) {
    TimedCheck c;
    const bool whole = step_count(block) <= kTimedPrefix;
    const Block prefix = whole ? Block{} : first_steps(block, kTimedPrefix);
    const Block& sample = whole ? block : prefix;
    const std::string tick = write_tick_block(sample), irq = write_interrupt_block(sample);
    if (tick.empty() || irq.empty()) return c;
    c.irq = irq.size() < tick.size();
    c.irq_mixed = irq.size() * kMixedIrqMargin <= tick.size() * (kMixedIrqMargin + 1);
    if (whole) c.plain = c.irq ? irq : tick;
    Cut segs;
    SegmentStats stats;
    if (!representable(sample, s.profile, sample.axes) ||
        !segment_block(sample, s.profile, SegmenterKind::greedy, segs, stats, 0, s.source, nullptr))
        return c;
    for (auto& chain : segs) align_timed_phases(s.profile, sample.axes, chain);
    c.segments = write_segment_model(sample, s.profile, segs, nullptr, true).size() < std::min(tick.size(), irq.size());
    return c;
}

// Timed frames at the thorough levels: the first block's TimedCheck, kept
// in `s` for the block's own choice; whether its segment-based codings may win.
bool timed_first_check(const Block& first, EncoderSettings& s) {
    s.timed_first = timed_check(first, s);
    s.timed_first_chains = first.chains.size();
    s.timed_first_steps = step_count(first);
    return s.timed_first.segments;
}

// Whether a block of `steps` steps takes the early checks of a step model
// (cm_step_model_first(), light_cm_first()): a large two-axis block that
// the profile can represent, not timed.
bool early_model_check_applies(const Block& block, std::uint64_t steps, const EncoderSettings& s) {
    return !s.timed && block.axes == 2 && block.axes == s.axes && steps > kCmSampleSteps && steps <= kMaxBlockSteps &&
           representable(block, s.profile, s.axes);
}

// Their sample: the whole chains of `block` spread over it, about
// kCmSampleSteps steps (the sample the later checks take).
Block whole_chains_sample(const Block& block) {
    Block sample;
    sample.axes = block.axes;
    spread_stretches(block, kCmSampleSteps, [&](std::size_t i, std::uint64_t) { sample.chains.push_back(block.chains[i]); });
    return sample;
}

// `sample_cm`, when given: the model's size on the sample if known (not 0),
// set to it when made.
bool cm_step_model_first(const Block& block, std::uint64_t steps, const EncoderSettings& s, std::size_t* sample_cm = nullptr) {
    if (s.level < kStrongLevel || !s.thorough || !early_model_check_applies(block, steps, s)) return false;
    const Block sample = whole_chains_sample(block);
    Cut segs;
    SegmentStats stats;
    EncoderSettings greedy = s;
    greedy.segmenter = SegmenterKind::greedy;
    if (!segment_block(sample, s.profile, SegmenterKind::greedy, segs, stats, 0, s.source, s.cut_cache)) return false;
    if (too_dense(segment_count(segs), step_count(sample))) return false;  // the step model's ground
    std::vector<Cut> cuts = model_cuts(sample, greedy, std::move(segs), false);
    std::size_t which = 0;
    smallest_segment_model(sample, s.profile, cuts, which, false);
    const std::size_t mixed = write_segment_model(sample, s.profile, cuts[which], nullptr, false, true).size();
    // (the sample is the same under every profile: its model's size, when
    // known, is not made again)
    const std::size_t cm = sample_cm && *sample_cm != 0 ? *sample_cm : write_cm_step_model(sample).size();
    if (sample_cm) *sample_cm = cm;
    return cm != 0 && cm_wins_by_margin(cm, mixed);
}

// A first block of at most kThoroughSampleSteps steps is the profiles'
// ranking trial itself (every profile, the optimal segmenter, every cut,
// the segment model of each: two thirds of -L 19's time on a 25 KB glyph
// file). At the strong levels under --profile auto such a two-axis block
// is first checked for the context-mixing step model on the whole block,
// under the profile whose greedy or default-phase cut codes smallest by
// the plain segment model (profiles too dense for the segment model left
// out; that profile won the ranking on every corpus file the model
// codes): it is the model's when the model codes it in at most
// (kCmPlainGain - 1) / kCmPlainGain of that plain model's size, or else
// in at most (kCmFirstMargin - 1) / kCmFirstMargin of its mixed coding
// (as cm_step_model_first()). The model's payload is then the block's
// record (no window: the first block's), and the ranking is skipped. On
// corpora/ the model came to 0.60-0.70 of the plain segment model on
// glyph and traced contours and 0.76 on hershey-pages-grbl.fc (0.93 of
// the mixed one), 0.96-1.33 on the other plots (chosen on
// corpora/glyphs/c059-8.fc, traced/icons-8.fc, plotter/hershey-pages-grbl.fc
// and plotter/hershey-eval4.fc). Otherwise the profiles are ranked as
// before and `cm_first_size` keeps the model's size for the block's choice.
constexpr std::size_t kCmPlainGain = 4;
// Steps spread over the block on which the profile is guessed.
constexpr std::uint64_t kGuessSteps = 1u << 13;

// The plain segment model of `block` under `p`, the smaller of its greedy
// and default-phase cuts (that cut in `cut`); SIZE_MAX when `p` cannot
// represent the block or its greedy cut is too dense for the segment model.
std::size_t greedy_plain_size(const Block& block, Profile p, const EncoderSettings& s, Cut& cut,
                              std::uint64_t* dense_segments = nullptr) {
    if (!representable(block, p, block.axes)) return SIZE_MAX;
    Cut segs;
    SegmentStats stats;
    if (!segment_block(block, p, SegmenterKind::greedy, segs, stats, 0, s.source, s.cut_cache)) return SIZE_MAX;
    const std::uint64_t nsegs = segment_count(segs);
    if (too_dense(nsegs, step_count(block))) {  // the step model's ground
        if (dense_segments) *dense_segments = nsegs;
        return SIZE_MAX;
    }
    EncoderSettings greedy = s;
    greedy.segmenter = SegmenterKind::greedy;
    greedy.profile = p;
    std::vector<Cut> cuts = model_cuts(block, greedy, std::move(segs), false);
    std::size_t which = 0;
    const std::size_t n = smallest_segment_model(block, p, cuts, which, false).size();
    cut = std::move(cuts[which]);
    return n;
}

// The profile whose greedy or default-phase cut codes kGuessSteps spread
// over `block` smallest by the plain segment model (greedy_plain_size());
// false when every profile is too dense for the segment model there.
// `cut` and `size`: that cut and size when the sample is the whole block
// (else empty and 0). `fewest`: when every profile that can represent the
// sample is too dense there (random walks), the one with the fewest
// segments (the first on a tie), as the ranking orders them.
bool guess_profile(const Block& block, const EncoderSettings& s, Profile& guess, Cut& cut, std::size_t& size,
                   std::optional<Profile>* fewest = nullptr) {
    const bool sampled = step_count(block) > kGuessSteps;
    const Block sample = sampled ? sample_of(block, kGuessSteps) : Block{};
    size = SIZE_MAX;
    std::uint64_t least_segments = UINT64_MAX;
    for (Profile p : kAllProfiles) {
        Cut c;
        std::uint64_t segments = UINT64_MAX;
        const std::size_t n = greedy_plain_size(sampled ? sample : block, p, s, c, &segments);
        if (n < size) {
            size = n;
            guess = p;
            cut = std::move(c);
        }
        if (segments < least_segments) {
            least_segments = segments;
            if (fewest) *fewest = p;
        }
    }
    if (size == SIZE_MAX) return false;
    if (fewest) fewest->reset();
    if (sampled) {  // (not the whole block's)
        cut.clear();
        size = 0;
    }
    return true;
}

// `dense`: set when every profile was too dense for the segment model on
// the guess's sample (guess_profile()'s `fewest`).
bool cm_small_first(const Block& first, std::uint64_t steps, EncoderSettings& s, std::optional<Profile>& dense) {
    if (s.level < kStrongLevel || s.timed || !s.thorough || s.profile_named || first.axes != 2 || steps == 0 ||
        steps > kThoroughSampleSteps || first.chains.size() > kMaxBlockChains)
        return false;
    Profile guess = s.profile;
    Cut guess_cut;
    std::size_t plain = 0;
    if (!guess_profile(first, s, guess, guess_cut, plain, &dense)) return false;  // random walks
    if (plain == 0) plain = greedy_plain_size(first, guess, s, guess_cut);
    if (plain == SIZE_MAX) return false;
    auto model = std::make_shared<std::string>(write_cm_step_model(first));
    const std::size_t cm = model->size();
    bool take = cm != 0 && cm * kCmPlainGain <= plain * (kCmPlainGain - 1);
    if (!take && cm != 0) {
        const std::size_t mixed = write_segment_model(first, guess, guess_cut, nullptr, false, true).size();
        take = cm_wins_by_margin(cm, mixed);
    }
    s.cm_first_chains = first.chains.size();
    s.cm_first_steps = steps;
    if (!take) {
        s.cm_first_size = cm;
        return false;
    }
    s.profile = guess;
    s.cm_first = true;
    s.cm_first_model = std::move(model);
    return true;
}

// A large two-axis block at the fast levels from kLightCmLevel that the
// light step model codes far below the other encodings is known for one
// before the whole block is cut: its whole chains spread over it (about
// kCmSampleSteps steps, cut as the block would be) coded by the light model
// must come out at least 1/kLightFirstMargin smaller than the table block,
// the segment model and the step model of the same sample (at -L 2 too,
// which tries the last two on large blocks only here: without this check
// -L 2 coded such a block's table block first and was slower than -L 3,
// with the same bytes). Such a block skips the cut, the other
// encodings and the whole-block trials of light_cm_may_win() (most of the
// first pass on large contours); the others take the full choice, which
// reuses the light model's size on the sample. The margin (chosen on
// glyphs-big.fc, pages-big-grbl.fc and corpora/glyphs: glyph samples come
// out at 0.73-0.87 of the other encodings, plots at 1.02-1.45) leaves
// the near cases to the full choice, where the whole block's table block,
// whose matches the sample cannot see, may still win (repeated glyphs of
// plots: hershey-pages-grbl.fc's sample is at 0.89).
constexpr std::size_t kLightFirstMargin = 8;

// `made`: what it coded of the sample (light_cm_may_win() reuses it).
bool light_cm_first(const Block& block, std::uint64_t steps, const EncoderSettings& s, LightSample& made) {
    if (s.thorough || s.level < kLightCmLevel || !early_model_check_applies(block, steps, s)) return false;
    const Block sample = whole_chains_sample(block);
    Cut cut;
    SegmentStats stats;
    // Cut as choose_block() cuts the block; the cuts go to the frame's
    // cache, where the block's own cut finds them.
    const bool aligned = s.aligned_cut && s.segmenter != SegmenterKind::patent &&
                         aligned_block_cut(sample, s.profile, cut, s.cut_cache);
    const SegmenterKind kind =
        s.segmenter == SegmenterKind::optimal && !s.optimal_recut ? SegmenterKind::greedy : s.segmenter;
    if (!aligned && !segment_block(sample, s.profile, kind, cut, stats, 0, s.source, s.cut_cache)) return false;
    made.light = write_light_cm_step_model(sample).size();
    made.steps = step_count(sample);
    // The other encodings one by one, the likelier to win first (on chains
    // too dense for the segment model, random walks, the step model; else
    // the table block, where plots fail): each size is reused by the later
    // check for a block of its type. The segment model only where
    // choose_block() tries it.
    auto beats = [&](std::size_t other) { return made.light * kLightFirstMargin <= other * (kLightFirstMargin - 1); };
    if (made.light == 0) return false;
    const bool dense = too_dense(segment_count(cut), step_count(sample));
    auto step_beaten = [&] { return beats(made.step = write_step_model(sample, kFastStepOrder).size()); };
    auto table_beaten = [&] {
        return beats(made.table = write_table_block(sample, s.profile, cut, table_effort(s.level)).size());
    };
    if (dense) return step_beaten() && table_beaten();
    return table_beaten() && step_beaten() && beats(write_segment_model(sample, s.profile, cut).size());
}

}  // namespace

// What a profile trial made: the segmenter's cut, its statistics and, but
// on a block too dense for the segment model, the cuts the segment model
// tried and the smallest model (cuts[which]).
struct FirstBlockTrial {
    Profile profile = Profile::eval8;
    Block block;  // the block the trial coded
    Cut segs;
    SegmentStats stats;
    std::vector<Cut> cuts;
    std::size_t which = 0;
    std::string model;
    bool optimal_pays = true;  // the optimal segmenter's cut was the greedy one or made the smallest model
};

namespace {

// Encoded size of a block under `p` (for --profile auto at the thorough
// levels); SIZE_MAX when `p` cannot represent it. `trial` receives the cuts
// and the model when given.
std::size_t trial_size(const Block& block, Profile p, const EncoderSettings& base, FirstBlockTrial* trial = nullptr) {
    if (!representable(block, p, block.axes)) return SIZE_MAX;
    EncoderSettings s = base;
    s.profile = p;
    Cut segs;
    SegmentStats stats;
    // The profiles are ranked by their segment models alone: zstd at the
    // level costs seconds per MB and changed the ranking on no corpus file.
    // (The greedy cut in place of the optimal one did: the 3.7 MB glyph
    // file of docs/benchmarks.md took eval8 instead of marlin, 2.6 % larger.)
    if (!segment_block(block, p, s.segmenter, segs, stats, 0, s.source, s.cut_cache)) return SIZE_MAX;
    if (trial) {
        *trial = FirstBlockTrial{};
        trial->profile = p;
        trial->segs = segs;
        trial->stats = stats;
    }
    // A two-axis block too dense for the segment model (random walks) is
    // coded by the step model, the same under every profile: such a profile
    // ranks after every other, by its count of segments (no model is made).
    if (block.axes == 2) {
        const std::uint64_t nsegs = segment_count(segs);
        if (too_dense(nsegs, step_count(block))) return SIZE_MAX / 2 + nsegs;
    }
    std::size_t which = 0;
    bool greedy_differs = false;
    std::vector<Cut> cuts = model_cuts(block, s, segs, false, &greedy_differs);
    std::string model = smallest_segment_model(block, p, cuts, which, s.timed);
    const std::size_t size = model.size();
    if (trial) {
        // (a cut equal to the greedy one on the trial leaves the question open)
        trial->optimal_pays = s.segmenter == SegmenterKind::optimal && (!greedy_differs || which == 0);
        trial->cuts = std::move(cuts);
        trial->which = which;
        trial->model = std::move(model);
    }
    return size;
}

// The optimal segmenter's cut is the ranking trial's costliest part (each
// chain's segments read up to 1024 steps from every start), and on the
// trials of corpora/ it made a profile's model at most 0.86 % smaller than
// its greedy and default-phase cuts did (dejavu-8.fc; on the plots and the
// 4-axis log never smaller), and it never changed which profile those cuts
// ranked first on a 2^15-step sample or a plot's trial. So every candidate
// is first ranked by those two cuts, and only those within
// 1/kOptimalReach of the best there are tried with the optimal segmenter's
// cut too (chosen on corpora/glyphs/dejavu-8.fc, plotter/hershey-eval8.fc,
// plotter/hershey-grbl.fc and stepper/engrave-4axis.steps).
constexpr std::size_t kOptimalReach = 100;

void optimal_candidates(const Block& trial, const EncoderSettings& s, std::vector<Profile>& candidates) {
    if (s.segmenter != SegmenterKind::optimal || candidates.size() < 2) return;
    EncoderSettings greedy = s;
    greedy.segmenter = SegmenterKind::greedy;
    std::vector<std::size_t> sizes;
    std::size_t least = SIZE_MAX;
    for (Profile p : candidates) {
        sizes.push_back(trial_size(trial, p, greedy));
        least = std::min(least, sizes.back());
    }
    if (least == SIZE_MAX) return;
    std::vector<Profile> kept;
    for (std::size_t i = 0; i < candidates.size(); ++i)
        if (sizes[i] != SIZE_MAX && sizes[i] - least <= least / kOptimalReach) kept.push_back(candidates[i]);
    candidates = std::move(kept);
}

// The trial of `s.profile` on this very block, if the ranking made one.
const FirstBlockTrial* trial_of(const BlockJob& job, const EncoderSettings& s) {
    const FirstBlockTrial* t = s.first_trial.get();
    // The whole block must match, its layout and flags too: a block cut for
    // the size of its layout can have the first block's (empty) chains.
    if (!t || t->profile != s.profile || job.first_chain != 0 || t->block.axes != job.block.axes ||
        t->block.continues != job.block.continues || t->block.open != job.block.open ||
        t->block.layout != job.block.layout || t->block.chains != job.block.chains)
        return nullptr;
    return t;
}

// Below the thorough levels: the segment-model size of the first block's
// sample under `p` with the segmenter's cut and, but for the patent profile,
// with the default-phase cut; SIZE_MAX when `p` cannot represent the
// sample. `aligned` tells which cut was smaller.
std::size_t sample_size(const Block& sample, Profile p, const EncoderSettings& base, bool& aligned) {
    aligned = false;
    if (!representable(sample, p, sample.axes)) return SIZE_MAX;
    Cut segs;
    SegmentStats stats;
    if (!segment_block(sample, p, base.segmenter, segs, stats, 0, base.source, base.cut_cache)) return SIZE_MAX;
    std::size_t best = write_segment_model(sample, p, segs).size();
    Cut cut;
    if (p != Profile::patent && aligned_block_cut(sample, p, cut, base.cut_cache)) {
        const std::size_t alt = write_segment_model(sample, p, cut).size();
        if (alt < best) {
            best = alt;
            aligned = true;
        }
    }
    return best;
}

// The first block's context-mixing step model made by cm_small_first()
// as its record: what cm_pass() makes of it (the first block's window is
// empty). A model that cannot code the block is left to cm_pass(), which
// finds so again and gives the block to the step model.
void take_cm_first(BlockJob& job, const std::string& model) {
    if (model.empty() || model.size() > kMaxBlockPayload) return;
    job.record = make_stored_record(kMixedModel, job.flags, model);
    job.cm_coded = true;
}

}  // namespace

bool raw_cm_may_win(std::string_view raw, std::size_t best) {
    if (best == 0 || raw.size() <= 2 * kRawCmProbeBytes) return true;
    const std::size_t each = std::max(raw.size() / kRawCmProbeShare, kRawCmProbeBytes) / kRawCmStretches;
    std::string probe;
    probe.reserve(each * kRawCmStretches);
    for (std::size_t k = 0; k < kRawCmStretches; ++k) probe += raw.substr(raw.size() / kRawCmStretches * k, each);
    std::size_t half = 0;
    const std::string coded = write_raw_cm_block(probe, &half);
    if (coded.empty()) return true;
    // (bytes per input byte of the two halves: the first holds the header's
    // few bytes too)
    const std::size_t first_in = probe.size() / 2, second_in = probe.size() - first_in;
    const std::size_t second = coded.size() > half ? coded.size() - half : 0;
    const bool learns = static_cast<double>(second) * static_cast<double>(first_in) * kRawCmLearns <
                        static_cast<double>(half) * static_cast<double>(second_in) * (kRawCmLearns - 1);
    // coded / probe bytes < reach * best / raw bytes
    const double reach = learns ? static_cast<double>(kRawCmReach) / 10.0
                                : static_cast<double>(kRawCmMargin - 1) / static_cast<double>(kRawCmMargin);
    return static_cast<double>(coded.size()) * static_cast<double>(raw.size()) <
           reach * static_cast<double>(best) * static_cast<double>(probe.size());
}

TableEffort table_effort(int level) {
    TableEffort e;
    e.recent_search = level <= 1 ? 16 : level <= 3 ? 64 : level <= 6 ? 256 : 1024;
    e.minors = MinorCoding::smaller;
    return e;
}

int window_log_for_level(int level) {
    // In steps + chains (about bytes of Freeman text); zstd's and xz's level
    // tables are the anchors: a few MiB at the fast levels, 8 MiB at the top.
    // A block is in the window whole or not at all, so the window holds
    // three blocks of the default 2^20 steps (with their chains) from level
    // 1 on: 2^21 held one, and a repeat farther than a block was missed.
    if (level < kThoroughLevel) return 22;
    return kMaxWindowLog;
}

Result<void> choose_frame_settings(const Block& first, EncoderSettings& s) {
    s.axes = first.axes;
    // The optimal segmenter implied by the level cuts two-axis frames only:
    // on more axes each start reads up to 1024 steps through the general
    // run-word recognizer, 90 % of -L 19's time on a 3-axis log of 85 kB
    // (1.3 s), and on the 3- and 4-axis logs measured (corpora/stepper,
    // corpora/timed read as steps, the 3-axis timed stream of
    // docs/benchmarks.md) its blocks came out the same bytes as the greedy
    // cut's but one, 0.3 % smaller (docs/benchmarks.md "The optimal
    // segmenter on more axes").
    if (!s.segmenter_named && s.segmenter == SegmenterKind::optimal && first.axes > 2) s.segmenter = SegmenterKind::greedy;
    std::optional<Profile> dense;
    if (!s.timed && s.allow_raw && reads_as_text(first)) {
        // (raw blocks only: no profile to rank)
    } else if (!s.profile_named && s.thorough && cm_small_first(first, step_count(first), s, dense)) {
        // (a small first block left to the context-mixing step model)
    } else if (!s.profile_named && s.thorough && s.timed && !timed_first_check(first, s)) {
        // (a timed frame whose first block the tick or interrupt block codes:
        // the profiles are ranked by segment models, which code none of it)
    } else if (!s.profile_named && s.thorough) {
        // A sample of kThoroughSampleSteps ranks the profiles, as the
        // sample of the fast levels (the whole block when smaller).
        const std::uint64_t steps = step_count(first);
        const Block sample = steps > kThoroughSampleSteps ? sample_of(first, kThoroughSampleSteps) : Block{};
        const Block& trial = steps > kThoroughSampleSteps ? sample : first;
        // On a block larger than the trial, every profile first on a small
        // sample (kSampleSteps); only those within 1/kRankMargin (+
        // kRankSlack bytes) of the best there are tried on the trial (none
        // when one alone is). On a smaller block the small sample would cost
        // a third of the trial and, on 8-connected contours, leave every
        // profile in.
        std::vector<Profile> candidates;
        if (steps <= kThoroughSampleSteps && dense) {
            // Too dense for the segment model under every profile (random
            // walks): the step model codes the block the same under each, and
            // the trial ranked them by their segments on the whole block; now
            // on the guess's sample (cm_small_first()), the trial made for the
            // one with the fewest there (four fifths of the ranking's time,
            // a fifth of -L 19's, on corpora/random/).
            candidates.push_back(*dense);
        } else if (steps <= kThoroughSampleSteps) {
            for (Profile p : kAllProfiles)
                if (representable(first, p, first.axes)) candidates.push_back(p);
        } else {
            // At the strong levels, a first block that the context-mixing
            // step model codes (cm_step_model_first(), under the profile
            // guessed by guess_profile()) keeps that profile: the ranking
            // ranks segment models, which then code none of it (a third of
            // -L 19's time on a 0.5 MB glyph file, a quarter on 0.3 MB).
            // The block's own choice takes what the check found.
            Profile guess = s.profile;
            Cut unused_cut;
            std::size_t unused_size = 0;
            if (s.level >= kStrongLevel && !s.timed && first.axes == 2 &&
                guess_profile(first, s, guess, unused_cut, unused_size)) {
                EncoderSettings probe_settings = s;
                probe_settings.profile = guess;
                std::size_t sample_cm = 0;
                s.cm_first_chains = first.chains.size();
                s.cm_first_steps = steps;
                if (cm_step_model_first(first, steps, probe_settings, &sample_cm)) {
                    candidates.assign(1, guess);
                    s.cm_first = true;
                } else {
                    s.cm_first_declined = guess;
                    s.cm_first_sample = sample_cm;
                }
            }
            if (candidates.empty()) {
                // (greedy and default-phase cuts only: ranked_sizes())
                const Block small = sample_of(first, kSampleSteps);
                std::size_t sizes[std::size(kAllProfiles)];
                std::size_t least = SIZE_MAX;
                EncoderSettings greedy = s;
                greedy.segmenter = SegmenterKind::greedy;
                for (std::size_t i = 0; i < std::size(kAllProfiles); ++i) {
                    const Profile p = kAllProfiles[i];
                    sizes[i] = representable(first, p, first.axes) ? trial_size(small, p, greedy) : SIZE_MAX;
                    least = std::min(least, sizes[i]);
                }
                for (std::size_t i = 0; i < std::size(kAllProfiles); ++i)
                    if (sizes[i] != SIZE_MAX && sizes[i] - least <= least / kRankMargin + kRankSlack)
                        candidates.push_back(kAllProfiles[i]);
            }
        }
        const bool whole = steps <= kThoroughSampleSteps;
        if (candidates.size() == 1) s.profile = candidates[0];
        // When the trial is the whole block, the winner's cuts and model are
        // kept for the block's own choice (choose_block()). The optimal
        // segmenter recuts the frame's blocks unless its cut, other than the
        // greedy one, lost to another cut in the winner's trial: on corpora/
        // it changed the -L 19 size of one file (plotter/gnuplot-grbl.fc,
        // 2.3 % smaller) and was 35-90 % of the time of contours and of the
        // 4-axis log.
        auto kept = std::make_shared<FirstBlockTrial>();
        FirstBlockTrial made;
        std::size_t best = SIZE_MAX;
        // A profile alone after the screening takes the trial too (but for a
        // block left to the context-mixing step model): without it the
        // optimal segmenter would recut the whole block (on
        // plotter/hershey-patent.fc two thirds of -L 19's time, for the
        // same bytes).
        const bool single = candidates.size() == 1 && !s.cm_first && s.segmenter == SegmenterKind::optimal;
        std::vector<Profile> tried = candidates.size() > 1 || whole || single ? candidates : std::vector<Profile>{};
        optimal_candidates(trial, s, tried);
        for (Profile p : tried) {
            const std::size_t n = trial_size(trial, p, s, &made);
            if (n < best) {
                best = n;
                s.profile = p;
                std::swap(*kept, made);
            }
        }
        if (best != SIZE_MAX) {
            s.optimal_recut = kept->optimal_pays;
            if (whole) {
                kept->block = first;
                s.first_trial = std::move(kept);
            }
        }
    } else if (!s.thorough && representable(first, s.profile, first.axes)) {
        // One sample picks the profile (auto) and the cut. On 4-connected
        // chains (those eval4 represents) every segment of an 8-connected
        // profile is a run along one axis (a step of both is a diagonal
        // one), whose phase is implied: eval8, grbl and marlin cut and code
        // them alike, and the later two, which a tie never chooses, are not
        // tried (two fifths of the choice on such chains).
        static_assert(kAllProfiles[0] == Profile::eval4 && kAllProfiles[1] == Profile::eval8);
        const Block sample = sample_of(first, kSampleSteps);
        std::size_t best = SIZE_MAX;
        bool four_connected = false;
        for (Profile p : kAllProfiles) {
            if (s.profile_named && p != s.profile) continue;
            if (four_connected && (p == Profile::grbl || p == Profile::marlin)) continue;
            bool aligned = false;
            const std::size_t n = sample_size(sample, p, s, aligned);
            if (p == Profile::eval4) four_connected = n != SIZE_MAX;
            if (n < best) {
                best = n;
                s.profile = p;
                s.aligned_cut = aligned;
            }
        }
    }
    if (s.profile_named && s.axes > profile_max_axes(s.profile))
        return make_error(Errc::invalid_argument, s.source + ": profile " + std::string(profile_name(s.profile)) +
                                                      " does not take " + std::to_string(s.axes) + " axes");
    return {};
}

void begin_contribution(BlockJob& job, const EncoderSettings& s) {
    if (s.window_log == 0) return;
    auto w = std::make_shared<WindowBlock>();
    w->weight = step_count(job.block) + job.block.chains.size();
    if (s.timed) w->ticks = tick_masks(job.block);
    job.contribution = std::move(w);
}

void end_contribution(BlockJob& job) {
    if (!job.contribution || job.type != kRaw || job.contribution->ticks.empty()) return;
    job.contribution->ticks = {};
    job.contribution->ticks_dropped = true;
}

namespace {
// What the block `job` chose adds to the window (with one): its symbols
// when a block needs them (compress.cpp), its items after the second pass.
void add_contribution(BlockJob& job) {
    if (job.contribution) job.contribution->first_type = job.type;
}

// The record of a tick or interrupt block's payload, flagged `window` when
// its coding byte has the window bit.
std::string tick_record(unsigned flags, const std::string& tick) {
    const bool windowed = tick.size() >= 2 && (static_cast<unsigned char>(tick[1]) & kTickWindow);
    return make_stored_record(kExtended, flags | (windowed ? kFlagWindow : 0u), tick);
}
}  // namespace

void choose_block(BlockJob& job, const EncoderSettings& s) {
    const Block& block = job.block;
    job.flags = (block.continues ? kFlagContinues : 0u) | (block.open ? kFlagOpen : 0u);
    std::string best;
    unsigned type = kRaw;
    auto consider = [&](unsigned t, std::string rec) {
        if (rec.empty() || (!best.empty() && rec.size() >= best.size())) return false;
        best = std::move(rec);
        type = t;
        return true;
    };
    const bool fits = block.axes == s.axes && block.chains.size() <= kMaxBlockChains;
    job.steps = 0;
    for (const Chain& c : block.chains) job.steps += c.steps.size();
    // What choose_frame_settings() found out about this block (the first).
    const bool first = job.first_chain == 0 && s.cm_first_chains == block.chains.size() &&
                       s.cm_first_steps == job.steps;
    const bool known_cm = first && s.cm_first;
    const bool declined = first && s.cm_first_declined == s.profile;
    // The model's size on the block's sample, or on the whole block of at
    // most kCmSampleSteps, when made.
    std::size_t sample_cm = first ? s.cm_first_sample : 0;
    if (first && job.steps <= kCmSampleSteps) sample_cm = s.cm_first_size;
    LightSample light_sample;      // what light_cm_first() coded of the block's sample
    // A block of plain steps (random walks: plain_steps()) is coded by the
    // step model and zstd only (at the strong levels also mixed, after the
    // context-mixing step model's check on a sample, which also decides the
    // mixing), below kLightCmLevel by zstd only, as the fast levels' large
    // blocks are not coded by the step model: the cuts, the segment, table
    // and record blocks, the light step model and the CM raw block never
    // came 1/32 under them there, and were three quarters of -L 3's time and
    // two thirds of -L 1's (docs/benchmarks.md "Plain steps").
    // (below kLightCmLevel judged on the block's first kCmSampleSteps
    // steps: the whole block's counts cost a tenth of -L 1's time on contours)
    const bool plain = !s.timed && fits && job.steps <= kMaxBlockSteps &&
                       plain_steps(s.level >= kLightCmLevel ? block : first_steps(block, kCmSampleSteps));
    const bool cm_first = known_cm || (!declined && !plain && cm_step_model_first(block, job.steps, s, &sample_cm));
    if (cm_first || (!plain && light_cm_first(block, job.steps, s, light_sample))) {
        // A step-model block, coded by the context-mixing model (or the
        // light one) in the second pass (cm_pass(); no record until then),
        // or here when choose_frame_settings() made the model.
        job.cm = true;
        job.cm_light = !cm_first;
        job.type = kStepModel;
        job.order = 1;
        add_contribution(job);
        if (known_cm && s.cm_first_model) take_cm_first(job, *s.cm_first_model);
        return;
    }
    bool segment_model_only = false;
    std::string chain_payload;  // the thorough levels: zstd of the segments, tried after the models
    const bool can_represent = representable(block, s.profile, s.axes);
    // Timed frames: what the block's first ticks say (the first block's
    // made by choose_frame_settings() at the thorough levels).
    const bool timed_first = s.timed_first_steps != 0 && job.first_chain == 0 &&
                             block.chains.size() == s.timed_first_chains && job.steps == s.timed_first_steps;
    const TimedCheck timed = !s.timed || !can_represent ? TimedCheck{}
                             : timed_first              ? s.timed_first
                                                        : timed_check(block, s);
    // (with --no-raw, or bytes over the raw block's limit, a chain block is
    // the only choice, text or not)
    const bool text = !s.timed && s.allow_raw && job.bytes.size() <= kMaxBlockBytes && reads_as_text(block);
    if (can_represent && timed.segments && !text && !plain) {
        Cut segs;
        // Below the thorough levels, when the sample chose the default-phase
        // cut, it is the only cut made (the chains were checked by representable()).
        bool aligned = !s.thorough && s.aligned_cut && s.segmenter != SegmenterKind::patent &&
                       aligned_block_cut(block, s.profile, segs, s.cut_cache);
        const FirstBlockTrial* trial = s.thorough ? trial_of(job, s) : nullptr;
        if (trial) {
            segs = trial->segs;
            job.stats += trial->stats;
        } else if (!aligned) {
            const SegmenterKind kind =
                s.segmenter == SegmenterKind::optimal && !s.optimal_recut ? SegmenterKind::greedy : s.segmenter;
            if (auto r = segment_block(block, s.profile, kind, segs, job.stats, job.first_chain, s.source, s.cut_cache); !r) {
                job.error = std::move(r).error();
                return;
            }
        }
        const std::uint64_t nsegs = segment_count(segs);
        if (s.thorough) chain_payload = write_chain_payload(block, s.profile, segs);
        segment_model_only = !s.thorough && nsegs * 1000 < kSegmentModelOnly * job.steps;
        if (table_late_pays(job, s, segs, plain, light_sample)) {
            // (what the end of this function sets for a table block)
            job.table_late = true;
            job.type = kTable;
            job.cut = std::move(segs);
            add_contribution(job);
            return;
        }
        if (!s.thorough && !s.timed) {
            TableItemKeys keys;
            unsigned record_type = kTable;
            const std::string table = write_table_block(block, s.profile, segs, table_effort(s.level), nullptr,
                                                        nullptr, s.window_log != 0 ? &keys : nullptr, &record_type);
            if (table.size() <= kMaxBlockPayload &&
                consider(kTable, make_stored_record(record_type, job.flags, table))) {
                job.cut = segs;
                job.table_keys = std::move(keys);
            }
        }
        // Lines and arcs (--arc-method): the arc cut's table block, at every
        // level, kept when smaller than every other encoding tried.
        if (s.arc_method && !s.timed && block.axes == 2) {
            Cut arcs;
            if (auto r = arc_block_cut(block, s.profile, *s.arc_method, arcs, job.first_chain, s.source); !r) {
                job.error = std::move(r).error();
                return;
            }
            unsigned record_type = kTable;
            const std::string table =
                write_table_block(block, s.profile, arcs, table_effort(s.level), nullptr, nullptr, nullptr, &record_type);
            if (table.size() <= kMaxBlockPayload &&
                consider(kTable, make_stored_record(record_type, job.flags, table))) {
                job.cut = std::move(arcs);
                job.table_keys = {};
            }
        }
        // The fast levels code small blocks by the segment model too: its
        // adaptive contexts need no tables (a table block's fixed cost), and
        // a small block decodes fast whatever its type. Timed frames keep the
        // segment model, which predicts their phases (FORMAT.md 1.5.1).
        // Nor do the thorough levels code a two-axis block too dense for it
        // (random walks): there the step model wins by 20-25 %.
        // From kFastStepLevel a large block too, where its sample says the
        // segment model may pay; kept when smaller.
        const bool model_fits = block.axes != 2 || !too_dense(nsegs, job.steps);
        const bool large_model = model_fits && !s.thorough && !s.timed && s.level >= kFastStepLevel &&
                                 job.steps >= kSmallBlockSteps && type == kTable &&
                                 segment_model_may_pay(block, s.profile, segs, table_effort(s.level));
        if ((s.thorough || s.timed || job.steps < kSmallBlockSteps || large_model) && model_fits) {
            std::vector<Cut> cuts;
            std::size_t which = 0;
            std::string model;
            if (trial && !trial->cuts.empty()) {
                cuts = trial->cuts;
                which = trial->which;
                model = trial->model;
            } else {
                cuts = model_cuts(block, s, std::move(segs), aligned);
                model = smallest_segment_model(block, s.profile, cuts, which, s.timed);
            }
            std::string rec = model.size() <= kMaxBlockPayload ? make_stored_record(kSegmentModel, job.flags, model)
                                                               : std::string();
            if (consider(kSegmentModel, std::move(rec))) job.cut = cuts[which];
            if (s.timed) timed_choice(job, s, cuts, type, best);
        }
    } else if (!can_represent && s.profile_named && block.axes == s.axes) {
        for (std::size_t c = 0; c < block.chains.size(); ++c) {
            auto r = profile_accepts(s.profile, block.chains[c].steps, block.axes);
            if (!r) {
                job.error = make_error(r.error().code, s.source + ": chain " + std::to_string(job.first_chain + c + 1) +
                                                           ": profile " + std::string(profile_name(s.profile)) +
                                                           " cannot represent it: " + r.error().message);
                return;
            }
        }
    }
    // Timed frames at every level: the tick block (type 7 subtype 5: 2 with
    // the planner model's byte) or the interrupt block (subtype 6: 1 with
    // it), the one the check chose (the smaller
    // plain one; for the mixed codings, kMixedIrqMargin), kept when smaller
    // than the segment-based blocks; from kMixedTickLevel
    // with mixed predictions but for the sure decisions (coding 2), 13-23 %
    // smaller than the plain coding on every block of the timed streams
    // measured and about half as fast to decode (docs/benchmarks.md "Timed
    // streams at the default level"), the plain one where the mixed one
    // cannot code the block.
    if (s.timed && can_represent) {
        const TickCoding coding = s.level >= kMixedTickLevel ? TickCoding::mixed_sure : TickCoding::plain;
        // From the window's ticks where it holds some (the match's; the
        // window bit).
        const WindowView* w = job.window && has_ticks(*job.window) ? job.window : nullptr;
        auto write = [&](TickCoding c, bool irq) {
            const unsigned flags = kTickFlags | (w ? kTickWindow : 0u);
            return irq ? write_interrupt_block(block, c, flags, w) : write_tick_block(block, c, flags, w);
        };
        const bool use_irq = coding == TickCoding::plain ? timed.irq : timed.irq_mixed;
        std::string tick =
            coding == TickCoding::plain && !timed.plain.empty() && !w ? timed.plain : write(coding, use_irq);
        if (coding != TickCoding::plain && (tick.empty() || tick.size() > kMaxBlockPayload))
            tick = write(TickCoding::plain, timed.irq);
        // The thorough levels code the other one whole too, the smaller
        // kept: the check's first ticks chose the larger one for 3 of the 15
        // blocks of the eleven timed streams of docs/benchmarks.md (1.9-3.6
        // % larger; "Timed streams: both blocks at the thorough levels").
        if (s.thorough && !tick.empty()) {
            const std::string other = write(coding, !use_irq);
            if (!other.empty() && other.size() < tick.size()) tick = other;
        }
        if (!tick.empty() && tick.size() <= kMaxBlockPayload && consider(kTickBlock, tick_record(job.flags, tick)))
            job.cut.clear();
    }
    // The step model decodes a few times slower than a table block: below
    // kFastStepLevel only small blocks try it.
    if (fits && job.steps <= kMaxBlockSteps && !segment_model_only &&
        (s.level >= kFastStepLevel || job.steps < kSmallBlockSteps || (plain && s.level >= kLightCmLevel))) {
        int order = 0;
        const std::string model =
            write_step_model(block, s.thorough ? thorough_step_order(block) : kFastStepOrder, nullptr, &order);
        if (!model.empty() && model.size() <= kMaxBlockPayload &&
            consider(kStepModel, make_stored_record(kStepModel, job.flags, model)))
            job.order = order;
    }
    // From the strong level a segment-model or step-model block is written
    // mixed (mixed_pass) when that is 1/64 smaller: zstd's blocks must beat
    // that size, not the plain model's. The mixed coding (no window) is made
    // only when one of them beats the plain model.
    std::size_t mixed_size = 0;
    auto beats_model = [&](const std::string& rec) {
        if (s.level < kStrongLevel || s.timed || (type != kSegmentModel && type != kStepModel) || rec.empty() ||
            rec.size() >= best.size())
            return true;
        if (mixed_size == 0) {
            const std::string m = type == kSegmentModel ? write_segment_model(block, s.profile, job.cut, nullptr, false, true)
                                  : mixed_pays(job) ? write_mixed_step_model(block, 1)
                                                                 : std::string();
            const std::size_t size = m.empty() ? SIZE_MAX : make_stored_record(kMixedModel, job.flags, m).size();
            mixed_size = size * 64 <= best.size() * 63 ? size : SIZE_MAX;
        }
        return rec.size() < mixed_size;
    };
    // The context-mixing step model, where it may win, is coded in the
    // second pass: zstd, which does not come near it there, is not tried.
    job.cm = cm_step_model_may_win(job, s, type, best, sample_cm);
    job.cm_light = !job.cm && !plain && light_cm_may_win(job, s, type, best, light_sample);
    job.cm = job.cm || job.cm_light;
    if (!job.cm && !chain_payload.empty() && chain_payload.size() <= kMaxBlockPayload &&
        zstd_may_win(chain_payload, best, true)) {
        std::string rec = make_block_record(kChains, job.flags, chain_payload, s.level);
        if (beats_model(rec)) consider(kChains, std::move(rec));
    }
    const bool chain_kind = !best.empty();
    if (job.bytes.size() > kMaxBlockBytes && !chain_kind) {
        job.error = make_error(Errc::limit, s.source + ": a block of " + std::to_string(job.bytes.size()) +
                                                " bytes exceeds the raw block limit");
        return;
    }
    // Below the thorough levels zstd of the bytes is tried only when the
    // chain block is weak (less than 5:1): a general-purpose compressor does
    // not come near a modeled block that reaches it (docs/benchmarks.md).
    const bool raw_can_win = s.thorough || !chain_kind || best.size() * 5 > job.bytes.size();
    if (job.bytes.size() <= kMaxBlockBytes && (!chain_kind || s.allow_raw) && raw_can_win && !job.cm) {
        std::string raw;
        put_varint(raw, block.chains.size());
        put_varint(raw, job.steps);
        raw += job.bytes;
        // From kRawCmLevel the same bytes coded by the CM raw block (type 7
        // subtype 3), about half zstd's size on text-like input, written
        // when smaller than zstd's, and at least 1/32 smaller than a chain
        // block (which decodes faster and gives the window its steps; on the
        // random walks of corpora/ it is 1 % smaller), coded whole only
        // where a sample of it says it may be (raw_cm_may_win(); against
        // zstd's block too: on random walks it came 0.6 % under it at a
        // third of the speed); the job stays a raw block.
        bool zstd_won = false, cm_won = false;
        auto zstd_at_level = [&] {
            std::string rec = make_block_record(kRaw, job.flags, raw, s.level);
            zstd_won = beats_model(rec) && consider(kRaw, std::move(rec));
        };
        auto cm_raw = [&](std::size_t against) {
            if (plain || s.level < kRawCmLevel || !raw_cm_may_win(raw, against)) return;
            const std::string cm = write_raw_cm_block(raw);
            std::string cm_rec = !cm.empty() && cm.size() <= kMaxBlockPayload
                                     ? make_stored_record(kExtended, job.flags, cm)
                                     : std::string();
            const bool margin = type == kRaw || best.empty() || cm_rec.size() + cm_rec.size() / kRawCmMargin < best.size();
            cm_won = !cm_rec.empty() && margin && beats_model(cm_rec) && consider(kRaw, std::move(cm_rec));
        };
        if (!s.thorough) {
            zstd_at_level();
            cm_raw(best.size());
        } else if (best.empty()) {
            // No chain block (text read as steps): the CM raw block first,
            // coded whole (no sample: there is no faster block it must beat),
            // then zstd at the level only where zstd's probe says it may come
            // under it (on text the CM raw block is a third of the probe, and
            // zstd at level 19 was a third of -L 19's time there).
            cm_raw(0);
            if (zstd_may_win(raw, best)) zstd_at_level();
        } else if (zstd_may_win(raw, best)) {
            zstd_at_level();
            cm_raw(best.size());
        }
        if (zstd_won || cm_won) job.raw_payload = std::move(raw);
    }
    if (best.empty()) {
        job.error = make_error(Errc::io, s.source + ": zstd compression failed");
        return;
    }
    job.type = type;
    job.record = std::move(best);
    if (type != kSegmentModel && type != kTable && type != kExtended) job.cut.clear();
    if (type != kTable) job.table_keys = {};
    if (type == kRaw) job.stats = {};
    add_contribution(job);
}

namespace {
bool has_symbols(const WindowView& window) {
    for (const auto& b : window)
        if (!b->symbols.empty()) return true;
    return false;
}
}  // namespace

bool wants_window_steps(const BlockJob& job, const EncoderSettings& s, const WindowView& window) {
    if (job.cm) return !window.empty();
    if (job.type == kRaw || job.block.axes != 2 || job.steps > kMaxBlockSteps || window.empty()) return false;
    // A table block tries the step model from the window where its first
    // pass tried the step model: at kFastStepLevel and above, dense blocks.
    if (job.type == kTable) {
        if (s.level < kFastStepLevel || segment_count(job.cut) * 1000 < kSegmentModelOnly * job.steps) return false;
    }
    // Below the thorough levels a segment-model block whose window holds
    // segment-model blocks only (as the first pass chose) stays one: the
    // segment model sees the window's content too.
    return s.thorough || job.type != kSegmentModel ||
           !std::all_of(window.begin(), window.end(), [](const auto& b) { return b->first_type == kSegmentModel; });
}

// The context-mixing step model of a block the first pass chose it for
// (job.cm), from the window when it holds steps; kept when smaller than the
// first pass's record. The block is then a step-model block (no segment
// items in the window).
void cm_pass(BlockJob& job, const WindowView& window) {
    const bool w = !window.empty() && has_symbols(window);
    const std::string model = job.cm_light && !w && !job.light_model.empty() ? std::move(job.light_model)
                              : job.cm_light ? write_light_cm_step_model(job.block, w ? &window : nullptr)
                                             : write_cm_step_model(job.block, w ? &window : nullptr);
    job.light_model = {};
    if (job.record.empty() && (model.empty() || model.size() > kMaxBlockPayload)) {
        // (the first pass left the block to this model: the step model at
        // order 1 takes it instead)
        const std::string plain = write_step_model(job.block, 1);
        if (plain.empty() || plain.size() > kMaxBlockPayload) {
            job.error = make_error(Errc::limit, "block of chain " + std::to_string(job.first_chain + 1) +
                                                    ": the step model cannot code it");
            return;
        }
        job.record = make_stored_record(kStepModel, job.flags, plain);
    }
    if (model.empty() || model.size() > kMaxBlockPayload) {
        job.cm = false;
        return;
    }
    std::string rec = make_stored_record(kMixedModel, job.flags | (w ? kFlagWindow : 0u), model);
    if (!job.record.empty() && rec.size() >= job.record.size()) {
        job.cm = false;
        return;
    }
    job.record = std::move(rec);
    job.type = kStepModel;
    job.cut.clear();
    job.raw_payload.clear();
    job.table_keys = {};
}

void window_step_pass(BlockJob& job, const EncoderSettings& s, const WindowView& window) {
    if (job.cm) {
        if (job.cm_coded) return;
        cm_pass(job, window);
        if (job.cm || job.error.code != Errc::ok) return;
    }
    if (!wants_window_steps(job, s, window) || !has_symbols(window)) return;
    int order = job.type == kStepModel ? job.order : s.thorough ? thorough_step_order(job.block) : kFastStepOrder;
    const std::string model = write_step_model(job.block, order, &window, &order);
    if (model.empty() || model.size() > kMaxBlockPayload) return;
    std::string rec = make_stored_record(kStepModel, job.flags | kFlagWindow, model);
    if (rec.size() >= job.record.size()) return;
    job.record = std::move(rec);
    job.type = kStepModel;
    job.order = order;
    job.cut.clear();
}

void note_items(BlockJob& job) {
    if (job.contribution && (job.type == kSegmentModel || job.type == kTable || job.type == kExtended))
        job.contribution->items = segment_items(job.block, job.cut);
}


bool mixed_step_model_pays(const Block& block) {
    if (step_count(block) <= 2 * kMixSampleSteps) return true;  // the sample would be most of the block
    const Block sample = first_steps(block, kMixSampleSteps);
    const std::size_t plain = write_step_model(sample, 1).size();
    const std::size_t mixed = write_mixed_step_model(sample, 1).size();
    return mixed * kMixSampleGain <= plain * (kMixSampleGain - 1);
}

namespace {

// The strong levels: the block's model (as chosen, with the window when the
// record uses it) coded again with mixed predictions (block type 6), kept
// when at least 1/64 smaller: a mixed block decodes several times slower,
// and on data the mixer cannot predict (random walks: about 1% smaller) it
// is not worth that. The block's type (job.type) stays the model's.
void mixed_pass(BlockJob& job, const EncoderSettings& s, const WindowView& window) {
    if (job.cm || s.level < kStrongLevel || (job.type != kSegmentModel && job.type != kStepModel && job.type != kExtended))
        return;
    const unsigned flags = view_record(job.record).flags;
    const WindowView* w = (flags & kFlagWindow) ? &window : nullptr;
    const std::size_t plain = job.record.size();
    auto keep = [&](const std::string& model, unsigned type = kMixedModel) {
        if (model.empty() || model.size() > kMaxBlockPayload) return;
        std::string rec = make_stored_record(type, flags, model);
        if (rec.size() * 64 <= plain * 63 && rec.size() < job.record.size()) job.record = std::move(rec);
    };
    if (job.type == kSegmentModel) {
        keep(write_segment_model(job.block, s.profile, job.cut, w, s.timed, true));
        return;
    }
    if (job.type == kExtended) {  // the cut's phases are aligned for it already
        Cut cut = job.cut;
        keep(write_timed_block(job.block, s.profile, cut, w, true), kExtended);
        return;
    }
    // The hashed models see the long contexts: a short primary order wins
    // (measured on corpora/glyphs/liberation-*.fc: order 1 < 2 < 3 < 4;
    // order 2 as well won nowhere in corpora/).
    if (!mixed_pays(job)) return;
    keep(write_mixed_step_model(job.block, 1, w));
}

}  // namespace

namespace {

// The block's segment items coded again from the window (table or segment
// model, as chosen), kept when smaller; a table block coded late
// (job.table_late) is coded here only, with the window when it holds
// items, else without.
void window_items_pass(BlockJob& job, const EncoderSettings& s, const WindowView& window) {
    if (job.type == kTable) {
        const bool w = std::any_of(window.begin(), window.end(), [](const auto& b) { return !b->items.starts.empty(); });
        if (!w && !job.table_late) return;
        // (the contribution's keys: window_segment_pass() kept them)
        const TableItemKeys* own =
            job.contribution ? &window_keys(*job.contribution, s.profile, job.block.axes) : nullptr;
        unsigned record_type = kTable;
        const std::string table = write_table_block(job.block, s.profile, job.cut, table_effort(s.level),
                                                    w ? &window : nullptr, own, nullptr, &record_type);
        if (table.size() > kMaxBlockPayload) {
            if (job.table_late)
                job.error = make_error(Errc::limit, s.source + ": chain " + std::to_string(job.first_chain + 1) +
                                                        ": its block's table block exceeds the payload limit");
            return;
        }
        std::string rec = make_stored_record(record_type, job.flags | (w ? kFlagWindow : 0u), table);
        if (job.record.empty() || rec.size() < job.record.size()) job.record = std::move(rec);
        return;
    }
    if (job.type == kTickBlock) {
        // The first pass read the ticks of every block in the window; a
        // block that became a raw one has none (end_contribution()): coded
        // again from the window as it is.
        const RecordView rec = view_record(job.record);
        if (rec.payload.size() < 2 || !(static_cast<unsigned char>(rec.payload[1]) & kTickWindow) ||
            std::none_of(window.begin(), window.end(), [](const auto& b) { return b->ticks_dropped; }))
            return;
        const unsigned sub = static_cast<unsigned char>(rec.payload[0]);
        const unsigned coding = static_cast<unsigned char>(rec.payload[1]);
        const auto c = static_cast<TickCoding>(coding & ~kTickAllFlags);
        const unsigned flags = coding | tick_model_flags(rec.payload);
        const std::string tick = is_interrupt_subtype(sub) ? write_interrupt_block(job.block, c, flags, &window)
                                                           : write_tick_block(job.block, c, flags, &window);
        if (tick.empty() || tick.size() > kMaxBlockPayload) {
            job.error = make_error(Errc::limit, s.source + ": chain " + std::to_string(job.first_chain + 1) +
                                                    ": its block's tick block exceeds the payload limit");
            return;
        }
        job.record = tick_record(job.flags, tick);
        return;
    }
    if (job.type == kExtended) {
        Cut cut = job.cut;
        const std::string timed = write_timed_block(job.block, s.profile, cut, &window);
        if (timed.empty() || timed.size() > kMaxBlockPayload) return;
        std::string rec = make_stored_record(kExtended, job.flags | kFlagWindow, timed);
        if (rec.size() < job.record.size()) job.record = std::move(rec);
        return;
    }
    if (job.type != kSegmentModel) return;
    const std::string model = write_segment_model(job.block, s.profile, job.cut, &window, s.timed);
    if (model.empty() || model.size() > kMaxBlockPayload) return;
    std::string rec = make_stored_record(kSegmentModel, job.flags | kFlagWindow, model);
    if (rec.size() < job.record.size()) job.record = std::move(rec);
}

}  // namespace

void window_segment_pass(BlockJob& job, const EncoderSettings& s, const WindowView& window) {
    if (job.error.code != Errc::ok) return;
    // A table block's contribution holds its cut's items (note_items): their
    // keys, from the first pass, are kept with it for the later blocks.
    if (job.type == kTable && job.contribution)
        window_keys(*job.contribution, s.profile, job.block.axes, &job.table_keys);
    if (!window.empty() || job.table_late) window_items_pass(job, s, window);
    mixed_pass(job, s, window);
}

}  // namespace stepzip::stz
