// .stz encoder, the frame writer (docs/FORMAT.md): read -> batch ->
// parallel jobs -> ordered write -> trailer. Each block of a batch runs the
// block strategy (block_strategy.cpp): a first pass without the window, then
// the step model and the segment model from the window, then the round-trip
// proof (round_trip.cpp: the record decoded and compared with the block,
// whose rendering was compared with the input bytes when it was parsed);
// the write follows in block order.
// Memory: about (threads + 1) blocks plus the window's content (a window
// block's chains until its step-model symbols are made, then the symbols),
// plus up to kCutCacheBytes of chain cuts (cut_cache.hpp). What a job
// sees depends only on the blocks before it, so -T N output equals -T 1
// output byte for byte.
#include <xxhash.h>

#include <algorithm>
#include <memory>
#include <thread>

#include "block_codec.hpp"
#include "cut_cache.hpp"
#include "../common/bytes.hpp"
#include "encoder.hpp"
#include "memory_io.hpp"
#include "modeled_block.hpp"
#include "timed_tick.hpp"
#include "stepzip/container.hpp"

namespace stepzip {

namespace {

using namespace stz;

// The chain cuts a frame keeps for chains that repeat (cut_cache.hpp).
constexpr std::size_t kCutCacheBytes = std::size_t{8} << 20;

SegmenterKind implied_segmenter(int level) {
    return level >= kOptimalLevel ? SegmenterKind::optimal : SegmenterKind::greedy;
}

// Runs f(i) for i in [0, n) on up to `threads` threads (the calling one
// included).
template <class F>
void parallel_for(std::size_t n, unsigned threads, F f) {
    const std::size_t t = std::min<std::size_t>(threads, n);
    if (t <= 1) {
        for (std::size_t i = 0; i < n; ++i) f(i);
        return;
    }
    std::vector<std::thread> pool;
    for (std::size_t k = 1; k < t; ++k)
        pool.emplace_back([&, k] {
            for (std::size_t i = k; i < n; i += t) f(i);
        });
    for (std::size_t i = 0; i < n; i += t) f(i);
    for (auto& th : pool) th.join();
}

// Version-2 trailer (docs/FORMAT.md 1.7): end mark, decoded size, flags,
// optional metadata (the patent segmenter's statistics), content XXH64.
std::string trailer(const FrameInfo& info, bool patent_stats) {
    std::string end;
    put_u8(end, kEnd);
    put_varint(end, info.decoded_bytes);
    put_u8(end, patent_stats ? 1u : 0u);
    if (patent_stats) {
        std::string value, meta;
        put_varint(value, info.stats.patent_segments);
        put_varint(value, info.stats.patent_exact);
        put_varint(value, static_cast<std::uint64_t>(info.stats.patent_max_deviation));
        put_varint(meta, kMetaPatentStats);
        put_varint(meta, value.size());
        meta += value;
        put_varint(end, meta.size());
        end += meta;
        put_le(end, check32(meta), 4);
    }
    put_le(end, info.checksum, 8);
    return end;
}

}  // namespace

Result<FrameInfo> compress_stream(const ReadFn& in, const WriteFn& out, const CompressOptions& opt,
                                  const ProgressFn& progress) {
    if (opt.level < 1 || opt.level > 19)
        return make_error(Errc::invalid_argument, "level must be 1..19, got " + std::to_string(opt.level));
    if (opt.block_steps && (*opt.block_steps == 0 || *opt.block_steps > kMaxBlockSteps))
        return make_error(Errc::invalid_argument, "block size must be 1..2^24 steps");
    unsigned threads = opt.threads == 0 ? std::max(1u, std::thread::hardware_concurrency()) : opt.threads;
    threads = std::min(threads, 256u);

    if (opt.window_log && (*opt.window_log < 0 || *opt.window_log > kMaxWindowLog))
        return make_error(Errc::invalid_argument, "window log must be 0.." + std::to_string(kMaxWindowLog));

    EncoderSettings s;
    s.profile = opt.profile.value_or(Profile::eval8);
    s.profile_named = opt.profile.has_value();
    s.segmenter = opt.segmenter.value_or(implied_segmenter(opt.level));
    s.segmenter_named = opt.segmenter.has_value();
    s.level = opt.level;
    s.source = opt.source;
    s.allow_raw = opt.allow_raw;
    s.thorough = opt.level >= kThoroughLevel;
    s.window_log = opt.window_log.value_or(window_log_for_level(opt.level));
    s.arc_method = opt.arc_method;
    CutCache cut_cache(kCutCacheBytes);
    s.cut_cache = &cut_cache;

    FrameInfo info;
    info.segmenter = s.segmenter;
    std::optional<BlockReader> reader;
    std::optional<InputFormat> format = opt.format;
    std::unique_ptr<BlockWriter> render;

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
        if (first)
            if (auto r = choose_frame_settings(*first, s); !r) return r;
        FrameHeader h;
        h.profile = s.profile;
        h.format = *format;
        h.axes = s.axes;
        h.segmenter = s.segmenter;
        h.window_log = s.window_log;
        header = write_frame_header(h);
        header_written = true;
        info.profile = s.profile;
        info.format = *format;
        info.axes = s.axes;
        info.segmenter = s.segmenter;  // (choose_frame_settings() may have changed it)
        info.window = h.window();
        return out(header);
    };

