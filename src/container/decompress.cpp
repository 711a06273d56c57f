// .stz decoder: frame header, blocks (chain payloads are expanded by forward
// interpolation and rendered by the BlockWriter), trailer (docs/FORMAT.md).
// Memory: one block at a time; no declared size drives an allocation before
// it is checked against the limits in container.hpp.
#include <xxhash.h>

#include <memory>

#include "block_codec.hpp"
#include "modeled_block.hpp"
#include "../common/bytes.hpp"
#include "memory_io.hpp"
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

// Decodes one frame; `render` false = inspect only (no expansion, no output).
Result<FrameInfo> decode_frame(const ReadFn& in, const WriteFn* out, std::string_view source_name,
                               const ProgressFn& progress) {
    Source src(in, source_name);
    std::string head;
    std::size_t got;
    if (auto r = src.read(kFrameHeaderSize, head, got); !r) return std::move(r).error();
    auto hdr = parse_frame_header(head, src.name());
    if (!hdr) return std::move(hdr).error();
    FrameInfo info;
    info.profile = hdr->profile;
    info.format = hdr->format;
    info.axes = hdr->axes;
    info.segmenter = hdr->segmenter;
    const bool render = out != nullptr;
    std::unique_ptr<BlockWriter> writer;
    if (render) writer = std::make_unique<BlockWriter>(hdr->format);
    XXH64_state_t* state = XXH64_createState();
    std::unique_ptr<XXH64_state_t, decltype(&XXH64_freeState)> guard(state, XXH64_freeState);
    XXH64_reset(state, 0);
    bool chain_open = false;
    std::string rec, rendered;
    for (;;) {
        const std::uint64_t block_at = src.offset();
        rec.clear();
        if (auto r = src.read(1, rec, got); !r) return std::move(r).error();
        if (got < 1) return truncated(src, "frame: no end mark");
        const unsigned type = static_cast<unsigned char>(rec[0]);
        const std::string at = src.name() + ": byte " + std::to_string(block_at);
        if (type == kEnd) break;
        if (type != kChains && type != kRaw && type != kSegmentModel && type != kStepModel)
            return make_error(Errc::corrupt, at + ": unknown block type " + std::to_string(type));
        if (auto r = src.read(kBlockHeaderSize - 1, rec, got); !r) return std::move(r).error();
        if (got < kBlockHeaderSize - 1) return truncated(src, "block header");
        const unsigned flags = static_cast<unsigned char>(rec[1]);
        const std::uint64_t csize = get_le(rec.data() + 2, 4);
        const std::uint64_t dsize = get_le(rec.data() + 6, 4);
        if ((flags & ~3u) != 0)
            return make_error(Errc::reserved_bits, src.name() + ": byte " +
                                                       std::to_string(block_at + 1) +
                                                       ": reserved block flags are set");
        const std::uint64_t dlimit = type == kRaw ? kMaxBlockBytes + 20 : kMaxBlockPayload;
        if (csize > kMaxBlockPayload || dsize > dlimit)
            return make_error(Errc::limit, src.name() + ": byte " + std::to_string(block_at + 2) +
                                               ": block sizes exceed the decoder limits");
        const bool stored = type == kSegmentModel || type == kStepModel;
        if (stored && dsize != csize)
            return make_error(Errc::corrupt, src.name() + ": byte " + std::to_string(block_at + 6) +
                                                 ": decoded size of a modeled block differs from its size");
        if (auto r = src.read(static_cast<std::size_t>(csize) + kBlockChecksumSize, rec, got); !r)
            return std::move(r).error();
        if (got < csize + kBlockChecksumSize) return truncated(src, "block");
        const std::string_view body(rec.data(), kBlockHeaderSize + csize);
        if (check32(body) != get_le(rec.data() + body.size(), 4))
            return make_error(Errc::checksum, src.name() + ": byte " +
                                                  std::to_string(block_at + body.size()) +
                                                  ": block checksum mismatch");
        const std::string where = at + " (block " + std::to_string(info.blocks) + ")";
        Result<std::string> raw = std::string();
        if (!stored) raw = unzstd(body.substr(kBlockHeaderSize), static_cast<std::uint32_t>(dsize), where);
        if (!raw) return std::move(raw).error();
        ++info.blocks;
        rendered.clear();
        if (type == kRaw) {
            ++info.raw_blocks;
            Cursor cur(*raw);
            std::uint64_t nchains, nsteps;
            if (!cur.varint(nchains) || !cur.varint(nsteps))
                return make_error(Errc::corrupt, where + ": bad raw block counts");
            info.chains += nchains;
            if ((flags & kFlagContinues) && chain_open && nchains > 0) --info.chains;
            chain_open = flags & kFlagOpen;
            info.steps += nsteps;
            info.decoded_bytes += cur.left();
            if (render) rendered.assign(*raw, cur.pos());
        } else {
            Block block;
            block.continues = flags & kFlagContinues;
            block.open = flags & kFlagOpen;
            BlockCounts counts;
            const std::string_view payload = body.substr(kBlockHeaderSize);
            Result<void> r =
                type == kChains ? read_chain_payload(*raw, hdr->profile, hdr->axes, render, block,
                                                     counts, where + " payload")
                : type == kSegmentModel
                    ? read_segment_model(payload, hdr->profile, hdr->axes, render, block, counts,
                                         where + " payload")
                    : read_step_model(payload, hdr->axes, render, block, counts, where + " payload");
            if (!r) return std::move(r).error();
            if (type == kSegmentModel) ++info.segment_model_blocks;
            if (type == kStepModel) ++info.step_model_blocks;
            info.segments += counts.segments;
            info.steps += counts.steps;
            info.chains += counts.chains;
            if (block.continues && chain_open && counts.chains > 0) --info.chains;
            chain_open = block.open;
            if (render) {
                if (auto r = writer->write(block, rendered); !r)
                    return make_error(r.error().code, where + ": " + r.error().message);
                info.decoded_bytes += rendered.size();
            }
        }
        if (render) {
            XXH64_update(state, rendered.data(), rendered.size());
            if (auto r = (*out)(rendered); !r) return std::move(r).error();
        }
        if (progress) progress(src.offset());
    }
    const std::uint64_t end_at = src.offset() - 1;
    if (auto r = src.read(kTrailerSize, rec, got); !r) return std::move(r).error();
    if (got < kTrailerSize) return truncated(src, "frame trailer");
    // rec = end mark + trailer
    const std::string_view t(rec.data() + 1, kTrailerSize);
    const std::uint64_t size = get_le(t.data(), 8);
    std::string checked = head;
    checked.append(rec, 0, 1 + 32);
    if (check32(checked) != get_le(t.data() + 32, 4))
        return make_error(Errc::checksum, src.name() + ": byte " + std::to_string(end_at + 33) +
                                              ": frame trailer checksum mismatch");
    info.stats.patent_segments = get_le(t.data() + 8, 8);
    info.stats.patent_exact = get_le(t.data() + 16, 8);
    info.stats.patent_max_deviation = static_cast<std::int64_t>(get_le(t.data() + 24, 8));
    info.checksum = get_le(t.data() + 36, 8);
    if (render) {
        if (size != info.decoded_bytes)
            return make_error(Errc::corrupt, src.name() + ": byte " + std::to_string(end_at + 1) +
                                                 ": decoded size " +
                                                 std::to_string(info.decoded_bytes) +
                                                 " differs from the recorded " + std::to_string(size));
        if (XXH64_digest(state) != info.checksum)
            return make_error(Errc::checksum, src.name() + ": byte " + std::to_string(end_at + 37) +
                                                  ": content checksum mismatch (decoded bytes "
                                                  "differ from the original)");
    } else {
        info.decoded_bytes = size;
    }
    auto end = src.at_end();
    if (!end) return std::move(end).error();
    if (!*end)
        return make_error(Errc::corrupt, src.name() + ": byte " + std::to_string(src.offset()) +
                                             ": trailing bytes after the frame");
    info.compressed_bytes = src.offset();
    return info;
}

}  // namespace

Result<FrameInfo> decompress_stream(const ReadFn& in, const WriteFn& out, std::string_view source,
                                    const ProgressFn& progress) {
    return decode_frame(in, &out, source, progress);
}

Result<FrameInfo> inspect_stream(const ReadFn& in, std::string_view source) {
    return decode_frame(in, nullptr, source, {});
}

Result<std::string> decompress(std::string_view frame, std::string_view source) {
    std::string out;
    auto r = decompress_stream(stz::memory_reader(frame), stz::string_writer(out), source);
    if (!r) return std::move(r).error();
    return out;
}

}  // namespace stepzip
