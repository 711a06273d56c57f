// .stz decoder (docs/FORMAT.md): a stream of frames back to back; per frame
// the header, the blocks in order (chain payloads are expanded by forward
// interpolation and rendered by the BlockWriter; each block's contribution
// enters the frame's window) and the trailer. Reads versions 1 and 2.
// Memory: one block at a time plus the window the frame declares (at most
// 2^kMaxWindowLog steps + chains); no declared size drives an allocation
// before it is checked against the limits in container.hpp.
#include <xxhash.h>

#include <algorithm>
#include <cstring>
#include <deque>
#include <memory>

#include "block_codec.hpp"
#include "modeled_block.hpp"
#include "../common/bytes.hpp"
#include "memory_io.hpp"
#include "raw_cm.hpp"
#include "table_block.hpp"
#include "timed_block.hpp"
#include "timed_tick.hpp"
#include "window.hpp"
#include "stepzip/container.hpp"

namespace stepzip {

namespace {

using namespace stz;

// Buffered exact reads from a ReadFn, tracking the frame offset.
class Source {
public:
    Source(const ReadFn& in, std::string_view name) : in_(in), name_(name) {}

    std::uint64_t offset() const noexcept { return offset_; }
    const std::string& name() const noexcept { return name_; }

    // Reads exactly n bytes into out (appending); `got` is how many arrived.
    Result<void> read(std::size_t n, std::string& out, std::size_t& got) {
        got = 0;
        while (got < n) {
            if (pos_ == buf_.size()) {
                if (eof_) break;
                buf_.resize(kChunk);
                pos_ = 0;
                auto r = in_(buf_.data(), buf_.size());
                if (!r) return std::move(r).error();
                buf_.resize(*r);
                if (*r == 0) {
                    eof_ = true;
                    break;
                }
            }
            const std::size_t take = std::min(n - got, buf_.size() - pos_);
            out.append(buf_, pos_, take);
            pos_ += take;
            got += take;
            offset_ += take;
        }
        return {};
    }
    Result<bool> at_end() {
        if (pos_ < buf_.size()) return false;
        std::string tmp;
        std::size_t got;
        if (auto r = read(1, tmp, got); !r) return std::move(r).error();
        if (got == 0) return true;
        --offset_;
        --pos_;
        return false;
    }

private:
    static constexpr std::size_t kChunk = 1 << 16;
    const ReadFn& in_;
    std::string name_;
    std::string buf_;
    std::size_t pos_ = 0;
    bool eof_ = false;
    std::uint64_t offset_ = 0;
};

Error truncated(const Source& s, const std::string& what) {
    return make_error(Errc::truncated,
                      s.name() + ": byte " + std::to_string(s.offset()) + ": truncated " + what);
}

// Reads a varint byte by byte (appending its bytes to `rec`).
Result<std::uint64_t> read_varint(Source& src, std::string& rec, const std::string& what) {
    std::uint64_t v = 0;
    for (int shift = 0;; shift += 7) {
        std::size_t got;
        const std::size_t at = rec.size();
        if (auto r = src.read(1, rec, got); !r) return std::move(r).error();
        if (got < 1) return truncated(src, what);
        const unsigned b = static_cast<unsigned char>(rec[at]);
        if (shift == 63 && b > 1)
            return make_error(Errc::corrupt, src.name() + ": byte " + std::to_string(src.offset() - 1) +
                                                 ": over-long varint in the " + what);
        v |= std::uint64_t{b & 0x7Fu} << shift;
        if ((b & 0x80u) == 0) return v;
    }
}

// One block as read from the frame.
struct BlockRead {
    unsigned type = 0, flags = 0;
    std::uint64_t csize = 0, dsize = 0;
    std::size_t header = 0;  // bytes of the block header in `rec`
};

// The decoder of one frame (docs/FORMAT.md section 1): header, blocks in
// order, trailer. `out` null: inspect only (no rendering).
class FrameDecoder {
public:
    FrameDecoder(Source& src, const WriteFn* out, const ProgressFn& progress)
        : src_(src), out_(out), progress_(progress) {}