    Window window(s.window_log == 0 ? 0 : std::uint64_t{1} << s.window_log);
    // Chain blocks in the window whose step-model symbols are not made yet:
    // they are made only when a block's second pass may read them (at the
    // fast levels a frame of table blocks never does). Until then the
    // block's chains are kept (2 bytes a step where the symbols take 1; a
    // table block's with its contribution, see the end of flush_batch).
    struct PendingSymbols {
        std::shared_ptr<WindowBlock> w;
        Block* block;                  // the job's block, then `kept`
        std::unique_ptr<Block> kept;   // after the block's batch
    };
    std::vector<PendingSymbols> pending_symbols;
    // The frame's step history (docs/FORMAT.md 1.8): the symbols of the
    // window's blocks before the batch, made when a batch first wants them.
    // The second pass's step coders and the proof stack their own history
    // on it (StepHistory::stack_on()) instead of adding their whole window
    // again: each block's symbols are added once, not once per block that
    // sees it. Only read while the batch's jobs run.
    StepHistoryPtr frame_steps;
    std::vector<std::weak_ptr<WindowBlock>> unsynced;  // window blocks not in it yet, in order
    auto sync_frame_steps = [&](const WindowView& before) {
        if (!frame_steps) frame_steps = make_step_history();
        for (const std::weak_ptr<WindowBlock>& u : unsynced) {
            const std::shared_ptr<WindowBlock> b = u.lock();
            // (a block out of the window before it was needed is never added)
            if (!b || std::none_of(before.begin(), before.end(), [&](const auto& v) { return v.get() == b.get(); }))
                continue;
            b->first_symbol = step_history_end(*frame_steps);
            step_history_add(*frame_steps, *b);
            b->history = frame_steps.get();
        }
        unsynced.clear();
        if (!before.empty()) step_history_begin_block(*frame_steps, before.front()->first_symbol, window.limit());
    };
    std::vector<BlockJob> batch;
    std::uint64_t next_chain = 0;
    bool chain_open = false;
    auto flush_batch = [&]() -> Result<void> {
        if (batch.empty()) return {};
        // The window each job starts from: the blocks before it (a block's
        // weight does not depend on its type). What a block adds is fixed
        // in steps, so that no job waits for the choices of the jobs before
        // it: a timed frame's ticks before pass 1 (which reads them; a
        // block that becomes a raw one drops them after it), its symbols by
        // pass 1, its segment items by pass 2.
        std::vector<WindowView> views(batch.size());
        for (std::size_t i = 0; i < batch.size(); ++i) {
            begin_contribution(batch[i], s);
            views[i] = window.view();
            batch[i].window = &views[i];
            if (batch[i].contribution) window.push(batch[i].contribution);
        }
        // Pass 1: block types and contributions, without the window (but
        // the ticks).
        parallel_for(batch.size(), threads, [&](std::size_t i) { choose_block(batch[i], s); });
        for (BlockJob& j : batch)
            if (j.error.code != Errc::ok) return std::move(j.error);
        for (BlockJob& j : batch) {
            end_contribution(j);
            j.window = nullptr;
            if (j.contribution && j.type != kRaw) pending_symbols.push_back({j.contribution, &j.block, nullptr});
        }
        // Blocks the window no longer holds never need their symbols.
        std::erase_if(pending_symbols, [](const PendingSymbols& p) { return p.w.use_count() == 1; });
        bool symbols_wanted = false;
        for (std::size_t i = 0; i < batch.size() && !symbols_wanted; ++i)
            symbols_wanted = wants_window_steps(batch[i], s, views[i]);
        if (symbols_wanted) {
            for (PendingSymbols& p : pending_symbols) add_steps_lent(*p.w, *p.block);
            pending_symbols.clear();
            sync_frame_steps(views[0]);
        }
        for (BlockJob& j : batch)
            if (j.contribution) unsynced.push_back(j.contribution);
        std::erase_if(unsynced, [](const std::weak_ptr<WindowBlock>& u) { return u.expired(); });
        // Pass 2: the step model from the window (final block types).
        parallel_for(batch.size(), threads, [&](std::size_t i) {
            window_step_pass(batch[i], s, views[i]);
            note_items(batch[i]);
        });
        // Pass 3: the segment model from the window; the round-trip proof.
        parallel_for(batch.size(), threads, [&](std::size_t i) {
            window_segment_pass(batch[i], s, views[i]);
            prove_decoded(batch[i], s, views[i]);
        });
        for (BlockJob& j : batch) {
            if (j.error.code != Errc::ok) return std::move(j.error);
            if (j.type != kRaw) {
                info.segments += j.counts.segments;
                info.stats += j.stats;
            } else {
                ++info.raw_blocks;
            }
            if (j.type == kSegmentModel) ++info.segment_model_blocks;
            if (j.type == kStepModel) ++info.step_model_blocks;
            if (j.type == kTable) ++info.table_blocks;
            if (j.type == kExtended || j.type == kTickBlock) ++info.timed_blocks;
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
        // A table block's chains stay with its contribution, as the decoder
        // keeps them: the proof of a later table block copies whole chains
        // from them as the decoder does.
        for (BlockJob& j : batch)
            if (j.type == kTable && j.contribution) j.contribution->chains = std::move(j.block.chains);
        for (PendingSymbols& p : pending_symbols)
            if (!p.kept) {
                p.kept = std::make_unique<Block>();
                p.kept->axes = p.block->axes;  // a job of this batch, written
                p.kept->chains = std::move(p.block->chains);
                p.block = p.kept.get();
            }
        batch.clear();
        return {};
    };

    auto take_blocks = [&]() -> Result<void> {
        Block block;
        while (reader->next(block)) {
            if (block.chains.empty() && block.layout.empty()) continue;  // nothing to write (empty input)
            BlockJob job;
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
                                             "freeman|points|steps|timed)");
        }
        if (!reader) {
            s.timed = *format == InputFormat::timed;
            // A timed frame's window holds one block of the default 2^22
            // ticks (its weight is its ticks + chains): the tick blocks'
            // match reads the block before (docs/FORMAT.md 1.8 "Ticks").
            if (s.timed && !opt.window_log) {
                s.window_log = kMaxWindowLog;
                window = Window(std::uint64_t{1} << s.window_log);
            }
            reader.emplace(*format, s.source, opt.block_steps.value_or(s.timed ? kDefaultTimedBlockTicks : kDefaultBlockSteps));
            render = std::make_unique<BlockWriter>(*format);
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
    info.checksum = XXH64_digest(state);
    const std::string end = trailer(info, s.segmenter == SegmenterKind::patent);
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
