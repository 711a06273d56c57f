// The .stz encoder's parts (docs/FORMAT.md section 4): the frame writer
// (compress.cpp: read -> batch -> parallel jobs -> ordered write -> trailer)
// runs, for every block, the block strategy (block_strategy.cpp: which
// encodings a level tries, and with the window) and the round-trip proof
// (round_trip.cpp). Internal to src/container.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "block_codec.hpp"
#include "stepzip/interpolate/arc.hpp"
#include "table_block.hpp"
#include "window.hpp"

namespace stepzip::stz {

/// Encoder effort: from this level on, every block is encoded every way;
/// below it the choices are made cheaply (docs/FORMAT.md section 4).
inline constexpr int kThoroughLevel = 10;
/// The strong tier: from this level on, a modeled block is also coded with
/// mixed predictions (block type 6) and kept when smaller.
inline constexpr int kStrongLevel = 10;

/// Above twice this many steps, a block's mixed step model is tried only
/// when mixing pays on a sample of this many (mixed_step_model_pays()).
inline constexpr std::uint64_t kMixSampleSteps = 1u << 15;

/// Whether the strong levels code `block` (two axes) with the mixed step
/// model: always up to 2 * kMixSampleSteps steps; above, when its first
/// kMixSampleSteps steps are at least 1/32 smaller mixed than plain (order 1).
bool mixed_step_model_pays(const Block& block);

/// The thorough levels' profile ranking, when it coded the whole first
/// block: the winning profile's cuts and segment model, which the first
/// block's own choice takes instead of making them again.
struct FirstBlockTrial;

class CutCache;

/// Timed frames: what the plain codings of a block's first ticks say
/// (timed_check() in block_strategy.cpp): whether the segment-based codings
/// may win against the tick and interrupt blocks, and which of those two
/// is the smaller.
struct TimedCheck {
    bool segments = true;
    bool irq = false;        ///< the interrupt block for the plain coding (the smaller one plain)
    bool irq_mixed = false;  ///< the interrupt block for the mixed codings (kMixedIrqMargin)
    std::string plain;  ///< the smaller plain payload, when the check coded the whole block
};

/// What the frame writer fixed for every block of a frame.
struct EncoderSettings {
    Profile profile = Profile::eval8;
    bool profile_named = false;
    bool segmenter_named = false;  ///< --segmenter given (else implied by the level and the axes)
    SegmenterKind segmenter = SegmenterKind::greedy;
    int level = 3;
    int axes = 2;
    std::string source;
    bool allow_raw = true;
    bool thorough = false;     ///< try every encoding on every block
    bool aligned_cut = false;  ///< below thorough: the default-phase cut won on the first block's sample
    int window_log = 0;        ///< the frame's window (0: none)
    bool timed = false;        ///< input format timed: segment-model phases predicted
    std::optional<ArcMethod> arc_method;  ///< also try table blocks of lines and arcs drawn by it
    std::shared_ptr<const FirstBlockTrial> first_trial;  ///< set by choose_frame_settings() (thorough levels)
    /// The optimal segmenter at the thorough levels: false when its cut made
    /// no smaller segment model than the greedy cut on the first block's
    /// trial; the blocks are then cut greedily (set by choose_frame_settings()).
    bool optimal_recut = true;
    /// The frame's chain cuts, shared by its jobs (null: every chain is cut).
    CutCache* cut_cache = nullptr;
    /// The strong levels, what choose_frame_settings() found out about the
    /// first block (its chains and steps; 0 chains: nothing): `cm_first`,
    /// it is the context-mixing step model's; `cm_first_model`, on a first
    /// block of at most 2^17 steps, that model's payload (no window: the
    /// first block's), which choose_block() takes as the block's record;
    /// `cm_first_declined`, the check for that model (cm_step_model_first())
    /// said no under that profile, the model's size on the block's sample
    /// being `cm_first_sample` (0: not made); `cm_first_size`, the model's
    /// size on the whole block (0: not made).
    std::uint64_t cm_first_chains = 0, cm_first_steps = 0;
    bool cm_first = false;
    std::shared_ptr<const std::string> cm_first_model;
    std::optional<Profile> cm_first_declined;
    std::size_t cm_first_sample = 0;
    std::size_t cm_first_size = 0;
    /// Timed frames at the thorough levels: the first block's TimedCheck,
    /// made by choose_frame_settings() (`timed_first_steps` 0: not made).
    std::uint64_t timed_first_chains = 0, timed_first_steps = 0;
    TimedCheck timed_first;
};

/// One block in flight, from the reader to the ordered write.
struct BlockJob {
    Block block;
    std::string bytes;              ///< the block's input bytes (proved equal to the input)
    std::uint64_t first_chain = 0;  ///< index of the block's first chain in the input
    std::uint64_t steps = 0;        ///< steps of the block