    // Decodes the frame whose first bytes (already read) are `head`.
    Result<FrameInfo> run(std::string head) {
        frame_at_ = src_.offset() - head.size();
        if (auto r = read_header(head); !r) return std::move(r).error();
        info_.format_version = hdr_.version;
        info_.profile = hdr_.profile;
        info_.format = hdr_.format;
        info_.axes = hdr_.axes;
        info_.segmenter = hdr_.segmenter;
        info_.window = hdr_.window();
        window_ = Window(hdr_.window());
        // With a window, every chain block is decoded in full: later blocks
        // start from its content.
        expand_ = out_ != nullptr || hdr_.window() != 0;
        // The step model's history is built when a block first needs it.
        steps_frame_ = hdr_.window() != 0 && hdr_.axes == 2;
        if (out_) writer_ = std::make_unique<BlockWriter>(hdr_.format);
        state_ = XXH64_createState();
        XXH64_reset(state_, 0);
        auto r = blocks();
        if (r) r = trailer();
        XXH64_freeState(state_);
        if (!r) return std::move(r).error();
        info_.compressed_bytes = src_.offset() - frame_at_;
        return info_;
    }

private:
    Result<void> read_header(std::string& head) {
        std::size_t got;
        if (head.size() < 5)
            if (auto r = src_.read(5 - head.size(), head, got); !r) return r;
        if (head.size() == 5) {
            const unsigned v = static_cast<unsigned char>(head[4]);
            const std::size_t size = v == 1 ? kFrameHeaderSizeV1 : kFrameHeaderSize;
            if (v == 1 || v == 2)
                if (auto r = src_.read(size - 5, head, got); !r) return r;
        }
        auto h = parse_frame_header(head, src_.name() + (frame_at_ ? " (frame at byte " +
                                                                         std::to_string(frame_at_) + ")"
                                                                   : std::string()));
        if (!h) return std::move(h).error();
        hdr_ = *h;
        head_ = head;
        return {};
    }

    std::string at(std::uint64_t offset) const { return src_.name() + ": byte " + std::to_string(offset); }

    // Reads a block header and its payload into rec_; false at the end mark.
    Result<bool> read_block(BlockRead& b) {
        const std::uint64_t block_at = src_.offset();
        std::size_t got;
        rec_.clear();
        if (auto r = src_.read(1, rec_, got); !r) return std::move(r).error();
        if (got < 1) return truncated(src_, "frame: no end mark");
        const unsigned first = static_cast<unsigned char>(rec_[0]);
        if (first == kEnd) return false;
        if (hdr_.version == 1) {
            b.type = first;
            if (b.type > kStepModel)
                return make_error(Errc::corrupt, at(block_at) + ": unknown block type " + std::to_string(b.type));
            if (auto r = src_.read(kBlockHeaderSizeV1 - 1, rec_, got); !r) return std::move(r).error();
            if (got < kBlockHeaderSizeV1 - 1) return truncated(src_, "block header");
            b.flags = static_cast<unsigned char>(rec_[1]);
            if ((b.flags & ~3u) != 0)
                return make_error(Errc::reserved_bits, at(block_at + 1) + ": reserved block flags are set");
            b.csize = get_le(rec_.data() + 2, 4);
            b.dsize = get_le(rec_.data() + 6, 4);
        } else {
            b.type = first & 7u;
            b.flags = first >> 3;
            if (b.type == kEnd || b.type > kExtended)
                return make_error(Errc::corrupt, at(block_at) + ": unknown block type " + std::to_string(b.type));
            if ((b.flags & ~7u) != 0)
                return make_error(Errc::reserved_bits, at(block_at) + ": reserved block flags are set");
            if ((b.flags & kFlagWindow) && hdr_.window() == 0)
                return make_error(Errc::corrupt, at(block_at) + ": block uses a window the frame does not declare");
            auto c = read_varint(src_, rec_, "block header");
            if (!c) return std::move(c).error();
            b.csize = *c;
            b.dsize = b.csize;
            if (b.type == kChains || b.type == kRaw) {
                auto d = read_varint(src_, rec_, "block header");
                if (!d) return std::move(d).error();
                b.dsize = *d;
            }
        }
        b.header = rec_.size();
        const std::uint64_t dlimit = b.type == kRaw ? kMaxBlockBytes + 20 : kMaxBlockPayload;
        if (b.csize > kMaxBlockPayload || b.dsize > dlimit)
            // The sizes start after the type and flags bytes in version 1, after
            // the one block byte in version 2.
            return make_error(Errc::limit, at(block_at + (hdr_.version == 1 ? 2 : 1)) +
                                               ": block sizes exceed the decoder limits");
        const bool stored = b.type == kSegmentModel || b.type == kStepModel || b.type == kTable || b.type == kMixedModel ||
                            b.type == kExtended;
        if (stored && b.dsize != b.csize)
            return make_error(Errc::corrupt, at(block_at + 6) +
                                                 ": decoded size of a modeled block differs from its size");
        if (auto r = src_.read(static_cast<std::size_t>(b.csize) + kBlockChecksumSize, rec_, got); !r)
            return std::move(r).error();
        if (got < b.csize + kBlockChecksumSize) return truncated(src_, "block");
        const std::string_view body(rec_.data(), b.header + b.csize);
        if (check32(body) != get_le(rec_.data() + body.size(), 4))
            return make_error(Errc::checksum, at(block_at + body.size()) + ": block checksum mismatch");
        where_ = at(block_at) + " (block " + std::to_string(info_.blocks) + ")";
        return true;
    }

