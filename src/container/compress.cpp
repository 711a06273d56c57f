// .stz encoder (docs/FORMAT.md): BlockReader -> segment_steps per chain ->
// chain payload -> zstd, with a raw-bytes fallback per block, and a
// round-trip proof of every block before it is written.
// Memory: about (threads + 1) blocks. Blocks are independent, so -T N output
// equals -T 1 output byte for byte (results are written in input order).
#include <xxhash.h>

#include <algorithm>
#include <memory>
#include <thread>

#include "aligned_cut.hpp"
#include "block_codec.hpp"
#include "modeled_block.hpp"
#include "../common/bytes.hpp"
#include "memory_io.hpp"
#include "stepzip/container.hpp"

namespace stepzip {

namespace {

using namespace stz;

// One block in flight.
struct Job {
    Block block;
    std::string bytes;         // the block's input bytes (proved equal to the input)
    std::uint64_t first_chain = 0;  // index of the block's first chain in the input
    std::string record;        // the encoded block record
    unsigned type = stz::kRaw;  // block type written
    Block decoded;             // the block as the decoder sees it (chain blocks)
    SegmentStats stats;
    BlockCounts counts;
    Error error;
};

struct Settings {
    Profile profile;
    bool profile_named;
    SegmenterKind segmenter;
    int level;
    int axes;
    std::string source;
    bool allow_raw;
    bool thorough;       // level >= kThoroughLevel: try every encoding on every block
    bool aligned_cut;    // below it: the cut chosen on the first block's sample
};

// Encoder effort (docs/FORMAT.md, encoder behaviour): from this level on,
// every block is encoded every way; below it the choices are made cheaply.
constexpr int kThoroughLevel = 10;
// Below kThoroughLevel: steps of the first block's sample that picks the
// profile and the cut under --profile auto.
constexpr std::uint64_t kSampleSteps = 1u << 15;
// Segments per 1000 steps below which the segment model always wins and
// above which the step model always wins (measured on corpora/: 8.6..52
// against 383..663); in between both are encoded.
constexpr std::uint64_t kSegmentModelOnly = 60, kStepModelOnly = 250;
// Step-model context order used below kThoroughLevel (within 1% of the best
// order on every corpus file).
constexpr int kFastStepOrder = 2;

// Segments every chain of `block` under `p`; errors name the chain and step.
Result<void> segment_block(const Block& block, Profile p, SegmenterKind kind,
                           std::vector<std::vector<Segment>>& segs, SegmentStats& stats,
                           std::uint64_t first_chain, const std::string& source) {
    segs.assign(block.chains.size(), {});
    for (std::size_t c = 0; c < block.chains.size(); ++c) {
        const Chain& chain = block.chains[c];
        auto r = segment_steps(chain.steps, block.axes, p, kind, segs[c], &stats);
        if (!r)
            return make_error(r.error().code, source + ": chain " +
                                                  std::to_string(first_chain + c + 1) + ": profile " +
                                                  std::string(profile_name(p)) + ": " +
                                                  r.error().message);
    }
    return {};
}

// The smaller segment-model payload of two cuts: the segmenter's, and one
// preferring default-phase segments (controller vectors, aligned_cut.hpp).
std::string segment_model_payload(const Block& block, Profile p,
                                  const std::vector<std::vector<Segment>>& segs, SegmenterKind kind) {
    std::string best = write_segment_model(block, p, segs);
    if (kind != SegmenterKind::greedy) {
        // The fewest segments are not always the cheapest to code: try greedy too.
        std::vector<std::vector<Segment>> greedy(block.chains.size());
        bool ok = true;
        for (std::size_t c = 0; ok && c < block.chains.size(); ++c)
            ok = segment_steps(block.chains[c].steps, block.axes, p, SegmenterKind::greedy, greedy[c]).ok();
        if (ok) {
            std::string alt = write_segment_model(block, p, greedy);
            if (alt.size() < best.size()) best = std::move(alt);
        }
    }
    std::vector<std::vector<Segment>> aligned(block.chains.size());
    for (std::size_t c = 0; c < block.chains.size(); ++c)
        if (!cut_preferring_default(block.chains[c].steps, block.axes, p, aligned[c])) return best;
    if (aligned != segs) {
        std::string alt = write_segment_model(block, p, aligned);
        if (alt.size() < best.size()) best = std::move(alt);
    }
    return best;
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

// The cheap encoder's choice of segment-model cut (aligned_cut.hpp).
std::string fast_segment_model(const Block& block, Profile p,
                               const std::vector<std::vector<Segment>>& segs, bool aligned) {
    if (aligned) {
        std::vector<std::vector<Segment>> cut(block.chains.size());
        bool ok = true;
        for (std::size_t c = 0; ok && c < block.chains.size(); ++c)
            ok = cut_preferring_default(block.chains[c].steps, block.axes, p, cut[c]);
        if (ok) return write_segment_model(block, p, cut);
    }
    return write_segment_model(block, p, segs);
}

// Encodes the candidates (segment records + zstd, segment model, step
// model, raw bytes + zstd; below kThoroughLevel only those that can win),
// keeps the smallest, and proves that the record decodes back to the block.
void run_job(Job& job, const Settings& s) {
    std::string best;
    const unsigned flags = (job.block.continues ? kFlagContinues : 0u) |
                           (job.block.open ? kFlagOpen : 0u);
    unsigned type = kRaw;
    auto consider = [&](unsigned t, std::string rec) {
        if (!rec.empty() && (best.empty() || rec.size() < best.size())) {
            best = std::move(rec);
            type = t;
        }
    };
    const bool fits = job.block.axes == s.axes && job.block.chains.size() <= kMaxBlockChains;
    std::uint64_t block_steps = 0;
    for (const Chain& c : job.block.chains) block_steps += c.steps.size();
    bool segment_model_only = false;
    if (representable(job.block, s.profile, s.axes)) {
        std::vector<std::vector<Segment>> segs;
        // Below kThoroughLevel, when the sample chose the default-phase cut,
        // it is the only cut made (the chains were checked by representable()).
        bool aligned = !s.thorough && s.aligned_cut && s.segmenter != SegmenterKind::patent;
        if (aligned) {
            segs.assign(job.block.chains.size(), {});
            for (std::size_t c = 0; aligned && c < job.block.chains.size(); ++c)
                aligned = cut_preferring_default(job.block.chains[c].steps, job.block.axes, s.profile, segs[c]);
        }
        if (!aligned) {
            auto r = segment_block(job.block, s.profile, s.segmenter, segs, job.stats, job.first_chain,
                                   s.source);
            if (!r) {
                job.error = std::move(r).error();
                return;
            }
        }
        std::uint64_t nsegs = 0;
        for (const auto& v : segs) nsegs += v.size();
        if (s.thorough) {
            const std::string payload = write_chain_payload(job.block, s.profile, segs);
            if (payload.size() <= kMaxBlockPayload)
                consider(kChains, make_block_record(kChains, flags, payload, s.level));
        }
        if (s.thorough || job.block.axes != 2 || nsegs * 1000 <= kStepModelOnly * block_steps) {
            const std::string model =
                s.thorough ? segment_model_payload(job.block, s.profile, segs, s.segmenter)
                           : fast_segment_model(job.block, s.profile, segs, s.aligned_cut && !aligned);
            if (model.size() <= kMaxBlockPayload)
                consider(kSegmentModel, make_stored_record(kSegmentModel, flags, model));
        }
        segment_model_only = !s.thorough && nsegs * 1000 < kSegmentModelOnly * block_steps;
    } else if (s.profile_named && job.block.axes == s.axes) {
        for (std::size_t c = 0; c < job.block.chains.size(); ++c) {
            auto r = profile_accepts(s.profile, job.block.chains[c].steps, job.block.axes);
            if (!r) {
                job.error = make_error(r.error().code,
                                       s.source + ": chain " + std::to_string(job.first_chain + c + 1) +
                                           ": profile " + std::string(profile_name(s.profile)) +
                                           " cannot represent it: " + r.error().message);
                return;
            }
        }
    }
    if (fits && block_steps <= kMaxBlockSteps && !segment_model_only) {
        const std::string model = write_step_model(job.block, s.thorough ? 0 : kFastStepOrder);
        if (!model.empty() && model.size() <= kMaxBlockPayload)
            consider(kStepModel, make_stored_record(kStepModel, flags, model));
    }
    const bool chain_kind = !best.empty();
    if (job.bytes.size() > kMaxBlockBytes && !chain_kind) {
        job.error = make_error(Errc::limit, s.source + ": a block of " + std::to_string(job.bytes.size()) +
                                                " bytes exceeds the raw block limit");
        return;
    }
    std::string raw_payload;
    put_varint(raw_payload, job.block.chains.size());
    put_varint(raw_payload, block_steps);
    // Below kThoroughLevel zstd of the bytes is tried only when the chain
    // block is weak (less than 5:1): a general-purpose compressor does not
    // come near a modeled block that reaches it (docs/benchmarks.md).
    const bool raw_can_win = s.thorough || !chain_kind || best.size() * 5 > job.bytes.size();
    if (job.bytes.size() <= kMaxBlockBytes && (!chain_kind || s.allow_raw) && raw_can_win) {
        raw_payload += job.bytes;
        consider(kRaw, make_block_record(kRaw, flags, raw_payload, s.level));
    }
    if (best.empty()) {
        job.error = make_error(Errc::io, s.source + ": zstd compression failed");
        return;
    }
    job.type = type;
    if (type == kRaw) job.stats = {};
    job.record = std::move(best);

    // Round-trip proof, part 1: decode the record exactly as the decoder does.
    const std::string where = s.source + ": round-trip proof";
    const std::uint64_t csize = get_le(job.record.data() + 2, 4);
    const std::uint64_t dsize = get_le(job.record.data() + 6, 4);
    const std::string_view body = std::string_view(job.record).substr(kBlockHeaderSize, csize);
    std::string dec;
    if (type == kRaw || type == kChains) {
        auto z = unzstd(body, static_cast<std::uint32_t>(dsize), where);
        if (!z) {
            job.error = make_error(Errc::mismatch, z.error().message);
            return;
        }
        dec = std::move(*z);
    }
    if (type == kRaw) {
        if (dec != raw_payload) job.error = make_error(Errc::mismatch, where + ": raw block differs");
        job.counts.chains = job.block.chains.size();
        job.counts.steps = block_steps;
        return;
    }
    job.decoded.continues = job.block.continues;
    job.decoded.open = job.block.open;
    Result<void> r = type == kChains
                         ? read_chain_payload(dec, s.profile, s.axes, true, job.decoded, job.counts, where)
                     : type == kSegmentModel
                         ? read_segment_model(body, s.profile, s.axes, true, job.decoded, job.counts, where)
                         : read_step_model(body, s.axes, true, job.decoded, job.counts, where);
    if (!r) {
        job.error = make_error(Errc::mismatch, r.error().message);
        return;
    }
    if (job.decoded.chains != job.block.chains || job.decoded.layout != job.block.layout)
        job.error = make_error(Errc::mismatch, where + ": decoded chains differ from the input "
                                                      "(internal error)");
}

SegmenterKind implied_segmenter(int level) {
    return level >= kOptimalLevel ? SegmenterKind::optimal : SegmenterKind::greedy;
}

// Encoded size of a block under `p` (for --profile auto); SIZE_MAX when `p`
// cannot represent it.
std::size_t trial_size(const Block& block, Profile p, const Settings& base) {
    if (!representable(block, p, block.axes)) return SIZE_MAX;
    std::vector<std::vector<Segment>> segs;
    SegmentStats stats;
    if (!segment_block(block, p, base.segmenter, segs, stats, 0, base.source)) return SIZE_MAX;
    const std::string payload = write_chain_payload(block, p, segs);
    const std::string rec = make_block_record(kChains, 0, payload, base.level);
    const std::size_t model = segment_model_payload(block, p, segs, base.segmenter).size();
    return rec.empty() ? model : std::min(rec.size(), model);
}

// About `limit` steps of `block` for estimates only: eight stretches of
// whole chains (the last of each cut short) spread evenly over the block,
// without its layout.
Block sample_of(const Block& block, std::uint64_t limit) {
    constexpr std::uint64_t kStretches = 8;
    Block out;
    out.axes = block.axes;
    std::uint64_t total = 0;
    for (const Chain& c : block.chains) total += c.steps.size();
    std::uint64_t at = 0, next = 0, left = 0;
    const std::uint64_t each = std::max<std::uint64_t>(1, limit / kStretches);
    for (const Chain& c : block.chains) {
        if (left == 0 && at >= next && next < total) {
            left = each;
            next = std::max(next + total / kStretches, at + 1);
        }
        at += c.steps.size();
        if (left == 0) continue;
        Chain piece;
        piece.axes = c.axes;
        piece.start = c.start;
        const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(left, c.steps.size()));
        piece.steps.assign(c.steps.begin(), c.steps.begin() + static_cast<std::ptrdiff_t>(n));
        left -= n;
        out.chains.push_back(std::move(piece));
    }
    return out;
}

// Below kThoroughLevel, --profile auto: the segment-model size of the first
// block's sample under `p` with the segmenter's cut and, for the 8-connected
// and eval4 profiles, with the default-phase cut; SIZE_MAX when `p` cannot
// represent the sample. `aligned` tells which cut was smaller.
std::size_t sample_size(const Block& sample, Profile p, const Settings& base, bool& aligned) {
    aligned = false;
    if (!representable(sample, p, sample.axes)) return SIZE_MAX;
    std::vector<std::vector<Segment>> segs;
    SegmentStats stats;
    if (!segment_block(sample, p, base.segmenter, segs, stats, 0, base.source)) return SIZE_MAX;
    std::size_t best = write_segment_model(sample, p, segs).size();
    if (p != Profile::patent) {
        const std::size_t alt = fast_segment_model(sample, p, segs, true).size();
        if (alt < best) {
            best = alt;
            aligned = true;
        }
    }
    return best;
}

}  // namespace

Result<FrameInfo> compress_stream(const ReadFn& in, const WriteFn& out, const CompressOptions& opt,
                                  const ProgressFn& progress) {
    if (opt.level < 1 || opt.level > 19)
        return make_error(Errc::invalid_argument, "level must be 1..19, got " + std::to_string(opt.level));
    if (opt.block_steps == 0 || opt.block_steps > kMaxBlockSteps)
        return make_error(Errc::invalid_argument, "block size must be 1..2^24 steps");
    unsigned threads = opt.threads == 0 ? std::max(1u, std::thread::hardware_concurrency()) : opt.threads;
    threads = std::min(threads, 256u);

    Settings s;
    s.profile = opt.profile.value_or(Profile::eval8);
    s.profile_named = opt.profile.has_value();
    s.segmenter = opt.segmenter.value_or(implied_segmenter(opt.level));
    s.level = opt.level;
    s.axes = 2;
    s.source = opt.source;
    s.allow_raw = opt.allow_raw;
    s.thorough = opt.level >= kThoroughLevel;
    s.aligned_cut = false;

    FrameInfo info;
    info.segmenter = s.segmenter;
    std::optional<BlockReader> reader;
    std::optional<InputFormat> format = opt.format;
    std::unique_ptr<BlockWriter> render, proof;

    // Input bytes fed to the reader and not yet matched by a rendered block.
    std::string pending;
    std::size_t pending_pos = 0;
    std::uint64_t consumed = 0;

    XXH64_state_t* state = XXH64_createState();
    std::unique_ptr<XXH64_state_t, decltype(&XXH64_freeState)> guard(state, XXH64_freeState);
    XXH64_reset(state, 0);

    bool header_written = false;
    std::string header;
    auto write_header = [&](const Block* first) -> Result<void> {
        if (first) {
            s.axes = first->axes;
            if (!s.profile_named && s.thorough) {
                std::size_t best = SIZE_MAX;
                for (Profile p : kAllProfiles) {
                    const std::size_t n = trial_size(*first, p, s);
                    if (n < best) {
                        best = n;
                        s.profile = p;
                    }
                }
            } else if (!s.thorough && representable(*first, s.profile, first->axes)) {
                // One sample picks the profile (auto) and the cut.
                const Block sample = sample_of(*first, kSampleSteps);
                std::size_t best = SIZE_MAX;
                for (Profile p : kAllProfiles) {
                    if (s.profile_named && p != s.profile) continue;
                    bool aligned = false;
                    const std::size_t n = sample_size(sample, p, s, aligned);
                    if (n < best) {
                        best = n;
                        s.profile = p;
                        s.aligned_cut = aligned;
                    }
                }
            }
            if (s.profile_named && s.axes > profile_max_axes(s.profile)) {
                return make_error(Errc::invalid_argument,
                                  s.source + ": profile " + std::string(profile_name(s.profile)) +
                                      " does not take " + std::to_string(s.axes) + " axes");
            }
        }
        FrameHeader h;
        h.profile = s.profile;
        h.format = *format;
        h.axes = s.axes;
        h.segmenter = s.segmenter;
        header = write_frame_header(h);
        header_written = true;
        info.profile = s.profile;
        info.format = *format;
        info.axes = s.axes;
        return out(header);
    };

    std::vector<Job> batch;
    std::uint64_t next_chain = 0;
    bool chain_open = false;
    auto flush_batch = [&]() -> Result<void> {
        if (batch.empty()) return {};
        if (batch.size() == 1 || threads == 1) {
            for (Job& j : batch) run_job(j, s);
        } else {
            std::vector<std::thread> pool;
            const std::size_t n = std::min<std::size_t>(threads, batch.size());
            for (std::size_t t = 1; t < n; ++t)
                pool.emplace_back([&, t] {
                    for (std::size_t i = t; i < batch.size(); i += n) run_job(batch[i], s);
                });
            for (std::size_t i = 0; i < batch.size(); i += n) run_job(batch[i], s);
            for (auto& th : pool) th.join();
        }
        for (Job& j : batch) {
            if (j.error.code != Errc::ok) return std::move(j.error);
            // Round-trip proof, part 2: render the decoded block with a writer
            // that sees exactly what the decoder's writer sees.
            if (j.type != kRaw) {
                std::string again;
                auto r = proof->write(j.decoded, again);
                if (!r || again != j.bytes)
                    return make_error(Errc::mismatch, s.source + ": round-trip proof failed on block " +
                                                          std::to_string(info.blocks) +
                                                          " (internal error); nothing written");
                info.segments += j.counts.segments;
                info.stats += j.stats;
            } else {
                ++info.raw_blocks;
            }
            if (j.type == kSegmentModel) ++info.segment_model_blocks;
            if (j.type == kStepModel) ++info.step_model_blocks;
            info.chains += j.counts.chains;
            if (j.block.continues && chain_open && j.counts.chains > 0) --info.chains;
            chain_open = j.block.open;
            info.steps += j.counts.steps;
            ++info.blocks;
            XXH64_update(state, j.bytes.data(), j.bytes.size());
            info.decoded_bytes += j.bytes.size();
            info.compressed_bytes += j.record.size();
            if (auto r = out(j.record); !r) return r;
        }
        batch.clear();
        return {};
    };

    auto take_blocks = [&]() -> Result<void> {
        Block block;
        while (reader->next(block)) {
            Job job;
            // Render with the encoder's writer: the bytes this block stands for.
            if (auto r = render->write(block, job.bytes); !r)
                return make_error(Errc::mismatch, s.source + ": cannot render block (internal error): " +
                                                      r.error().message);
            if (job.bytes.size() > pending.size() - pending_pos ||
                pending.compare(pending_pos, job.bytes.size(), job.bytes) != 0)
                return make_error(Errc::unsupported,
                                  s.source + ": byte " + std::to_string(consumed) +
                                      ": the input cannot be reproduced byte-exactly from its chains "
                                      "(refused rather than normalized)");
            pending_pos += job.bytes.size();
            consumed += job.bytes.size();
            if (pending_pos > (1u << 20) && pending_pos * 2 > pending.size()) {
                pending.erase(0, pending_pos);
                pending_pos = 0;
            }
            if (!header_written)
                if (auto r = write_header(&block); !r) return r;
            job.first_chain = next_chain;
            next_chain += block.chains.size() - (block.continues && !block.chains.empty() ? 1 : 0);
            job.block = std::move(block);
            block = Block{};
            batch.push_back(std::move(job));
            if (batch.size() >= threads)
                if (auto r = flush_batch(); !r) return r;
        }
        return {};
    };

    std::string chunk(1 << 20, '\0');
    for (;;) {
        auto n = in(chunk.data(), chunk.size());
        if (!n) return std::move(n).error();
        const std::string_view data(chunk.data(), *n);
        if (!format && data.empty()) format = InputFormat::freeman;  // empty input
        if (!format) {
            format = detect_format(data);
            if (!format)
                return make_error(Errc::unsupported,
                                  s.source + ": cannot tell the input format (use --format "
                                             "freeman|points|steps)");
        }
        if (!reader) {
            reader.emplace(*format, s.source, opt.block_steps);
            render = std::make_unique<BlockWriter>(*format);
            proof = std::make_unique<BlockWriter>(*format);
        }
        pending.append(data);
        if (auto r = reader->feed(data, *n == 0); !r) return std::move(r).error();
        if (auto r = take_blocks(); !r) return std::move(r).error();
        if (progress) progress(consumed);
        if (*n == 0) break;
    }
    if (auto r = flush_batch(); !r) return std::move(r).error();
    if (pending.size() != pending_pos)
        return make_error(Errc::unsupported,
                          s.source + ": byte " + std::to_string(consumed) +
                              ": the input cannot be reproduced byte-exactly from its chains "
                              "(refused rather than normalized)");
    if (!header_written)
        if (auto r = write_header(nullptr); !r) return std::move(r).error();
    std::string end;
    put_u8(end, kEnd);
    put_le(end, info.decoded_bytes, 8);
    put_le(end, info.stats.patent_segments, 8);
    put_le(end, info.stats.patent_exact, 8);
    put_le(end, static_cast<std::uint64_t>(info.stats.patent_max_deviation), 8);
    put_le(end, check32(header + end), 4);
    info.checksum = XXH64_digest(state);
    put_le(end, info.checksum, 8);
    if (auto r = out(end); !r) return std::move(r).error();
    info.compressed_bytes += header.size() + end.size();
    return info;
}

Result<std::string> compress(std::string_view input, const CompressOptions& opt) {
    std::string out;
    auto r = compress_stream(stz::memory_reader(input), stz::string_writer(out), opt);
    if (!r) return std::move(r).error();
    return out;
}

}  // namespace stepzip
