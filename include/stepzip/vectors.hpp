// stepzip — vector exchange (SPEC §5): G-code and HP-GL in both directions,
// SVG and JSON out.
//
// The vector model is deliberately small: a drawing is a list of pen-down
// paths; each path has a start point and a sequence of moves, a straight line
// or a circular arc to an end point. Every coordinate is an integer number of
// steps (after the step size, if any, has been applied by the reader).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "stepzip/chain.hpp"
#include "stepzip/document.hpp"
#include "stepzip/error.hpp"
#include "stepzip/interpolate/arc.hpp"
#include "stepzip/interpolate/feedrate.hpp"
#include "stepzip/profile.hpp"
#include "stepzip/segment.hpp"
#include "stepzip/segment/arc.hpp"
#include "stepzip/segmenter.hpp"

namespace stepzip {

/// Largest |coordinate|, in steps, a reader accepts (2^30; the same bound as
/// kMaxSegmentTotal, so the totals of a line between two accepted points are
/// at most 2^31 and interpolators check their own tighter limits).
inline constexpr std::int64_t kMaxVectorCoord = std::int64_t{1} << 30;

/// What a move draws.
enum class MoveKind : std::uint8_t {
    line,     ///< straight line to (x, y)
    arc_cw,   ///< clockwise arc about (cx, cy) to (x, y) (G2)
    arc_ccw,  ///< counter-clockwise arc about (cx, cy) to (x, y) (G3)
};

/// One pen-down move. Coordinates are absolute, in steps.
struct VectorMove {
    MoveKind kind = MoveKind::line;
    std::int64_t x = 0, y = 0;    ///< end point
    std::int64_t cx = 0, cy = 0;  ///< arc centre (arcs only; 0 for lines)
    std::uint32_t line = 0;       ///< 1-based source line of the move (0: not from a file)
    std::uint32_t column = 0;     ///< 1-based source column of the move's first word
    /// Feed for the G-code writer: an F word in units per minute (steps, or
    /// millimetres with a step size); 0 writes none. Readers leave it 0 and
    /// comparisons ignore it.
    double feed = 0;
    friend bool operator==(const VectorMove& a, const VectorMove& b) {
        return a.kind == b.kind && a.x == b.x && a.y == b.y && a.cx == b.cx && a.cy == b.cy;
    }
};

/// One pen-down path: where the pen goes down, then its moves (at least one).
struct VectorPath {
    std::int64_t x0 = 0, y0 = 0;
    std::vector<VectorMove> moves;
    int pen = 1;  ///< HP-GL pen (SP); 1 for G-code
    friend bool operator==(const VectorPath&, const VectorPath&) = default;
};

using Drawing = std::vector<VectorPath>;

/// A step size: millimetres per step, held exactly as an integer number of
/// 10^-12 mm (a decimal with up to 12 fraction digits).
struct StepSize {
    std::int64_t mm_e12 = 0;
};

/// Parses a step size such as "0.0125". Errors: Errc::invalid_argument
/// (not a decimal number, not positive, more than 12 fraction digits, larger
/// than 10^6 mm).
Result<StepSize> parse_step_size(std::string_view text);

/// Vector input formats.
enum class VectorFormat : std::uint8_t { gcode, hpgl, svg };

/// "gcode", "hpgl" or "svg". Thread-safe.
std::string_view vector_format_name(VectorFormat f) noexcept;
/// The format with that name, or nullopt. Thread-safe.
std::optional<VectorFormat> parse_vector_format(std::string_view name) noexcept;

/// Guesses G-code or HP-GL from the first bytes of a file: HP-GL when the
/// text starts with ESC (a device-control or PCL escape) or with two
/// letters (a mnemonic; no G-code word has two) followed by a parameter, a
/// separator or another mnemonic; G-code when the
/// first word is a letter and a number (G0, N10, M3 ...) or the text starts
/// with a comment or '%'; SVG when the text (after a byte-order mark and
/// white space) starts with '<' and holds an "<svg" tag (looks_like_svg()).
/// nullopt when none fits. Thread-safe.
std::optional<VectorFormat> detect_vector_format(std::string_view head) noexcept;

/// Options of the readers.
struct VectorReadOptions {
    std::string source = "<input>";   ///< names the input in error messages
    std::optional<StepSize> step_size;  ///< absent: coordinates are steps
    /// SVG: largest distance, in steps, of a flattened curve's chords from
    /// the curve (before vertices are rounded to whole steps); > 0.
    double tolerance = 0.5;
};

/// True when `head` starts (after a UTF-8 byte-order mark and white space)
/// with '<' and holds an "<svg" start tag. Thread-safe.
bool looks_like_svg(std::string_view head) noexcept;

/// Reads G-code. Accepted (case-insensitive, spaces allowed between a letter
/// and its number):
///  - G0 (rapid: pen up, the next drawing move starts a new path), G1 (line),
///    G2 / G3 (clockwise / counter-clockwise arc with centre offsets I, J
///    relative to the arc's start), modal: a line with only X/Y/I/J repeats
///    the last of G0-G3; X or Y may be omitted (the axis stays);
///  - G90 / G91 absolute / relative X Y; G20 / G21 inches / millimetres
///    (matter only with a step size; default millimetres); G17 (XY plane),
///    G94 (feed per minute), G4 P.. (dwell) accepted and ignored;
///  - T n (a whole number): the pen of the paths that follow (VectorPath::pen;
///    a new path starts where it changes);
///  - F (feed), S (spindle/laser power), M (machine functions: M3 /
///    M5 pen or spindle control, M2 / M30 end ...) and N (line numbers) are
///    accepted and ignored: only G0 moves break paths;
///  - comments "; ..." to the end of the line and "( ... )", blank lines,
///    lines holding only '%';
///  - the pen starts up at (0, 0); a G1-G3 with no earlier G0 starts a path
///    at the current position; moves that go nowhere are dropped, and a path
///    with no moves (a dot) is not output.
/// Coordinates: without a step size a value must be a whole number of steps
/// ("7" or "7.000"); with one, the exact decimal position (relative moves
/// accumulate exactly) is divided by the step size and rounded to the nearest
/// step, halves away from zero. Arc centres are rounded the same way.
/// Errors (messages "SOURCE:LINE:COLUMN: ..."): Errc::unsupported for a word
/// that is not listed above ("unsupported word 'G28'"), an arc without I/J
/// or with R, a Z move; Errc::syntax for malformed numbers, a repeated word,
/// two motion words on one line, a character that starts no word, an
/// unterminated comment, too many fraction digits (more than 12);
/// Errc::limit for a coordinate beyond kMaxVectorCoord steps.
/// Thread-safe. Does not check that an arc's end lies on its circle (the
/// interpolator does that).
Result<Drawing> read_gcode(std::string_view text, const VectorReadOptions& options = {});

/// G-code of slicers and CAM, read as a machine job on up to six named axes
/// (`stepzip interpolate --axes`).
struct MachineReadOptions {
    std::string source = "<input>";  ///< names the input in error messages
    /// The job's axes in output order: distinct letters among X Y Z A B C E,
    /// two to six of them (case-insensitive).
    std::string axes = "XY";
    /// Steps per millimetre (per degree for A B C) as exact decimals: none
    /// (values are whole steps), one for every axis, or one per axis in the
    /// order of `axes` (GRBL $100-$103, Marlin M92).
    std::vector<std::string> steps_per_mm;
};

/// One planned move of a machine job. Coordinates are steps, in the order of
/// the job's axes.
struct MachineMove {
    bool rapid = false;              ///< G0 (the pen is up; stepped all the same)
    MoveKind kind = MoveKind::line;  ///< arcs turn in the X Y plane; other axes move linearly
    Point to{};                      ///< end point
    std::int64_t cx = 0, cy = 0;     ///< arc centre on the X and Y axes (arcs only)
    double feed = 0;                 ///< the F word in force, units per minute as written; 0: none yet
    int pen = 1;                     ///< read_gcode(): the T word in force (the pen)
    std::uint32_t line = 0, column = 0;  ///< where the move was read
};

/// A stretch of moves the machine steps without a break: the job starts at
/// the origin; a G28 that changes the position starts a new run.
struct MachineRun {
    Point start{};
    std::vector<MachineMove> moves;
};

struct MachineJob {
    int axes = 2;
    std::string letters;  ///< the axes, upper case
    std::vector<MachineRun> runs;
    std::size_t skipped_words = 0;  ///< words read and skipped (M-codes, S, T, unknown words)
};

/// Reads G-code as a machine job. Accepted (case-insensitive):
///  - G0 / G1 / G2 / G3 (modal), every move stepped, travel included;
///    G2 / G3 turn in the X Y plane with I J centre offsets (G91.1, default)
///    or absolute centres (G90.1) while the other axes move linearly (a
///    helix); the axes X and Y must then be among the job's axes;
///  - G90 / G91 absolute / relative; M82 / M83 absolute / relative E (once
///    given they override G90 / G91 for E, as in Marlin); G20 / G21 inches /
///    millimetres (X Y Z E; A B C are degrees);
///  - G92 sets the position of the named axes (all axes, to 0, without any)
///    without stepping; G28 homes the named axes (all without any): no move
///    is planned, the machine is taken to be at 0 on those axes afterwards
///    (their G92 offsets cleared), and a new run starts there if that moved
///    it;
///  - F (feed, kept in the moves), N (line numbers), G17, G94, G4 (dwell),
///    G80 (cancel canned cycle);
///  - skipped and counted in skipped_words: every M-code other than M82 /
///    M83, S, T, other G-codes that do not move (G29, G21.1, ...), axis
///    words of axes that are not in the job, any other letter.
/// Errors (SOURCE:LINE:COLUMN): Errc::unsupported for motion words that are
/// not G0-G3 (G5, G33, G38.x, G73, G76, G81-G89 ...), an arc given by R, an
/// arc outside the X Y plane (G18 / G19) or without X and Y axes;
/// Errc::syntax and Errc::limit as read_gcode(). Coordinates round per axis
/// to the nearest step, halves away from zero (exact decimals, no drift).
/// Thread-safe. Complexity: O(bytes).
Result<MachineJob> read_gcode_job(std::string_view text, const MachineReadOptions& options);

/// How a machine job is stepped.
struct JobStepping {
    Profile profile = Profile::grbl;       ///< lines at this profile's default phase
    std::optional<ArcMethod> arc_method;   ///< as DrawingInterpolation
    std::size_t max_steps = std::size_t{1} << 28;
    std::string source = "<input>";
};

/// The STEP/DIR signals of a job: one chain per run, and per tick the DIR
/// levels (bit 2i+1 for axis i) the controller holds on its direction lines.
/// Lines: the profile's leading-axis method, one tick per step of the
/// leading axis, every DIR bit of an axis whose move is negative set for the
/// whole move (also on ticks where that axis rests). Arcs: X and Y by the arc
/// method; the other axes spread over the arc's ticks by the profile's line
/// rule; a DIR line of X or Y follows its steps (before its first step in
/// the arc: the direction of that step). A move of zero steps is no tick.
struct SteppedJob {
    std::vector<Chain> chains;                  ///< one per run with steps
    std::vector<std::vector<std::uint16_t>> dir;  ///< per chain, per tick
};

/// Steps a machine job. Errors (SOURCE:LINE:COLUMN of the move):
/// Errc::invalid_argument when the profile does not take the job's axis
/// count (eval4 and patent take X Y only); Errc::unsupported for a helix
/// whose linear axis moves more steps than the arc has ticks; the errors of
/// interpolate_drawing(). Thread-safe. Complexity: O(steps · axes).
Result<SteppedJob> step_job(const MachineJob& job, const JobStepping& how);

/// The bytes of a STEP/DIR log (the `steps` chain format, docs/formats.md):
/// per tick, bit 2i = axis i steps, bit 2i+1 = its DIR level; the runs back
/// to back. Errors: Errc::unsupported for more than 4 axes. Thread-safe.
Result<std::string> step_dir_bytes(const SteppedJob& job);

/// Reads HP-GL / HP-GL/2 as a plotter interprets it (docs/cli.md lists the
/// instructions): pen moves (PU PD PA PR PE), arcs and circles (AA AR AT RT
/// CI), rectangles, wedges and polygons as outlines (EA ER RA RR EW WG PM EP
/// FP), Beziers (BZ BR), user scaling (SC IP IR), clipping to the window
/// (IW), rotation (RO), pens (SP; VectorPath::pen, pen 0 draws nothing),
/// labels and symbols in the stroke font (LB SM DT SI SR DI DR SL ES LO CP),
/// comments, and device-control / PCL escapes skipped; instructions that do
/// not change the drawn paths (line types, widths, fills, page size ...)
/// are accepted. Curves are flattened to chords of the chord angle (5
/// degrees by default). A path starts where the pen goes down and ends when
/// it lifts, changes pen, or leaves the window.
/// Coordinates: plotter units, rounded to the nearest unit (halves away
/// from zero); with a step size, a plotter unit is 0.025 mm, rounded to the
/// nearest step.
/// Errors ("SOURCE:LINE:COLUMN: ..."): Errc::unsupported for an unknown
/// instruction ("unsupported instruction 'ZZ'"); Errc::syntax for an odd
/// number of coordinates, missing parameters, a malformed number or escape,
/// a label without its terminator, a character that starts no instruction;
/// Errc::limit for a coordinate beyond kMaxVectorCoord. Thread-safe.
/// Complexity: O(bytes + drawn points).
Result<Drawing> read_hpgl(std::string_view text, const VectorReadOptions& options = {});

/// Reads the stroked geometry of SVG (docs/cli.md, "SVG input"): path
/// (M L H V C S Q T A Z, absolute and relative, implicit repeats), line,
/// polyline, polygon, rect (rounded corners too), circle, ellipse, inside
/// svg, g, a and switch elements with their transforms (matrix, translate,
/// scale, rotate, skewX, skewY, nested). Everything else (defs, style,
/// text, use, symbol, images, metadata, display="none" ...) is skipped with
/// its content; styles (stroke, fill) are not read: every shape is drawn.
/// Each subpath and shape outline is one path; a top-level <g> that is an
/// Inkscape layer (inkscape:groupmode="layer") or has an id is a pen
/// (VectorPath::pen 1, 2, ... in document order; shapes outside them pen 1).
/// Coordinates: the root's user units (the viewBox's units, its origin
/// kept) with y negated, so y grows upwards as in `segment --to svg`; a
/// user unit is a step, or with a step size a millimetre size from the
/// root's width / height over its viewBox (CSS pixels of 1/96 inch without
/// a viewBox). Curves are flattened in step space to chords within
/// options.tolerance steps of the curve (Beziers by subdivision, arcs by
/// angle); vertices are rounded to the nearest step, halves away from zero.
/// Errors ("SOURCE:LINE:COLUMN: ..."): Errc::syntax for malformed XML, path
/// data, numbers, transforms; Errc::unsupported for a DOCTYPE internal
/// subset, a length in percent or in font units; Errc::limit for a
/// coordinate beyond kMaxVectorCoord; Errc::invalid_argument for a
/// tolerance that is not positive. Thread-safe. Complexity: O(bytes +
/// flattened vertices).
Result<Drawing> read_svg(std::string_view text, const VectorReadOptions& options = {});

/// Dispatches to read_gcode / read_hpgl / read_svg. Thread-safe.
Result<Drawing> read_vectors(VectorFormat format, std::string_view text,
                             const VectorReadOptions& options = {});

/// Options of the G-code writer.
struct GcodeWriteOptions {
    bool relative = false;              ///< G91 with incremental X Y (default: G90 absolute)
    std::optional<StepSize> step_size;  ///< write millimetres (exact decimals) instead of steps
    std::string comment;                ///< one more header comment line (none when empty)
};

/// G-code text: a header comment (and `comment`, if any, on its own line), G90 (or G91) and G21 when a step size is
/// given, then per path a G0 to its start and one G1 / G2 / G3 per move with
/// integer (or exact decimal) X Y words, and a T word before a path whose
/// pen differs from the one before (the first pen is 1); arcs carry I J relative to their
/// start. A move with a feed gets an F word (G94, units per minute, three
/// decimals) when it differs from the last one written (F is modal); G94 is
/// then written in the header. Reading the text back with the same step size gives `drawing`
/// again (apart from moves that go nowhere). Thread-safe.
std::string write_gcode(const Drawing& drawing, const GcodeWriteOptions& options = {});

/// Options of interpolate_drawing().
struct DrawingInterpolation {
    Profile profile = Profile::eval8;  ///< lines: the profile's interpolator at its default phase
    std::optional<LineMethod> line_method;  ///< set: lines by DDA or constant carrier instead
    /// Arcs (G2 / G3); nullopt: evaluation for the 4-connected profiles,
    /// accelerated for the 8-connected ones.
    std::optional<ArcMethod> arc_method;
    std::size_t max_steps = std::size_t{1} << 28;  ///< total output steps refused beyond this
    std::string source = "<input>";                ///< names the input in error messages
};

/// Forward interpolation of a drawing: one two-axis chain per path that
/// produces steps, starting at the path's start. Lines use the profile's
/// interpolator at its default phase, so segment_steps() under the same
/// profile finds each line again as one segment (or fewer, merged).
/// Errors ("SOURCE:LINE:COLUMN: ..." for moves read from a file):
/// Errc::limit (a line longer than kMaxSegmentTotal, output beyond
/// max_steps), Errc::invalid_argument from the line and arc interpolators
/// (coordinates beyond kMaxInterpolateCoord, an arc end off its circle).
/// Thread-safe. Complexity: O(steps).
/// `pens`, when given, receives the pen of each chain (VectorPath::pen).
Result<std::vector<Chain>> interpolate_drawing(const Drawing& drawing,
                                               const DrawingInterpolation& options = {},
                                               std::vector<int>* pens = nullptr);

/// Chain text (freeman or points, write_chains()) that keeps the pens:
/// before each run of chains with the same pen a comment line "# pen N"
/// (none when every pen is 1). Errors: those of write_chains(), and
/// Errc::unsupported for the steps format when a pen is not 1. Thread-safe.
Result<std::string> write_chains_with_pens(InputFormat format, const std::vector<Chain>& chains,
                                           const std::vector<int>& pens);

/// The pens of the chains in freeman or points text, from its "# pen N"
/// comment lines (a chain takes the last one before it; 1 before any).
/// One entry per chain, in order, whatever else the text holds (the text is
/// assumed to have been read by read_chains() already). Thread-safe.
std::vector<int> chain_pens(InputFormat format, std::string_view text);

/// HP-GL text: "IN;" and, when `comment` is not empty, CO"comment"; (double
/// quotes in it become single ones), "SP1;", then per path
/// "PU x0,y0;PD x1,y1,...;" and "PU;SP0;" at the end; coordinates are steps
/// (absolute).
/// Errors: Errc::unsupported when the drawing holds an arc (HP-GL's arcs are
/// given by angle, which integer end points cannot carry exactly).
/// Thread-safe.
Result<std::string> write_hpgl(const Drawing& drawing, std::string_view comment = {});

/// A chain together with the segments reverse interpolation found for it.
struct SegmentedChain {
    Chain chain;
    /// The segments in order. When `exact`, expanding them under the profile
    /// reproduces chain.steps; otherwise (the patent approximation mode) only
    /// their end points are meaningful and their phases are the defaults.
    std::vector<Segment> segments;
};

/// The drawing of segmented two-axis chains: one path per chain that has
/// steps, one line move per segment (its end point), starting at the chain's
/// start. Errors: Errc::unsupported for a chain that is not two-axis.
/// Thread-safe. Does not check that the segments expand to the chain.
Result<Drawing> segments_to_drawing(const std::vector<SegmentedChain>& chains);

/// Feed words for G-code output, from the feed-rate block (seed 000, see
/// interpolate/feedrate.hpp): the steps of a chain are timed by
/// feed_times(steps, 2, steps_per_second, factor), i.e. ticks of 1/V seconds
/// stretched by 1.41 after a diagonal step. A segment takes the time between
/// the stamp of its last step and that of the step before its first (0 for
/// a chain's first segment); its F word is its straight length divided by
/// that time, in steps per minute, or millimetres per minute with a step
/// size, so a controller in G94 mode at that F finishes the segment in the
/// time the step stream took. Along a run F = 60·V; along a diagonal it is
/// about 60·V too (√2 / 1.41).
struct FeedOptions {
    double steps_per_second = 0;        ///< V, the feed-rate block's tick rate (> 0)
    AxisFactor factor = AxisFactor::seed;
    std::optional<StepSize> step_size;  ///< F in mm/min instead of steps/min
};

/// As segments_to_drawing(), with each move's `feed` set as FeedOptions
/// describes. A segment is matched to its steps by walking the chain from
/// the previous segment's end until its end point is reached (segments are
/// monotone per axis, so this also works for the patent mode's end points).
/// Errors: as segments_to_drawing(); Errc::invalid_argument for a feed rate
/// that is not positive and finite, or segments whose end points the chain
/// does not pass through in order.
Result<Drawing> segments_to_drawing(const std::vector<SegmentedChain>& chains,
                                    const FeedOptions& feed);

/// Longest segment segment_default_phase() considers, in ticks.
inline constexpr std::int64_t kLongestVectorSegment = 4096;

/// The cut that vectors can carry. A vector (a G1, a PD pair, an SVG line)
/// has end points only, no phase, and `stepzip interpolate` draws it at the
/// profile's default phase; so this cut uses only default-phase segments:
/// at each point, of the segments starting there that the default phase
/// draws exactly (at most kLongestVectorSegment ticks, and at most 256
/// shorter than the longest), the one after which the next such segment
/// reaches farthest (the longer on a tie); `kind` greedy weighs the six
/// longest, optimal all of them (slower; patent is taken as greedy).
/// One step is always such a segment, so the cut always exists; for steps
/// the profile drew itself from a polyline it usually finds the polyline's
/// vertices (or fewer, merged). Appends to `out` segments whose expansion in
/// order is exactly `steps`, each equal to default_segment(p, delta, axes).
/// Errors: as profile_accepts(). Thread-safe.
/// Complexity: O(n) recognizer work plus O(length) per candidate checked;
/// O(kLongestVectorSegment^2) per segment in the worst case.
Result<void> segment_default_phase(std::span<const Step> steps, int axes, Profile p,
                                   std::vector<Segment>& out,
                                   SegmenterKind kind = SegmenterKind::greedy);

/// Redraws `drawing` with interpolate_drawing() under `profile` (lines at
/// the default phase; arcs by `arc_method`, or the profile's default arc
/// method when nullopt) and compares the chains with `chains`, skipping those
/// without steps: the proof that vectors written for `chains` give them
/// back. Errors: Errc::mismatch naming the first (1-based) chain that
/// differs and the first step where it does; errors of interpolate_drawing().
/// Thread-safe. Complexity: O(steps).
Result<void> check_redraw(const Drawing& drawing, const std::vector<Chain>& chains,
                          Profile profile, std::optional<ArcMethod> arc_method = std::nullopt);

/// A chain cut into arcs and lines by cut_arcs_and_lines().
struct ArcCutChain {
    Chain chain;
    std::vector<ArcCutMove> moves;
};

/// Cuts every chain with cut_arcs_and_lines() (two-axis chains only).
/// Errors: those of cut_arcs_and_lines(), the message prefixed with
/// "chain N: ". Thread-safe.
Result<std::vector<ArcCutChain>> cut_chains_into_arcs(const std::vector<Chain>& chains,
                                                      Profile profile, ArcMethod method,
                                                      const ArcCutOptions& options = {});

/// The drawing of chains cut into arcs and lines: one path per chain that has
/// steps, starting at its start; a line move per line (its end point), an
/// arc move per arc (MoveKind::arc_ccw or arc_cw, end point and centre
/// absolute). write_gcode() writes them as G1 and G2 / G3 with I J.
/// Errors: Errc::unsupported for a chain that is not two-axis. Thread-safe.
Result<Drawing> arc_cut_to_drawing(const std::vector<ArcCutChain>& chains);

/// How a segment looks, for colouring: an axis-parallel run, a 45° diagonal,
/// or a general slope.
enum class SegmentShape : std::uint8_t { run, diagonal, slope };
SegmentShape segment_shape(const Segment& segment) noexcept;

/// What the SVG and JSON writers say about the cut.
struct CutInfo {
    Profile profile = Profile::eval8;
    SegmenterKind segmenter = SegmenterKind::greedy;
    bool exact = true;                 ///< false for the patent approximation mode
    std::optional<SegmentStats> stats;  ///< the patent mode's deviation, when known
};

/// An SVG picture: each chain's unit steps as a thin grey polyline, its
/// segments drawn over it as lines (one colour per SegmentShape; dashed when
/// the cut is not exact), segment end points as small dots, the chain start
/// as a larger circle. y grows upwards (the picture is flipped). Two-axis
/// chains only. Errors: Errc::unsupported for another axis count.
/// Thread-safe. The exact markup may change between versions.
Result<std::string> write_svg(const std::vector<SegmentedChain>& chains, const CutInfo& info);

/// Plain SVG for plotter programs (vpype, Inkscape, AxiDraw): one
/// <path d="M x0 y0 L x1 y1 ..."/> per drawing path, black stroke, no fill,
/// in one group <g transform="scale(1,-1)"> so that the coordinates are the
/// steps as they are (integers, user units) and y grows upwards on the page;
/// the viewBox is the drawing's bounding box with a margin of 2 units, and
/// `comment` (if not empty) an XML comment after the root element ("--"
/// becomes "- -"). Errors: Errc::unsupported for an arc. Thread-safe.
Result<std::string> write_svg_paths(const Drawing& drawing, std::string_view comment = {});

/// JSON: {"profile", "segmenter", "exact", "stats" (patent mode), "chains":
/// [{"start": [..], "steps": N, "segments": [{"delta": [..], "phase": [..]}]}]}
/// with one phase per evaluation function (phase_count()). Any axis count.
/// Thread-safe. Key order and spacing may change between versions.
std::string write_json(const std::vector<SegmentedChain>& chains, const CutInfo& info);

}  // namespace stepzip