    Result<void> blocks() {
        std::string rendered;
        for (;;) {
            BlockRead b;
            auto more = read_block(b);
            if (!more) return std::move(more).error();
            if (!*more) return {};
            const std::string_view payload = std::string_view(rec_).substr(b.header, b.csize);
            auto contribution = std::make_shared<WindowBlock>();
            // The segments' memory of a block that left the window (its pages
            // are in place: a fresh array of several MB is faulted in again).
            contribution->items.segments = std::move(spare_segments_);
            const WindowView view = window_.view();
            const bool step_model = b.type == kStepModel || (b.type == kMixedModel && !payload.empty() &&
                                                             mixed_model_of(static_cast<unsigned char>(payload[0])) == kStepModel);
            if (steps_frame_ && !steps_ && step_model && (b.flags & kFlagWindow)) start_history(view);
            if (steps_) {
                const std::uint64_t end = step_history_end(*steps_);
                contribution->first_symbol = end;
                step_history_begin_block(*steps_, view.empty() ? end : view.front()->first_symbol, window_.limit());
            }
            bool on_history = false;  // the block's symbols went into steps_ as it was decoded
            Block held_block;         // kept for start_history() (raw blocks: none)
            rendered.clear();
            ++info_.blocks;
            // A CM raw block (type 7 subtype 3) decodes to a raw block's payload.
            const bool cm_raw = b.type == kExtended && !payload.empty() &&
                                static_cast<unsigned char>(payload[0]) == kRawCmSubtype;
            if (b.type == kRaw || cm_raw) {
                auto raw = cm_raw ? read_raw_cm_block(payload, where_ + " payload")
                                  : unzstd(payload, static_cast<std::uint32_t>(b.dsize), where_);
                if (!raw) return std::move(raw).error();
                ++info_.raw_blocks;
                Cursor cur(*raw);
                std::uint64_t nchains, nsteps;
                if (!cur.varint(nchains) || !cur.varint(nsteps))
                    return make_error(Errc::corrupt, where_ + ": bad raw block counts");
                info_.chains += nchains;
                if ((b.flags & kFlagContinues) && chain_open_ && nchains > 0) --info_.chains;
                chain_open_ = b.flags & kFlagOpen;
                info_.steps += nsteps;
                info_.decoded_bytes += cur.left();
                contribution->weight = nsteps + nchains;
                if (out_) rendered.assign(*raw, cur.pos());
            } else {
                Block block;
                block.continues = b.flags & kFlagContinues;
                block.open = b.flags & kFlagOpen;
                BlockCounts counts;
                const WindowView* w = (b.flags & kFlagWindow) ? &view : nullptr;
                const std::string what = where_ + " payload";
                Result<void> r;
                // Block type 6 decodes as the model its first byte names.
                const bool mixed = b.type == kMixedModel;
                // Block type 7 decodes as the subtype its first byte names:
                // a timed or tick block, or a table block (read_table_block checks the rest).
                const unsigned char sub = payload.empty() ? 0xFF : static_cast<unsigned char>(payload[0]);
                const bool ext_table = b.type == kExtended && sub == kTableSubtype;
                if (b.type == kExtended && !ext_table && sub != kTimedSubtype && !is_tick_subtype(sub))
                    return make_error(Errc::corrupt, what + " byte 0: unknown subtype of an extended block");
                if (b.type == kExtended && !ext_table && hdr_.format != InputFormat::timed)
                    return make_error(Errc::corrupt, what + " byte 0: a timed block in a frame that is not timed");
                const unsigned model = ext_table ? kTable
                                       : !mixed ? b.type
                                       : payload.empty() ? kEnd
                                       : mixed_model_of(static_cast<unsigned char>(payload[0]));
                if (model == kEnd)
                    return make_error(Errc::corrupt, what + " byte 0: unknown model of a mixed-model block");
                if (b.type == kChains) {
                    auto raw = unzstd(payload, static_cast<std::uint32_t>(b.dsize), where_);
                    if (!raw) return std::move(raw).error();
                    r = read_chain_payload(*raw, hdr_.profile, hdr_.axes, expand_, block, counts, what);
                } else if (model == kSegmentModel) {
                    r = read_segment_model(payload, hdr_.profile, hdr_.axes, expand_, block, counts, what, w,
                                           window_.limit() ? &contribution->items : nullptr,
                                           hdr_.format == InputFormat::timed, mixed);
                } else if (model == kExtended) {
                    r = read_extended_block(payload, hdr_.profile, hdr_.axes, expand_, block, counts, what, w,
                                         window_.limit() ? &contribution->items : nullptr);
                } else if (model == kTable) {
                    r = read_table_block(payload, hdr_.profile, hdr_.axes, expand_, block, counts, what, w,
                                         window_.limit() ? &contribution->items : nullptr, b.type);
                } else {
                    on_history = w && steps_;
                    r = read_step_model(payload, hdr_.axes, expand_, block, counts, what, w, hdr_.version,
                                        steps_.get(), mixed);
                }
                if (!r) return std::move(r).error();
                if (model == kSegmentModel) ++info_.segment_model_blocks;
                if (model == kStepModel) ++info_.step_model_blocks;
                if (model == kTable) ++info_.table_blocks;
                if (model == kExtended) ++info_.timed_blocks;
                info_.segments += counts.segments;
                info_.steps += counts.steps;
                info_.chains += counts.chains;
                if (block.continues && chain_open_ && counts.chains > 0) --info_.chains;
                chain_open_ = block.open;
                contribution->weight = counts.steps + counts.chains;
                // A timed frame's chain block: its ticks, for the tick blocks' match.
                if (hdr_.format == InputFormat::timed && window_.limit()) contribution->ticks = tick_masks(block);
                if (steps_ && !on_history) {
                    add_steps(*contribution, block);
                    step_history_add(*steps_, *contribution);
                    // The history holds the symbols: the window keeps their place only.
                    contribution->symbols = {};
                    contribution->starts = {};
                }
                if (out_) {
                    if (auto rr = writer_->write(block, rendered); !rr)
                        return make_error(rr.error().code, where_ + ": " + rr.error().message);
                    info_.decoded_bytes += rendered.size();
                }
                // A table block's chains stay with its contribution while the
                // window holds it (later table blocks copy their steps).
                if (model == kTable && expand_ && window_.limit()) contribution->chains = std::move(block.chains);
                // Before the history exists the decoded block itself is held:
                // start_history() takes its symbols if a block ever needs them.
                if (steps_frame_ && !steps_) held_block = std::move(block);
            }
            if (steps_frame_ && !steps_) held_.push_back(Held{contribution, std::move(held_block)});
            window_.push(std::move(contribution));
            if (!held_.empty()) {
                // Only the window's blocks are held (it drops the oldest first).
                const WindowView now = window_.view();
                while (!held_.empty() && std::none_of(now.begin(), now.end(), [&](const auto& b) {
                           return b.get() == held_.front().contribution.get();
                       })) {
                    // Out of the window: no later block reads its items.
                    spare_segments_ = std::move(held_.front().contribution->items.segments);
                    held_.pop_front();
                }
            }
            if (out_) {
                XXH64_update(state_, rendered.data(), rendered.size());
                if (auto r = (*out_)(rendered); !r) return r;
            }
            if (progress_) progress_(src_.offset());
        }
    }

