// The tick block (docs/FORMAT.md "Tick block"): block type 7, subtype 2. A
// timed frame's chains coded tick by tick instead of segment by segment:
// on each tick, whether each axis steps and, when it does, whether it
// reverses, each one adaptive binary decision whose context is chiefly what
// the axis's digital straight segment in (time, axis) -- a constant step
// rate -- ending at the tick admits next. Internal to src/container.
#pragma once

#include <string>
#include <string_view>

#include "block_codec.hpp"
#include "window.hpp"

namespace stepzip::stz {

/// Subtype 2 of block type 7: the tick block.
inline constexpr unsigned kTickSubtype = 2;
/// Subtype 1 of block type 7: the interrupt block, a tick block whose
/// followers B[a] read per step of the leader whether the axis stepped since
/// the leader's previous step (a controller's Bresenham line over its
/// stepper interrupts, whatever its step smoothing level).
inline constexpr unsigned kInterruptSubtype = 1;
/// Subtypes 5 and 6 of block type 7: the tick block and the interrupt block
/// with a model byte after the coding byte, whose value 1 names the planner
/// model (docs/FORMAT.md 1.16; kTickPlanner), and 2 on an interrupt block
/// with a mixed coding the planner model with slot lines (1.17; kTickSlots).
inline constexpr unsigned kTickPlannerSubtype = 5;
inline constexpr unsigned kInterruptPlannerSubtype = 6;
/// Whether block type 7 subtype `s` is a tick or interrupt block, and an
/// interrupt block.
constexpr bool is_tick_subtype(unsigned s) {
    return s == kTickSubtype || s == kInterruptSubtype || s == kTickPlannerSubtype || s == kInterruptPlannerSubtype;
}
constexpr bool is_interrupt_subtype(unsigned s) { return s == kInterruptSubtype || s == kInterruptPlannerSubtype; }
/// Whether block type 7 subtype `s` is a tick or interrupt block with a model byte.
constexpr bool has_model_byte(unsigned s) { return s == kTickPlannerSubtype || s == kInterruptPlannerSubtype; }
/// The encoder's name for a block written as a tick block (its record is of
/// block type 7): not a block type of the format.
inline constexpr unsigned kTickBlock = 8;

/// The codings of a tick or interrupt block (payload byte 1): every bit in
/// its adaptive context; every bit with mixed predictions; with mixed
/// predictions but for the bits whose context is sure (mix_sure(), the
/// strong levels' choice).
enum class TickCoding : unsigned { plain = 0, mixed = 1, mixed_sure = 2 };
/// Flag of the coding byte, added to a TickCoding: a follower's line that
/// breaks restarts at its last 1 (docs/FORMAT.md 1.13, "Rebuild"). The
/// encoder sets it on every block; the blocks without it decode as before.
inline constexpr unsigned kTickRestart = 4;

/// Flag of the coding byte, with a mixed coding only: each axis's line
/// guesses its rate after a break from the rates of the two lines before,
/// and mixed contexts take the letter that rate gives next
/// (docs/FORMAT.md 1.13, "Guess"). The blocks without it decode as before.
inline constexpr unsigned kTickGuess = 8;
/// Flag of the coding byte, with a mixed coding only: each step decision's
/// guessed letter, admitted sets and rate trend choose the mixers' weight
/// sets and a second probability map's row, and the block's mixers and
/// maps learn faster (docs/FORMAT.md 1.13, "Guided mixing"). The blocks
/// without it decode as before.
inline constexpr unsigned kTickGuided = 16;
/// Flag of the coding byte, with a mixed coding only: a match model finds
/// the block's earlier ticks that the last few step events repeat and
/// predicts each tick by the one that followed them there; a ninth hashed
/// model, the guided mixer's weight set when the match is long, and with
/// coding 2 a sure decision that the match contradicts goes to the mixer
/// (docs/FORMAT.md 1.13, "Match"). The blocks without it decode as before.
inline constexpr unsigned kTickMatch = 32;
/// Flag of the coding byte, with the plain coding only: the match of
/// kTickMatch, whose state refines each step decision's context once the
/// match is long: the decision is coded in an adaptive context of that
/// state and of the context's probability, and both adapt
/// (docs/FORMAT.md 1.13, "Match"). The blocks without it decode as before.
inline constexpr unsigned kTickRefine = 128;
/// Not a bit of the coding byte: the block is written as subtype 5 or 6
/// with model byte 1, the planner model (docs/FORMAT.md 1.16): the leader
/// is the axis of the shortest mean of its last four intervals; with a
/// mixed coding, each axis's line keeps a segment clock and the line the
/// next stepper segment would start, which give contexts, a direct input
/// to the mixers and, with coding 2, a map for the sure decisions. The
/// encoder sets it on every block.
inline constexpr unsigned kTickPlanner = 256;
/// Not a bit of the coding byte: with kTickPlanner, an interrupt block
/// with a mixed coding is written with model byte 2, the planner model
/// with slot lines (docs/FORMAT.md 1.17): each axis that follows the
/// leader is read on the grid of interrupts that 2, 4 and 8 slots per
/// leader interval make, where its Bresenham line is exact, and the line
/// of each grid gives a context and the mixers' direct input. The encoder
/// sets it on every block; a tick block or the plain coding drops it.
inline constexpr unsigned kTickSlots = 512;
/// The coding byte's flags the encoder sets on every block (those that go
/// with its coding and subtype: tick_flags()), kTickPlanner and kTickSlots.
inline constexpr unsigned kTickFlags =
    kTickRestart | kTickGuess | kTickGuided | kTickMatch | kTickRefine | kTickPlanner | kTickSlots;
/// Flag of the coding byte, with the match or refine flag only: the match
/// starts from the ticks of the window's blocks, as if they had been coded
/// before the block's first tick; the block is flagged `window`
/// (docs/FORMAT.md 1.13, "Match", and 1.8 "Ticks"). The encoder sets it
/// where the window holds ticks.
inline constexpr unsigned kTickWindow = 64;
/// Every flag: the coding byte's bits above the coding, kTickPlanner and kTickSlots.
inline constexpr unsigned kTickAllFlags = kTickFlags | kTickWindow;
/// The flags that may go with `coding`: the guess, guided and match flags
/// and the slot lines with a mixed one, the refine flag with the plain
/// one, the window flag (with the match or refine flag only) and the
/// planner with either.
inline constexpr unsigned tick_flags(TickCoding coding) {
    return coding == TickCoding::plain
               ? kTickRestart | kTickRefine | kTickWindow | kTickPlanner
               : kTickRestart | kTickGuess | kTickGuided | kTickMatch | kTickWindow | kTickPlanner | kTickSlots;
}
/// The flags of a tick or interrupt block's payload that its bytes 0-2
/// name outside the coding byte: kTickPlanner (subtypes 5 and 6), with
/// kTickSlots (model byte 2). Only for a payload read_tick_block() accepts.
unsigned tick_model_flags(std::string_view payload);
/// Whether the window holds ticks (tick_masks()) for the window flag.
bool has_ticks(const WindowView& window);

/// Payload of a tick block for `block` (subtype and coding bytes first);
/// empty when the block cannot be one: a step that does not advance time
/// (axis 0) by exactly one, or more than kMaxAxes - 1 axes besides time.
/// `flags`: of kTickFlags and kTickWindow, those that do not go with
/// `coding` dropped (tick_flags()), and the window flag without the match
/// or refine flag or without ticks in `window`.
std::string write_tick_block(const Block& block, TickCoding coding = TickCoding::plain, unsigned flags = kTickFlags,
                             const WindowView* window = nullptr);

/// Payload of an interrupt block for `block` (subtype 1, docs/FORMAT.md
/// 1.14); empty when it cannot be one (as write_tick_block).
std::string write_interrupt_block(const Block& block, TickCoding coding = TickCoding::plain, unsigned flags = kTickFlags,
                                  const WindowView* window = nullptr);

/// Parses a tick-block or interrupt-block payload into `out` (when `expand`) and adds its
/// counts to `counts` (no segments); `window`: the block's window when it
/// is flagged `window`, else null. Errors: Errc::corrupt and Errc::limit
/// naming the payload byte after `where`.
Result<void> read_tick_block(std::string_view payload, int axes, bool expand, Block& out, BlockCounts& counts,
                             const std::string& where, const WindowView* window = nullptr);

}  // namespace stepzip::stz
