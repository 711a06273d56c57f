// The .stz block codec: chain payload serialization and parsing, block
// records, frame header (docs/FORMAT.md). Shared by compressor and decoder.
#include "block_codec.hpp"

#include <xxhash.h>
#include <zstd.h>

#include <cstdlib>
#include <limits>

#include "bench_hooks.hpp"
#include "../common/bytes.hpp"

namespace stepzip::stz {

std::uint64_t hash64(std::string_view data) { return XXH64(data.data(), data.size(), 0); }
std::uint32_t check32(std::string_view data) { return static_cast<std::uint32_t>(hash64(data)); }

// ---------------------------------------------------------------- header

namespace {
// Version 2 header byte 5: profile bits 0-2, input format bits 3-4,
// segmenter bits 5-6, bit 7 reserved; byte 6: axes bits 0-2, window log
// bits 3-7; byte 7: header check.
unsigned header_check(std::string_view first7) {
    return static_cast<unsigned>(hash64(first7.substr(0, 7)) >> 8) & 0xFFu;
}
}  // namespace

std::string write_frame_header(const FrameHeader& h) {
    std::string out(reinterpret_cast<const char*>(kMagic), 4);
    put_u8(out, kFormatVersion);
    put_u8(out, static_cast<unsigned>(h.profile) | (static_cast<unsigned>(h.format) << 3) |
                    (static_cast<unsigned>(h.segmenter) << 5));
    put_u8(out, static_cast<unsigned>(h.axes) | (static_cast<unsigned>(h.window_log) << 3));
    put_u8(out, header_check(out));
    return out;
}

Result<FrameHeader> parse_frame_header(std::string_view b, std::string_view source) {
    const std::string src(source);
    for (std::size_t i = 0; i < 4; ++i) {
        if (i >= b.size())
            return make_error(Errc::truncated, src + ": byte " + std::to_string(i) +
                                                   ": truncated frame header");
        if (static_cast<unsigned char>(b[i]) != kMagic[i])
            return make_error(Errc::bad_magic,
                              src + ": byte " + std::to_string(i) + ": not a .stz file (bad magic)");
    }
    if (b.size() < 5)
        return make_error(Errc::truncated, src + ": byte 4: truncated frame header");
    const unsigned version = static_cast<unsigned char>(b[4]);
    if (version < static_cast<unsigned>(kOldestFormatVersion) || version > static_cast<unsigned>(kFormatVersion))
        return make_error(Errc::bad_version, src + ": byte 4: format version " +
                                                 std::to_string(version) + " is not supported (this "
                                                 "decoder reads versions " +
                                                 std::to_string(kOldestFormatVersion) + " to " +
                                                 std::to_string(kFormatVersion) + ")");
    FrameHeader h;
    h.version = static_cast<int>(version);
    if (b.size() < h.size())
        return make_error(Errc::truncated,
                          src + ": byte " + std::to_string(b.size()) + ": truncated frame header");
    unsigned prof, fmt, axes, seg;
    if (version == 1) {
        prof = static_cast<unsigned char>(b[5]);
        fmt = static_cast<unsigned char>(b[6]);
        axes = static_cast<unsigned char>(b[7]);
        seg = static_cast<unsigned char>(b[8]);
        const unsigned reserved = static_cast<unsigned char>(b[9]);
        if ((seg & ~3u) != 0 || reserved != 0)
            return make_error(Errc::reserved_bits,
                              src + ": byte " + ((seg & ~3u) ? "8" : "9") + ": reserved bits are set");
    } else {
        if (static_cast<unsigned char>(b[7]) != header_check(b))
            return make_error(Errc::checksum, src + ": byte 7: frame header check mismatch");
        const unsigned d = static_cast<unsigned char>(b[5]);
        const unsigned w = static_cast<unsigned char>(b[6]);
        if ((d & 0x80u) != 0)
            return make_error(Errc::reserved_bits, src + ": byte 5: reserved bit is set");
        prof = d & 7u;
        fmt = (d >> 3) & 3u;
        seg = (d >> 5) & 3u;
        axes = w & 7u;
        h.window_log = static_cast<int>(w >> 3);
        if (h.window_log > kMaxWindowLog)
            return make_error(Errc::limit, src + ": byte 6: window of 2^" + std::to_string(h.window_log) +
                                               " exceeds the decoder limit of 2^" +
                                               std::to_string(kMaxWindowLog));
    }
    if (prof > static_cast<unsigned>(Profile::marlin))
        return make_error(Errc::corrupt, src + ": byte 5: unknown profile " + std::to_string(prof));
    if (fmt > static_cast<unsigned>(version == 1 ? InputFormat::steps : InputFormat::timed))
        return make_error(Errc::corrupt, src + ": byte " + (version == 1 ? "6" : "5") +
                                             ": unknown input format " + std::to_string(fmt));
    h.profile = static_cast<Profile>(prof);
    if (axes < 2 || static_cast<int>(axes) > profile_max_axes(h.profile))
        return make_error(Errc::corrupt, src + ": byte " + (version == 1 ? "7" : "6") + ": axis count " +
                                             std::to_string(axes) + " is not valid for profile " +
                                             std::string(profile_name(h.profile)));
    if (seg > 2)
        return make_error(Errc::corrupt, src + ": byte " + (version == 1 ? "8" : "5") + ": unknown segmenter 3");
    h.format = static_cast<InputFormat>(fmt);
    h.axes = static_cast<int>(axes);
    h.segmenter = static_cast<SegmenterKind>(seg);
    return h;
}

std::string block_header(unsigned type, unsigned flags, std::uint64_t csize, std::uint64_t dsize) {
    std::string out;
    put_u8(out, type | (flags << 3));
    put_varint(out, csize);
    if (type == kChains || type == kRaw) put_varint(out, dsize);
    return out;
}

RecordView view_record(std::string_view rec) {
    RecordView v;
    Cursor cur(rec);
    unsigned b = 0;
    std::uint64_t csize = 0;
    cur.u8(b);
    v.type = b & 7u;
    v.flags = b >> 3;
    cur.varint(csize);
    v.dsize = csize;
    if (v.type == kChains || v.type == kRaw) cur.varint(v.dsize);
    cur.bytes(static_cast<std::size_t>(csize), v.payload);
    return v;
}

// ---------------------------------------------------------------- directions

namespace {

// 2D direction: angular octant 0..7 counter-clockwise from +x, indexed by
// lead * 4 + negmask (negmask bit i = axis i negative).
constexpr int kOctantOf[8] = {0, 3, 7, 4, 1, 2, 6, 5};
constexpr int kCodeOfOctant[8] = {0, 4, 5, 1, 3, 7, 6, 2};

struct Direction {
    int lead = 0;
    unsigned negmask = 0;
};

Direction direction_of(const Point& d, int axes) {
    Direction dir;
    dir.lead = leading_axis(d, axes);
    for (int i = 0; i < axes; ++i)
        if (d[i] < 0) dir.negmask |= 1u << i;
    return dir;
}

std::int64_t seg_steps(Profile p, const Point& d, int axes) {
    return segment_length(d, axes, profile_eight_connected(p));
}

}  // namespace

// ---------------------------------------------------------------- chain payload

namespace {
enum Stream { kLayout, kHeads, kDirs, kLeads, kMinors, kPhases, kStreams };
}

std::string write_chain_payload(const Block& block, Profile p,
                                const std::vector<std::vector<Segment>>& segs) {
    return write_chain_payload_variant(block, p, segs, PayloadVariant{});
}

std::string write_chain_payload_variant(const Block& block, Profile p,
                                        const std::vector<std::vector<Segment>>& segs,
                                        const PayloadVariant& variant) {
    const int axes = block.axes;
    std::string streams[kStreams];
    std::string* s[kStreams];
    for (int i = 0; i < kStreams; ++i) s[i] = variant.interleaved && i > kHeads ? &streams[kHeads] : &streams[i];
    streams[kLayout] = block.layout;
    std::uint64_t nsegments = 0, nsteps = 0;
    Point ref{};
    int prev_octant = 0;
    for (std::size_t c = 0; c < block.chains.size(); ++c) {
        const Chain& chain = block.chains[c];
        for (int i = 0; i < axes; ++i) put_svarint(*s[kHeads], wrap_sub(chain.start[i], ref[i]));
        put_varint(*s[kHeads], segs[c].size());
        for (const Segment& seg : segs[c]) {
            const Direction dir = direction_of(seg.delta, axes);
            if (axes == 2) {
                const int oct = kOctantOf[dir.lead * 4 + dir.negmask];
                put_u8(*s[kDirs], static_cast<unsigned>((oct - prev_octant) & 7));
                if (variant.octant_delta) prev_octant = oct;
            } else {
                put_varint(*s[kDirs], (static_cast<std::uint64_t>(dir.lead) << axes) | dir.negmask);
            }
            const std::int64_t l = std::llabs(seg.delta[dir.lead]);
            put_varint(*s[kLeads], static_cast<std::uint64_t>(l - 1));
            for (int i = 0; i < axes; ++i)
                if (i != dir.lead) put_varint(*s[kMinors], static_cast<std::uint64_t>(std::llabs(seg.delta[i])));
            for (int j = 0; j < phase_count(p, axes); ++j) {
                const auto ab = *phase_arguments(p, seg, axes, j);
                const PhaseRange r = phase_range(p, ab.first, ab.second);
                if (r.hi - r.lo == 1) continue;
                put_svarint(*s[kPhases], seg.phase[j] - default_phase(p, ab.first, ab.second));
            }
            nsteps += static_cast<std::uint64_t>(seg_steps(p, seg.delta, axes));
            ++nsegments;
        }
        ref = variant.start_from_end ? chain.end() : chain.start;
    }
    std::string out;
    put_varint(out, block.chains.size());
    put_varint(out, nsegments);
    put_varint(out, nsteps);
    if (variant.interleaved) {
        put_varint(out, streams[kLayout].size());
        out += streams[kLayout];
        out += streams[kHeads];
    } else {
        for (const std::string& st : streams) put_varint(out, st.size());
        for (const std::string& st : streams) out += st;
    }
    return out;
}

Result<void> read_chain_payload(std::string_view payload, Profile p, int axes, bool expand,
                                Block& out, BlockCounts& counts, const std::string& where) {
    Cursor hdr(payload);
    auto fail = [&](Errc e, std::size_t at, const std::string& what) -> Error {
        return make_error(e, where + " byte " + std::to_string(at) + ": " + what);
    };
    std::uint64_t nchains, nsegments, nsteps, layout_size;
    if (!hdr.varint(nchains) || !hdr.varint(nsegments) || !hdr.varint(nsteps) ||
        !hdr.varint(layout_size))
        return fail(Errc::corrupt, hdr.pos(), "bad payload header");
    if (nchains > kMaxBlockChains || nsegments > kMaxBlockSteps || nsteps > kMaxBlockSteps)
        return fail(Errc::limit, 0, "payload declares more chains, segments or steps than the limits");
    std::string_view layout;
    if (!hdr.bytes(layout_size > hdr.left() ? hdr.left() + 1 : static_cast<std::size_t>(layout_size), layout))
        return fail(Errc::corrupt, hdr.pos(), "layout runs past the payload");
    // Records: every field is read from one cursor, in record order.
    const std::size_t base = hdr.pos();
    Cursor records(payload.substr(base));
    Cursor* cur[kStreams];
    for (auto& c : cur) c = &records;
    auto at = [&](int) { return base + records.pos(); };
    auto short_stream = [&](int st) {
        return fail(Errc::corrupt, at(st), "records end early");
    };
    if (expand) {
        out.axes = axes;
        out.chains.clear();
        out.layout.assign(layout);
    }
    Point ref{};
    int prev_octant = 0;
    std::uint64_t seen_segments = 0, seen_steps = 0;
    for (std::uint64_t c = 0; c < nchains; ++c) {
        Chain chain;
        chain.axes = axes;
        for (int i = 0; i < axes; ++i) {
            std::int64_t d;
            if (!cur[kHeads]->svarint(d)) return short_stream(kHeads);
            chain.start[i] = wrap_add(ref[i], d);
            if (!start_in_range(chain.start[i]))
                return fail(Errc::corrupt, at(kHeads), "chain start out of range");
        }
        std::uint64_t nseg;
        if (!cur[kHeads]->varint(nseg)) return short_stream(kHeads);
        if (nseg > nsegments - seen_segments)
            return fail(Errc::corrupt, at(kHeads), "more segments than declared");
        Point pos = chain.start;
        for (std::uint64_t k = 0; k < nseg; ++k) {
            Segment seg;
            Direction dir;
            std::uint64_t code;
            if (axes == 2) {
                unsigned b;
                if (!cur[kDirs]->u8(b)) return short_stream(kDirs);
                if (b > 7) return fail(Errc::corrupt, at(kDirs) - 1, "bad direction code");
                prev_octant = (prev_octant + static_cast<int>(b)) & 7;
                code = static_cast<std::uint64_t>(kCodeOfOctant[prev_octant]);
                dir.lead = static_cast<int>(code >> 2);
                dir.negmask = static_cast<unsigned>(code & 3);
            } else {
                if (!cur[kDirs]->varint(code)) return short_stream(kDirs);
                dir.lead = static_cast<int>(code >> axes);
                dir.negmask = static_cast<unsigned>(code & ((1u << axes) - 1));
                if (code >> axes >= static_cast<std::uint64_t>(axes))
                    return fail(Errc::corrupt, at(kDirs), "bad direction code");
            }
            std::uint64_t l1;
            if (!cur[kLeads]->varint(l1)) return short_stream(kLeads);
            if (l1 >= static_cast<std::uint64_t>(kMaxSegmentTotal))
                return fail(Errc::limit, at(kLeads), "segment longer than 2^30 steps");
            const std::int64_t l = static_cast<std::int64_t>(l1) + 1;
            for (int i = 0; i < axes; ++i) {
                std::int64_t v;
                if (i == dir.lead) {
                    v = l;
                } else {
                    std::uint64_t s;
                    if (!cur[kMinors]->varint(s)) return short_stream(kMinors);
                    if (s > static_cast<std::uint64_t>(l) || (i < dir.lead && s == static_cast<std::uint64_t>(l)))
                        return fail(Errc::corrupt, at(kMinors), "minor total exceeds the leading total");
                    v = static_cast<std::int64_t>(s);
                }
                if ((dir.negmask >> i) & 1u) {
                    if (v == 0) return fail(Errc::corrupt, at(kDirs), "sign on a resting axis");
                    v = -v;
                }
                seg.delta[i] = v;
            }
            for (int j = 0; j < phase_count(p, axes); ++j) {
                const auto ab = *phase_arguments(p, seg, axes, j);
                const PhaseRange r = phase_range(p, ab.first, ab.second);
                if (r.hi - r.lo == 1) {
                    seg.phase[j] = r.lo;
                    continue;
                }
                std::int64_t d;
                if (!cur[kPhases]->svarint(d)) return short_stream(kPhases);
                if (d > (std::int64_t{1} << 62) || d < -(std::int64_t{1} << 62))
                    return fail(Errc::corrupt, at(kPhases), "phase out of range");
                seg.phase[j] = default_phase(p, ab.first, ab.second) + d;
            }
            if (auto ok = check_segment(p, seg, axes); !ok)
                return fail(Errc::corrupt, at(kPhases), "invalid segment: " + ok.error().message);
            const std::int64_t n = seg_steps(p, seg.delta, axes);
            seen_steps += static_cast<std::uint64_t>(n);
            if (seen_steps > nsteps)
                return fail(Errc::corrupt, at(kLeads), "more steps than declared");
            for (int i = 0; i < axes; ++i) pos[i] += seg.delta[i];
            if (expand) expand_segment(p, seg, axes, chain.steps);
            ++seen_segments;
        }
        ref = pos;
        if (expand) out.chains.push_back(std::move(chain));
    }
    if (seen_segments != nsegments || seen_steps != nsteps)
        return fail(Errc::corrupt, 0, "declared segment or step count does not match");
    if (!records.done()) return fail(Errc::corrupt, at(0), "trailing bytes after the last record");
    counts.chains += nchains;
    counts.segments += nsegments;
    counts.steps += nsteps;
    return {};
}

// ---------------------------------------------------------------- records

std::string make_block_record(unsigned type, unsigned flags, std::string_view raw, int level) {
    const std::size_t bound = ZSTD_compressBound(raw.size());
    std::string z(bound, '\0');
    const std::size_t n = ZSTD_compress(z.data(), bound, raw.data(), raw.size(), level);
    if (ZSTD_isError(n)) return {};
    z.resize(n);
    std::string rec = block_header(type, flags, z.size(), raw.size());
    rec += z;
    put_le(rec, check32(rec), 4);
    return rec;
}

std::string make_stored_record(unsigned type, unsigned flags, std::string_view payload) {
    std::string rec = block_header(type, flags, payload.size(), payload.size());
    rec += payload;
    put_le(rec, check32(rec), 4);
    return rec;
}

Result<std::string> unzstd(std::string_view compressed, std::uint32_t dsize, const std::string& where) {
    const unsigned long long declared = ZSTD_getFrameContentSize(compressed.data(), compressed.size());
    if (declared == ZSTD_CONTENTSIZE_ERROR || declared != dsize)
        return make_error(Errc::corrupt, where + ": payload is not a zstd frame of the declared size");
    std::string out(dsize, '\0');
    const std::size_t n = ZSTD_decompress(out.data(), out.size(), compressed.data(), compressed.size());
    if (ZSTD_isError(n) || n != dsize)
        return make_error(Errc::corrupt, where + ": payload does not decompress (" +
                                             (ZSTD_isError(n) ? ZSTD_getErrorName(n) : "size") + ")");
    return out;
}

}  // namespace stepzip::stz