    // The step model's history of the frame, built from the window's blocks
    // (their positions counted from the window's start: a table rebuilt from
    // the window alone, section 1.8) when a block first decodes on it; from
    // then on every block is added as it is decoded. Until then no block
    // pays for the history (the table blocks of the fast levels never do).
    void start_history(const WindowView& view) {
        steps_ = make_step_history();
        for (const auto& c : view) {
            Held* held = nullptr;
            for (auto& h : held_)
                if (h.contribution.get() == c.get()) held = &h;
            if (!held) continue;  // cannot happen: the window holds at most kMaxWindowBlocks
            WindowBlock& w = *held->contribution;
            w.first_symbol = step_history_end(*steps_);
            add_steps_lent(w, held->block);
            step_history_add(*steps_, w);
            w.symbols = {};
            w.starts = {};
        }
        held_.clear();
    }

    Result<void> trailer() {
        const std::uint64_t end_at = src_.offset() - 1;
        std::uint64_t size = 0;
        std::size_t got;
        std::uint64_t hash_at;
        if (hdr_.version == 1) {
            if (auto r = src_.read(kTrailerSizeV1, rec_, got); !r) return r;
            if (got < kTrailerSizeV1) return truncated(src_, "frame trailer");
            // rec_ = end mark + trailer
            const std::string_view t(rec_.data() + 1, kTrailerSizeV1);
            size = get_le(t.data(), 8);
            std::string checked = head_;
            checked.append(rec_, 0, 1 + 32);
            if (check32(checked) != get_le(t.data() + 32, 4))
                return make_error(Errc::checksum, at(end_at + 33) + ": frame trailer checksum mismatch");
            info_.stats.patent_segments = get_le(t.data() + 8, 8);
            info_.stats.patent_exact = get_le(t.data() + 16, 8);
            info_.stats.patent_max_deviation = static_cast<std::int64_t>(get_le(t.data() + 24, 8));
            info_.checksum = get_le(t.data() + 36, 8);
            hash_at = end_at + 37;
        } else {
            auto s = read_varint(src_, rec_, "frame trailer");
            if (!s) return std::move(s).error();
            size = *s;
            const std::uint64_t flags_at = src_.offset();
            if (auto r = src_.read(1, rec_, got); !r) return r;
            if (got < 1) return truncated(src_, "frame trailer");
            const unsigned flags = static_cast<unsigned char>(rec_.back());
            if ((flags & ~1u) != 0) return make_error(Errc::reserved_bits, at(flags_at) + ": reserved trailer flags are set");
            if (flags & 1u) {
                std::string meta;
                auto m = read_varint(src_, meta, "frame trailer metadata");
                if (!m) return std::move(m).error();
                if (*m > kMaxMetadata)
                    return make_error(Errc::limit, at(flags_at + 1) + ": trailer metadata over the limit");
                const std::uint64_t meta_at = src_.offset();
                meta.clear();
                if (auto r = src_.read(static_cast<std::size_t>(*m) + 4, meta, got); !r) return r;
                if (got < *m + 4) return truncated(src_, "frame trailer metadata");
                const std::string_view body(meta.data(), static_cast<std::size_t>(*m));
                if (check32(body) != get_le(meta.data() + *m, 4))
                    return make_error(Errc::checksum, at(meta_at + *m) + ": trailer metadata checksum mismatch");
                if (auto r = read_metadata(body, meta_at); !r) return r;
            }
            hash_at = src_.offset();
            std::string h;
            if (auto r = src_.read(8, h, got); !r) return r;
            if (got < 8) return truncated(src_, "frame trailer");
            info_.checksum = get_le(h.data(), 8);
        }
        if (out_) {
            if (size != info_.decoded_bytes)
                return make_error(Errc::corrupt, at(end_at + 1) + ": decoded size " +
                                                     std::to_string(info_.decoded_bytes) +
                                                     " differs from the recorded " + std::to_string(size));
            if (XXH64_digest(state_) != info_.checksum)
                return make_error(Errc::checksum, at(hash_at) +
                                                      ": content checksum mismatch (decoded bytes "
                                                      "differ from the original)");
        } else {
            info_.decoded_bytes = size;
        }
        return {};
    }

