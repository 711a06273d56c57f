// stepzip fuzz targets: one function per target, shared by the libFuzzer
// entry points (fuzz/<target>_fuzz.cpp) and the regression replay test
// (tests/hardening_regressions_test.cpp), so an input that once broke a
// target is replayed by the normal test suite without libFuzzer.
//
// Each function takes arbitrary bytes and returns an empty string when every
// property held, or a description of the violated property. A crash, leak,
// hang or sanitizer report inside the library is of course also a failure.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "stepzip/chain.hpp"
#include "stepzip/container.hpp"
#include "stepzip/document.hpp"
#include "stepzip/profile.hpp"
#include "stepzip/segment/arc.hpp"
#include "stepzip/segmenter.hpp"
#include "stepzip/vectors.hpp"
#include "../src/container/arc_items.hpp"
#include "../src/container/modeled_block.hpp"
#include "../src/container/table_block.hpp"
#include "../src/container/timed_block.hpp"
#include "../src/container/timed_tick.hpp"

namespace stepzip::fuzz {

/// The target names, as used for fuzz/seeds/<name> and tests/regressions/<name>.
inline constexpr std::string_view kTargets[] = {"container", "freeman",   "points", "steps",
                                                "vectors",   "roundtrip", "arc",    "payload"};

/// Errors a chain-file or vector reader may report for bad text.
inline bool reader_error(Errc e) {
    switch (e) {
        case Errc::syntax:
        case Errc::not_a_step:
        case Errc::limit:
        case Errc::overflow:
        case Errc::unsupported: return true;
        default: return false;
    }
}

inline std::string describe(const Error& e) {
    return std::string(errc_name(e.code)) + ": " + e.message;
}

/// Arbitrary bytes -> decompress: an error from the documented set, or
/// bytes; inspect_stream agrees on success, and a successful frame decodes
/// the same through a reader that returns one byte at a time.
inline std::string container_target(const std::uint8_t* data, std::size_t size) {
    const std::string_view frame(reinterpret_cast<const char*>(data), size);
    auto out = decompress(frame, "fuzz");
    if (!out) {
        if (!is_frame_error(out.error().code)) return "decompress: undocumented error " + describe(out.error());
        if (out.error().message.rfind("fuzz", 0) != 0)
            return "decompress: message does not name the source: " + out.error().message;
        return {};
    }
    // The same frame read one byte at a time must give the same bytes.
    std::size_t pos = 0;
    ReadFn slow = [&](char* buf, std::size_t cap) -> Result<std::size_t> {
        if (pos >= frame.size() || cap == 0) return std::size_t{0};
        buf[0] = frame[pos++];
        return std::size_t{1};
    };
    std::string again;
    WriteFn sink = [&](std::string_view b) -> Result<void> {
        again.append(b);
        return {};
    };
    auto info = decompress_stream(slow, sink, "fuzz");
    if (!info) return "decompress_stream: byte-wise read fails where the whole frame decodes: " + describe(info.error());
    if (again != *out) return "decompress_stream: byte-wise read decodes other bytes";
    if (info->decoded_bytes != out->size()) return "decompress_stream: decoded_bytes disagrees";
    pos = 0;
    auto inspected = inspect_stream(slow, "fuzz");
    if (!inspected) return "inspect_stream fails on a frame that decodes: " + describe(inspected.error());
    return {};
}

/// A block size near `wanted` that cuts `total_steps` into at most 16
/// blocks: tiny blocks exercise the block boundaries, but each block has a
/// fixed cost, and thousands of them would only slow the fuzzer down.
inline std::size_t bounded_block_steps(std::size_t wanted, std::size_t total_steps) {
    return std::max<std::size_t>(wanted, total_steps / 16 + 1);
}

/// Parses `text` with a BlockReader, fed in pieces whose sizes come from
/// `cuts` (cycled); returns the blocks or the error.
inline Result<std::vector<Block>> read_blocks(InputFormat format, std::string_view text,
                                              std::string_view cuts, std::size_t block_steps) {
    BlockReader reader(format, "fuzz", block_steps);
    std::vector<Block> blocks;
    std::size_t pos = 0, k = 0;
    do {
        std::size_t n = text.size() - pos;
        if (!cuts.empty()) {
            n = std::min<std::size_t>(n, 1 + static_cast<std::uint8_t>(cuts[k++ % cuts.size()]));
        }
        const bool last = pos + n == text.size();
        if (auto r = reader.feed(text.substr(pos, n), last); !r) return std::move(r).error();
        pos += n;
        Block b;
        while (reader.next(b)) blocks.push_back(std::move(b));
    } while (pos < text.size());
    return blocks;
}

/// Compression levels the fuzz targets pick from: 1, the default 3, 9 (the
/// last of the cheap tier), 10 (the first level that encodes every block
/// every way) up to 19, so both tiers of the encoder and both segmenters
/// that levels imply are fuzzed.
inline constexpr int kFuzzLevels[] = {1, 2, 3, 6, 9, 10, 14, 19};

/// A text parser target: the first byte picks the block size (bits 0-2) and
/// the compression level (bits 3-5, kFuzzLevels), the second the number of
/// feed() chunk sizes that follow (0-2); the rest is the file. The reader
/// must accept or reject it the same way however it is cut; accepted input
/// must render back to the identical bytes and compress/decompress exactly.
inline std::string chain_file_target(InputFormat format, const std::uint8_t* data,
                                     std::size_t size) {
    if (size < 4) return {};
    static constexpr std::size_t kBlockSizes[] = {1, 2, 3, 5, 8, 64, 1000, kDefaultBlockSteps};
    const std::size_t block_steps = kBlockSizes[data[0] % 8];
    const std::size_t ncuts = data[1] % 3;  // 0: whole input in one feed()
    const std::string_view cuts(reinterpret_cast<const char*>(data + 2), ncuts);
    const std::string_view text(reinterpret_cast<const char*>(data + 2 + ncuts), size - 2 - ncuts);

    auto whole = read_blocks(format, text, {}, block_steps);
    auto piecewise = read_blocks(format, text, ncuts ? cuts : std::string_view("\0", 1), block_steps);
    if (whole.ok() != piecewise.ok()) return "feed(): the result depends on the chunking";
    if (!whole) {
        if (!reader_error(whole.error().code)) return "reader: undocumented error " + describe(whole.error());
        if (whole.error().message.rfind("fuzz", 0) != 0)
            return "reader: message does not name the source: " + whole.error().message;
        if (whole.error().message != piecewise.error().message)
            return "feed(): the error depends on the chunking: '" + whole.error().message +
                   "' vs '" + piecewise.error().message + "'";
        return {};
    }
    if (whole->size() != piecewise->size()) return "feed(): block count depends on the chunking";
    BlockWriter writer(format);
    std::string rendered;
    for (std::size_t i = 0; i < whole->size(); ++i) {
        const Block& a = (*whole)[i];
        const Block& b = (*piecewise)[i];
        if (a.chains != b.chains || a.layout != b.layout || a.open != b.open ||
            a.continues != b.continues || a.axes != b.axes)
            return "feed(): block " + std::to_string(i) + " depends on the chunking";
        for (const Chain& c : a.chains)
            if (c.steps.size() > block_steps) return "reader: a block holds more than block_steps steps";
        if (auto r = writer.write(a, rendered); !r) return "writer refuses a block the reader made: " + describe(r.error());
    }
    if (rendered != text) return "writer does not reproduce the input bytes";

    // The whole container round trip on the same input, every block's proof
    // included, at the level bits 3-5 of the first byte pick.
    CompressOptions opt;
    opt.format = format;
    opt.level = kFuzzLevels[(data[0] >> 3) % 8];
    std::size_t total_steps = 0;
    for (const Block& b : *whole)
        for (const Chain& c : b.chains) total_steps += c.steps.size();
    opt.block_steps = bounded_block_steps(block_steps, total_steps);
    opt.source = "fuzz";
    auto z = compress(text, opt);
    if (!z) return "compress fails on input the reader accepts: " + describe(z.error());
    auto back = decompress(*z);
    if (!back) return "decompress fails on a fresh frame: " + describe(back.error());
    if (*back != text) return "decompress(compress(x)) != x";
    return {};
}

inline std::string freeman_target(const std::uint8_t* d, std::size_t n) {
    return chain_file_target(InputFormat::freeman, d, n);
}
inline std::string points_target(const std::uint8_t* d, std::size_t n) {
    return chain_file_target(InputFormat::points, d, n);
}
/// The steps format, or with bit 6 of the first byte the same bytes read
/// timed (time as axis 0: the timed and tick blocks of the encoder).
inline std::string steps_target(const std::uint8_t* d, std::size_t n) {
    return chain_file_target(n > 0 && (d[0] & 0x40) ? InputFormat::timed : InputFormat::steps, d, n);
}

/// G-code, HP-GL and SVG readers: the first byte picks G-code or HP-GL and
/// the step size (text detected as SVG is read as SVG); the reader returns
/// a drawing or a documented error; every coordinate it returns is within
/// kMaxVectorCoord; a drawing written back as G-code (and HP-GL and plain
/// SVG when it has no arcs) reads back as the same drawing (SVG: pens 1).
inline std::string vectors_target(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return {};
    VectorFormat format = (data[0] & 1) ? VectorFormat::hpgl : VectorFormat::gcode;
    VectorReadOptions options;
    options.source = "fuzz";
    static constexpr const char* kSizes[] = {"0.0125", "1", "0.000000000001", "1000000"};
    if (data[0] & 2) options.step_size = *parse_step_size(kSizes[(data[0] >> 2) & 3]);
    const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
    if (detect_vector_format(text) == VectorFormat::svg) format = VectorFormat::svg;
    auto drawing = read_vectors(format, text, options);
    if (!drawing) {
        if (!reader_error(drawing.error().code)) return "vectors: undocumented error " + describe(drawing.error());
        if (drawing.error().message.rfind("fuzz", 0) != 0)
            return "vectors: message does not name the source: " + drawing.error().message;
        return {};
    }
    bool arcs = false;
    auto in_range = [](std::int64_t v) { return v >= -kMaxVectorCoord && v <= kMaxVectorCoord; };
    for (const VectorPath& p : *drawing) {
        if (p.moves.empty()) return "vectors: a path without moves";
        if (!in_range(p.x0) || !in_range(p.y0)) return "vectors: a path start beyond kMaxVectorCoord";
        for (const VectorMove& m : p.moves) {
            if (!in_range(m.x) || !in_range(m.y)) return "vectors: a coordinate beyond kMaxVectorCoord";
            arcs = arcs || m.kind != MoveKind::line;
        }
    }
    VectorReadOptions plain;
    plain.source = "fuzz-rewritten";
    auto again = read_gcode(write_gcode(*drawing), plain);
    if (!again) return "G-code written from a drawing does not read back: " + describe(again.error());
    if (*again != *drawing) return "G-code written from a drawing reads back differently";
    if (!arcs) {
        auto hpgl = write_hpgl(*drawing);
        if (!hpgl) return "write_hpgl refuses a drawing without arcs: " + describe(hpgl.error());
        auto back = read_hpgl(*hpgl, plain);
        if (!back) return "HP-GL written from a drawing does not read back: " + describe(back.error());
        if (*back != *drawing) return "HP-GL written from a drawing reads back differently";
        auto svg = write_svg_paths(*drawing);
        if (!svg) return "write_svg_paths refuses a drawing without arcs: " + describe(svg.error());
        auto svg_back = read_svg(*svg, plain);
        if (!svg_back) return "SVG written from a drawing does not read back: " + describe(svg_back.error());
        Drawing one_pen = *drawing;
        for (VectorPath& p : one_pen) p.pen = 1;
        if (*svg_back != one_pen) return "SVG written from a drawing reads back differently";
    }
    return {};
}

/// Bytes -> chains. Byte 0: axes and format; then every byte (two bytes for
/// six axes) is a step: for two axes a Freeman code (byte & 7), else the
/// base-3 digits of the value (0: rest, 1: +1, 2: -1) per axis; a byte
/// whose step would be zero (two axes: a byte >= 0xF8) ends the chain.
struct FuzzChains {
    int axes = 2;
    InputFormat format = InputFormat::freeman;
    std::vector<Chain> chains;
};

inline FuzzChains make_chains(const std::uint8_t* data, std::size_t size) {
    FuzzChains fc;
    if (size == 0) return fc;
    const unsigned sel = data[0];
    fc.format = static_cast<InputFormat>(sel % 3);
    if (fc.format == InputFormat::freeman) fc.axes = 2;
    else if (fc.format == InputFormat::steps) fc.axes = 2 + static_cast<int>((sel / 3) % 3);  // 2..4
    else fc.axes = 2 + static_cast<int>((sel / 3) % 5);                                     // 2..6
    const std::size_t width = fc.axes == 6 ? 2 : 1;
    std::int64_t next_start = 0;
    auto new_chain = [&] {
        Chain c;
        c.axes = fc.axes;
        // The steps format has a single chain from the origin.
        if (fc.format != InputFormat::steps) {
            for (int i = 0; i < fc.axes; ++i) c.start[i] = (i % 2 ? -next_start : next_start);
            // Starts spread over a wide range, far apart but well inside the
            // readers' +-2^62 (the jump between chains is coded as a difference).
            next_start = next_start * 7 + 3;
            if (next_start > (std::int64_t{1} << 36) || next_start < -(std::int64_t{1} << 36))
                next_start = next_start > 0 ? -5 : 11;
        }
        fc.chains.push_back(std::move(c));
    };
    new_chain();
    for (std::size_t i = 1; i + width <= size; i += width) {
        unsigned v = data[i];
        if (width == 2) v |= static_cast<unsigned>(data[i + 1]) << 8;
        Step s = 0;
        if (fc.axes == 2) {
            if (v < 0xF8) s = freeman_to_step(static_cast<int>(v & 7));
        } else {
            int d[kMaxAxes] = {};
            for (int a = 0; a < fc.axes; ++a) {
                const unsigned t = v % 3;
                v /= 3;
                d[a] = t == 0 ? 0 : t == 1 ? 1 : -1;
            }
            s = make_step(d, fc.axes);
        }
        if (s == 0) {
            if (fc.format != InputFormat::steps) new_chain();
        } else {
            fc.chains.back().steps.push_back(s);
        }
    }
    return fc;
}

/// Round trip: arbitrary bytes -> chains (make_chains on the bytes after
/// the first three) -> text -> compress under the profile / segmenter and
/// level (kFuzzLevels) / block size chosen by the first three bytes ->
/// decompress must equal the
/// text; and every segmenter under every profile that accepts a chain cuts
/// it into checked segments that expand back to exactly its steps.
inline std::string roundtrip_target(const std::uint8_t* data, std::size_t size) {
    if (size < 4) return {};
    const FuzzChains fc = make_chains(data + 3, size - 3);
    auto text = write_chains(fc.format, fc.chains);
    if (!text) return "write_chains refuses generated chains: " + describe(text.error());
    auto parsed = read_chains(fc.format, *text, "fuzz");
    if (!parsed) return "read_chains refuses what write_chains wrote: " + describe(parsed.error());

    // Segmenters, directly.
    for (const Chain& c : fc.chains) {
        for (Profile p : kAllProfiles) {
            if (!profile_accepts(p, c.steps, c.axes)) continue;
            for (SegmenterKind k : {SegmenterKind::greedy, SegmenterKind::optimal, SegmenterKind::patent}) {
                if (k == SegmenterKind::patent && !c.four_connected()) continue;
                if (k == SegmenterKind::patent && c.axes != 2) continue;
                std::vector<Segment> segs;
                SegmentStats stats;
                auto r = segment_steps(c.steps, c.axes, p, k, segs, &stats);
                if (!r) return std::string("segment_steps(") + std::string(profile_name(p)) + ", " +
                               std::string(segmenter_name(k)) + ") fails on an accepted chain: " + describe(r.error());
                std::vector<Step> back;
                for (const Segment& s : segs) {
                    if (auto ok = check_segment(p, s, c.axes); !ok)
                        return "segmenter emits a segment that fails check_segment: " + describe(ok.error());
                    expand_segment(p, s, c.axes, back);
                }
                if (back != c.steps)
                    return std::string("segments do not expand to the chain under ") +
                           std::string(profile_name(p)) + " / " + std::string(segmenter_name(k));
            }
        }
    }

    // The container.
    CompressOptions opt;
    opt.format = fc.format;
    opt.level = kFuzzLevels[(data[1] / 3) % 8];
    opt.source = "fuzz";
    const unsigned pick = data[0] % 6;
    if (pick < 5) opt.profile = kAllProfiles[pick];
    opt.segmenter = static_cast<SegmenterKind>(data[1] % 3);
    static constexpr std::size_t kBlockSizes[] = {1, 2, 3, 7, 16, 100, 4096, kDefaultBlockSteps};
    std::size_t total_steps = 0;
    for (const Chain& c : fc.chains) total_steps += c.steps.size();
    opt.block_steps = bounded_block_steps(kBlockSizes[data[2] % 8], total_steps);
    opt.allow_raw = (data[2] & 8) == 0;
    opt.threads = (data[2] & 16) ? 2 : 1;

    bool representable = true;
    for (const Chain& c : fc.chains) {
        if (opt.profile && !profile_accepts(*opt.profile, c.steps, c.axes)) representable = false;
        if (*opt.segmenter == SegmenterKind::patent && (c.axes != 2 || !c.four_connected()))
            representable = false;
    }
    auto z = compress(*text, opt);
    if (!z) {
        const Errc e = z.error().code;
        if (representable ||
            (e != Errc::connectivity && e != Errc::invalid_argument && e != Errc::unsupported))
            return "compress fails: " + describe(z.error());
        return {};
    }
    auto back = decompress(*z);
    if (!back) return "decompress fails on a fresh frame: " + describe(back.error());
    if (*back != *text) return "decompress(compress(x)) != x";
    return {};
}

/// Bytes -> an arc method and two-axis steps: byte 0 picks the method and
/// the case, bytes 1..6 (case 1) an arc drawn by the method about the origin
/// (start and end offsets in -16..15, direction), then every further byte a
/// Freeman step (4-connected codes for the 4-connected methods). Properties:
/// longest_arc's answer is 0 or an arc that interpolate_arc draws as exactly
/// its first steps, and longest_arc_about at its centre finds it too; for a
/// drawn arc, longest_arc_about about the true centre finds at least the
/// drawn steps; cut_arcs_and_lines' moves (eval4 lines for the 4-connected
/// methods, eval8 for the others) draw exactly the steps, and as a table
/// block with arc items they decode to them. At most 240 steps.
inline std::string arc_target(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return {};
    static constexpr ArcMethod kMethods[] = {ArcMethod::evaluation, ArcMethod::accelerated,
                                             ArcMethod::dda, ArcMethod::prediction_correction,
                                             ArcMethod::double_recursion};
    const ArcMethod m = kMethods[data[0] % 5];
    const bool eight = m == ArcMethod::accelerated || m == ArcMethod::dda ||
                       m == ArcMethod::double_recursion;
    std::vector<Step> steps;
    std::size_t at = 1, drawn = 0;
    std::int64_t sx = 0, sy = 0;
    bool ccw = false;
    if ((data[0] / 5) % 2 == 1 && size >= 7) {
        const auto c = [&](std::size_t i) { return static_cast<std::int64_t>(data[i] % 32) - 16; };
        sx = c(1);
        sy = c(2);
        ccw = data[5] % 2 == 1;
        at = 7;
        if ((sx != 0 || sy != 0) && (c(3) != 0 || c(4) != 0) &&
            interpolate_arc(m, sx, sy, c(3), c(4), ccw, steps))
            drawn = steps.size();
    }
    for (; at < size && steps.size() < 240; ++at)
        steps.push_back(freeman_to_step(eight ? data[at] % 8 : 2 * (data[at] % 4)));
    const std::span<const Step> all(steps);

    ArcSearchOptions o;
    o.min_length = 1 + data[0] % 9;
    o.max_length = 1024;
    const ArcFit f = longest_arc(m, all, o);
    std::vector<Step> out;
    if (f.length > 0) {
        if (f.length > steps.size() || f.length < o.min_length)
            return "longest_arc: length out of range";
        if (!interpolate_arc(m, -f.cx, -f.cy, f.ex - f.cx, f.ey - f.cy, f.ccw, out) ||
            !std::equal(out.begin(), out.end(), steps.begin(), steps.begin() + static_cast<long>(f.length)) ||
            out.size() != f.length)
            return "longest_arc: the arc found does not draw its steps";
        if (longest_arc_about(m, all, f.cx, f.cy, f.ccw, o.max_length) < f.length)
            return "longest_arc_about misses the arc longest_arc found";
    }
    if (drawn > 0 && longest_arc_about(m, all, -sx, -sy, ccw, o.max_length) < drawn)
        return "longest_arc_about misses the drawn arc about its own centre";

    {
        const Profile p = eight ? Profile::eval8 : Profile::eval4;
        std::vector<ArcCutMove> moves;
        if (auto r = cut_arcs_and_lines(all, 2, p, m, {}, moves); !r)
            return "cut_arcs_and_lines fails: " + describe(r.error());
        std::vector<Step> back;
        for (const ArcCutMove& mv : moves) {
            if (mv.is_arc) {
                const ArcFit& a = mv.arc;
                if (!interpolate_arc(m, -a.cx, -a.cy, a.ex - a.cx, a.ey - a.cy, a.ccw, back))
                    return "cut_arcs_and_lines: an arc that does not draw";
            } else {
                expand_segment(p, mv.line, 2, back);
            }
        }
        if (back != steps) return "cut_arcs_and_lines: the moves do not draw the steps";

        // The container with arc items: these moves as a table block decode
        // to the chain (whether or not compress would keep that block), when
        // every arc's step bound fits the block (else the format refuses it).
        Chain chain;
        chain.axes = 2;
        chain.steps = steps;
        Block block;
        block.axes = 2;
        block.chains = {chain};
        std::vector<std::vector<Segment>> cut(1);
        for (const ArcCutMove& mv : moves) {
            if (mv.is_arc && stz::arc_step_bound(mv.arc.cx, mv.arc.cy) > steps.size()) return {};
            cut[0].push_back(mv.is_arc ? stz::arc_item(mv.arc, m) : mv.line);
        }
        Block decoded;
        stz::BlockCounts counts;
        if (auto r = stz::read_table_block(stz::write_table_block(block, p, cut), p, 2, true, decoded, counts, "fuzz");
            !r || decoded.chains != block.chains)
            return "a table block with arc items does not decode to its chain";
    }
    return {};
}

/// A block payload given straight to its decoder, past the block checksum
/// that the `container` target's mutations seldom get through. Byte 0 picks
/// the decoder (mod 8): 0 tick block, 1 table block (type 5), 2 table block
/// with unpredicted minor totals (type 7 subtype 4), 3 step model, 4 mixed
/// step model (model bytes 1 and 3, and 4: the context-mixing one), 5
/// segment model, 6 mixed segment model, 7 type 7 by its subtype (timed,
/// tick); byte 1 the profile (bits 0-2, mod 5) and the axis count (bits
/// 3-5: 2 plus that mod the profile's range, as a frame header allows); the
/// rest is the payload. The decoder must give a block whose chains agree
/// with its counts, or a documented error naming the payload byte; decoding
/// without expanding must accept or reject it the same way.
inline std::string payload_target(const std::uint8_t* data, std::size_t size) {
    if (size < 2) return {};
    const unsigned kind = data[0] % 8u;
    const auto p = static_cast<Profile>((data[1] & 7u) % 5u);
    const int axes = 2 + static_cast<int>((data[1] >> 3) & 7u) % (profile_max_axes(p) - 1);
    const std::string_view payload(reinterpret_cast<const char*>(data) + 2, size - 2);
    auto decode = [&](bool expand, Block& out, stz::BlockCounts& counts) -> Result<void> {
        switch (kind) {
            case 0: return stz::read_tick_block(payload, axes, expand, out, counts, "fuzz");
            case 1: return stz::read_table_block(payload, p, axes, expand, out, counts, "fuzz");
            case 2:
                return stz::read_table_block(payload, p, axes, expand, out, counts, "fuzz", nullptr, nullptr,
                                             stz::kExtended);
            case 3: return stz::read_step_model(payload, axes, expand, out, counts, "fuzz");
            case 4:
                return stz::read_step_model(payload, axes, expand, out, counts, "fuzz", nullptr, kFormatVersion,
                                            nullptr, true);
            case 5: return stz::read_segment_model(payload, p, axes, expand, out, counts, "fuzz");
            case 6: return stz::read_segment_model(payload, p, axes, expand, out, counts, "fuzz", nullptr, nullptr, false, true);
            default: return stz::read_extended_block(payload, p, axes, expand, out, counts, "fuzz");
        }
    };
    Block out;
    stz::BlockCounts counts;
    const auto r = decode(true, out, counts);
    Block bare;
    stz::BlockCounts bare_counts;
    const auto again = decode(false, bare, bare_counts);
    if (r.ok() != again.ok()) return "the decoder accepts or rejects differently without expanding";
    if (!r) {
        const Error& e = r.error();
        if (e.code != Errc::corrupt && e.code != Errc::limit) return "undocumented error " + describe(e);
        if (e.message.rfind("fuzz byte ", 0) != 0) return "error does not name the payload byte: " + e.message;
        return {};
    }
    std::uint64_t steps = 0;
    for (const Chain& c : out.chains) {
        if (c.axes != axes) return "a chain of another axis count";
        steps += c.steps.size();
    }
    if (out.chains.size() != counts.chains || steps != counts.steps) return "decoded chains disagree with the counts";
    if (bare_counts.chains != counts.chains || bare_counts.steps != counts.steps ||
        bare_counts.segments != counts.segments)
        return "counts differ without expanding";
    return {};
}

/// Runs target `name` on one input; nullopt for an unknown name.
inline std::optional<std::string> run_target(std::string_view name, const std::uint8_t* d,
                                             std::size_t n) {
    if (name == "container") return container_target(d, n);
    if (name == "freeman") return freeman_target(d, n);
    if (name == "points") return points_target(d, n);
    if (name == "steps") return steps_target(d, n);
    if (name == "vectors") return vectors_target(d, n);
    if (name == "roundtrip") return roundtrip_target(d, n);
    if (name == "arc") return arc_target(d, n);
    if (name == "payload") return payload_target(d, n);
    return std::nullopt;
}

}  // namespace stepzip::fuzz