    // The block strategy's choice.
    unsigned type = kRaw;
    unsigned flags = 0;      ///< kFlagContinues / kFlagOpen (kFlagWindow: set in `record`)
    std::string record;      ///< the block record written
    std::string raw_payload; ///< a raw block's payload before zstd
    std::vector<std::vector<Segment>> cut;  ///< segment-model block: the cut coded
    int order = 0;                          ///< step-model block: the context order
    bool cm = false;  ///< the strong levels: coded by the context-mixing step model in the second pass
    bool cm_light = false;  ///< with cm: the light model (the fast levels)
    bool cm_coded = false;  ///< with cm: `record` is the model's already (the frame's first block)
    /// Step-model block: whether its mixed coding is tried (1) or not (0),
    /// when the first pass decided it on its sample; -1: mixed_step_model_pays().
    int mixed_pays = -1;
    std::string light_model;  ///< the light model's payload of the whole block without the window, when made
    std::shared_ptr<WindowBlock> contribution;  ///< what the block adds to the window
    /// The blocks before it in the window (compress.cpp; the first pass
    /// reads their ticks only), or null.
    const WindowView* window = nullptr;
    TableItemKeys table_keys;  ///< table block: `cut`'s item keys from the first pass (for `contribution`)
    /// Table block coded once, by the third pass (from the window when it
    /// holds items): `record` is empty until then.
    bool table_late = false;

    // The round-trip proof.
    Block decoded;  ///< the block as the decoder sees it (chain blocks)
    BlockCounts counts;
    SegmentStats stats;
    Error error;
};

/// Block strategy, frame level: under --profile auto the profile, and below
/// the thorough levels the segment-model cut, chosen on the first block.
Result<void> choose_frame_settings(const Block& first, EncoderSettings& s);

/// The table-block encoder effort of a fast level (below kThoroughLevel).
TableEffort table_effort(int level);

/// The window a level declares (log2 of steps + chains).
int window_log_for_level(int level);

/// Whether `block` reads as text rather than as a machine's steps: more
/// than two axes whose moves (at least 4096) reverse direction more than
/// once in eight. The encoder codes such a block raw (zstd, the CM raw
/// block) without trying the chain encodings, unless raw blocks are not
/// allowed (block_strategy.cpp says why).
bool reads_as_text(const Block& block);
/// Whether a two-axis block of at least 2^14 steps is "plain": its steps'
/// order-2 entropy is at least 9/10 of their order-0 entropy (random walks),
/// which the fast levels code by the step model and zstd only.
bool plain_steps(const Block& block);

/// Whether the CM raw block coding the raw block content `raw` whole may
/// come out under a block of `best` bytes (0: none; 1/32 under a chain
/// block): true for `raw` of at most 64 KiB; else whether its model codes
/// eight stretches spread over `raw` (an eighth of it, at least 32 KiB)
/// under 1.3 times `best` scaled to their share where it learns (their
/// second half 1/32 cheaper per byte than their first), under 31/32 of it
/// where it does not (block_strategy.cpp says why).
bool raw_cm_may_win(std::string_view raw, std::size_t best);

/// Block strategy, first pass (parallel, without the window): the encodings
/// the level tries, the smallest kept; sets the job's type, record, cut or
/// order, and the part of its contribution to the window that depends only
/// on whether it is a chain block: weight, Freeman symbols, chain starts.
void choose_block(BlockJob& job, const EncoderSettings& s);

/// Before the first pass, with a window: what the block adds to it whatever
/// its type (its weight; a timed frame's, its ticks).
void begin_contribution(BlockJob& job, const EncoderSettings& s);
/// After the first pass: a block that became a raw one adds no ticks (its
/// contribution's ticks_dropped is set).
void end_contribution(BlockJob& job);

/// Whether window_step_pass() may code `job` by the step model from
/// `window` (then the window's blocks need their symbols: add_steps()).
/// A function of the first pass's choices.
bool wants_window_steps(const BlockJob& job, const EncoderSettings& s, const WindowView& window);

/// Second pass (parallel): a chain block on two axes coded by the step
/// model from `window` (whose symbols are made before this pass when
/// wants_window_steps()), kept when smaller. Decides the final block type.
void window_step_pass(BlockJob& job, const EncoderSettings& s, const WindowView& window);

/// The segment items a segment-model block adds to the window, once its
/// type is final.
void note_items(BlockJob& job);

/// Third pass (parallel): a segment-model or table block coded again from `window`
/// (whose items are fixed once every earlier block passed the second pass),
/// kept when smaller; at the strong levels, then the block's model with
/// mixed predictions (block type 6), kept when smaller.
void window_segment_pass(BlockJob& job, const EncoderSettings& s, const WindowView& window);

/// Round-trip proof (parallel): decodes the job's record exactly as the
/// decoder does (with `window` when flagged) and compares the chains and
/// layout with the input block's, whose rendering was compared with the
/// input bytes when it was parsed (a renderer reads the block alone, so
/// the decoded block renders to the same bytes). Sets job.error
/// (Errc::mismatch) on failure.
void prove_decoded(BlockJob& job, const EncoderSettings& s, const WindowView& window);

}  // namespace stepzip::stz