    // Metadata records: varint tag, varint length, value. Tag 1: patent
    // segmenter statistics; others are skipped (informational).
    Result<void> read_metadata(std::string_view body, std::uint64_t base) {
        Cursor cur(body);
        while (!cur.done()) {
            std::uint64_t tag, len;
            std::string_view value;
            if (!cur.varint(tag) || !cur.varint(len) || len > cur.left() ||
                !cur.bytes(static_cast<std::size_t>(len), value))
                return make_error(Errc::corrupt, at(base + cur.pos()) + ": bad trailer metadata record");
            if (tag != kMetaPatentStats) continue;
            Cursor v(value);
            std::uint64_t n, exact, dev;
            if (!v.varint(n) || !v.varint(exact) || !v.varint(dev) || !v.done() || exact > n ||
                dev > static_cast<std::uint64_t>(INT64_MAX))
                return make_error(Errc::corrupt, at(base + cur.pos()) + ": bad patent statistics");
            info_.stats.patent_segments = n;
            info_.stats.patent_exact = exact;
            info_.stats.patent_max_deviation = static_cast<std::int64_t>(dev);
        }
        return {};
    }

    Source& src_;
    const WriteFn* out_;
    const ProgressFn& progress_;
    FrameHeader hdr_;
    std::string head_;
    std::uint64_t frame_at_ = 0;
    FrameInfo info_;
    Window window_;
    StepHistoryPtr steps_;  // frames with a window on two axes, once a block needs it
    bool steps_frame_ = false;  // a frame with a window on two axes
    // Before steps_: the window's blocks with their decoded chains (their
    // symbols are made only if a block decodes on the history).
    struct Held {
        std::shared_ptr<WindowBlock> contribution;
        Block block;
    };
    std::deque<Held> held_;
    std::vector<Segment> spare_segments_;  // see blocks()
    bool expand_ = false;
    std::unique_ptr<BlockWriter> writer_;
    XXH64_state_t* state_ = nullptr;
    bool chain_open_ = false;
    std::string rec_;
    std::string where_;
};

void add(FrameInfo& total, const FrameInfo& f) {
    ++total.frames;
    total.blocks += f.blocks;
    total.raw_blocks += f.raw_blocks;
    total.segment_model_blocks += f.segment_model_blocks;
    total.step_model_blocks += f.step_model_blocks;
    total.table_blocks += f.table_blocks;
    total.chains += f.chains;
    total.steps += f.steps;
    total.segments += f.segments;
    total.decoded_bytes += f.decoded_bytes;
    total.compressed_bytes += f.compressed_bytes;
    total.stats += f.stats;
}

// Decodes every frame of the stream (`out` null: inspect only).
Result<FrameInfo> decode_stream(const ReadFn& in, const WriteFn* out, std::string_view source_name,
                                const ProgressFn& progress) {
    Source src(in, source_name);
    FrameInfo total;
    std::string head;
    for (bool first = true;; first = false) {
        FrameDecoder frame(src, out, progress);
        auto f = frame.run(std::move(head));
        if (!f) return std::move(f).error();
        if (first) total = *f;
        else add(total, *f);
        // Another frame may follow; anything else after a frame is an error.
        const std::uint64_t end = src.offset();
        head.clear();
        std::size_t got;
        if (auto r = src.read(4, head, got); !r) return std::move(r).error();
        if (got == 0) return total;
        if (got < 4 || std::memcmp(head.data(), kMagic, 4) != 0)
            return make_error(Errc::corrupt, src.name() + ": byte " + std::to_string(end) +
                                                 ": trailing bytes after the frame");
    }
}

}  // namespace

Result<FrameInfo> decompress_stream(const ReadFn& in, const WriteFn& out, std::string_view source,
                                    const ProgressFn& progress) {
    return decode_stream(in, &out, source, progress);
}

Result<FrameInfo> inspect_stream(const ReadFn& in, std::string_view source) {
    return decode_stream(in, nullptr, source, {});
}

Result<std::string> decompress(std::string_view frame, std::string_view source) {
    std::string out;
    auto r = decompress_stream(stz::memory_reader(frame), stz::string_writer(out), source);
    if (!r) return std::move(r).error();
    return out;
}

}  // namespace stepzip
