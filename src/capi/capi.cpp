// The C interface (include/stepzip.h) over the C++ library. Every entry
// point catches everything: no exception crosses into C.
#include "stepzip.h"

#include <algorithm>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <new>
#include <optional>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "stepzip/container.hpp"
#include "stepzip/profile.hpp"
#include "stepzip/segmenter.hpp"
#include "stepzip/streaming.hpp"
#include "stepzip/version.hpp"

struct stepzip_compressor {
    stepzip::CompressOptions options;
    std::string error;
};

struct stepzip_decompressor {
    std::string error;
};

struct stepzip_segmenter {
    stepzip::StreamingSegmenter segmenter;
    std::deque<stepzip::Segment> queue;
    std::vector<stepzip::Segment> scratch;
    std::string error;
};

namespace {

using stepzip::Errc;

enum stepzip_result to_result(Errc code) noexcept {
    return static_cast<enum stepzip_result>(static_cast<int>(code));
}

// Records `e` in `slot` (if any) and returns its code.
enum stepzip_result fail(std::string* slot, const stepzip::Error& e) noexcept {
    if (slot) {
        try {
            *slot = e.message;
        } catch (...) {
            slot->clear();
        }
    }
    return to_result(e.code);
}

enum stepzip_result fail(std::string* slot, enum stepzip_result r, const char* message) noexcept {
    if (slot) {
        try {
            *slot = message;
        } catch (...) {
            slot->clear();
        }
    }
    return r;
}

// Runs `body`, turning exceptions into results.
template <class F>
enum stepzip_result guarded(std::string* slot, F&& body) noexcept {
    try {
        if (slot) slot->clear();
        return body();
    } catch (const std::bad_alloc&) {
        return fail(slot, STEPZIP_NO_MEMORY, "out of memory");
    } catch (const std::exception& e) {
        if (slot) {
            try {
                *slot = std::string("internal error: ") + e.what();
            } catch (...) {
            }
        }
        return STEPZIP_INTERNAL;
    } catch (...) {
        return fail(slot, STEPZIP_INTERNAL, "internal error");
    }
}

bool known_profile(int p) noexcept { return p >= 0 && p <= 4; }

stepzip_segment to_c(const stepzip::Segment& s) noexcept {
    stepzip_segment c{};
    for (int i = 0; i < STEPZIP_MAX_AXES; ++i) c.delta[i] = s.delta[static_cast<std::size_t>(i)];
    for (int i = 0; i < STEPZIP_MAX_AXES - 1; ++i) c.phase[i] = s.phase[static_cast<std::size_t>(i)];
    return c;
}

stepzip::Segment from_c(const stepzip_segment& c) noexcept {
    stepzip::Segment s;
    for (int i = 0; i < STEPZIP_MAX_AXES; ++i) s.delta[static_cast<std::size_t>(i)] = c.delta[i];
    for (int i = 0; i < STEPZIP_MAX_AXES - 1; ++i) s.phase[static_cast<std::size_t>(i)] = c.phase[i];
    return s;
}

// Copies `bytes` out, or reports the size needed.
enum stepzip_result copy_out(const std::string& bytes, void* out, size_t avail,
                             size_t* out_nbytes, std::string* slot) noexcept {
    *out_nbytes = bytes.size();
    if (bytes.size() > avail)
        return fail(slot, STEPZIP_SHORT_BUFFER, "output buffer too small");
    if (!bytes.empty()) std::memcpy(out, bytes.data(), bytes.size());
    return STEPZIP_OK;
}


// Runs a pull-style coder (compress_stream / decompress_stream, which read
// through a ReadFn and write through a WriteFn) on a helper thread and feeds
// it from push-style calls with caller buffers (the *_stream functions).
// The helper touches the caller's input only under the lock and only while a
// call offers it; its output waits in `pending_`, at most about kOutHigh
// bytes beyond one write, until a call has room for it.
class Pump {
public:
    using Coder = std::function<stepzip::Result<stepzip::FrameInfo>(const stepzip::ReadFn&,
                                                                    const stepzip::WriteFn&)>;
    explicit Pump(Coder coder) : coder_(std::move(coder)) {}
    ~Pump() { stop(); }
    Pump(const Pump&) = delete;
    Pump& operator=(const Pump&) = delete;

    enum stepzip_result step(stepzip_out_buffer* out, stepzip_in_buffer* in, bool end,
                             size_t* remaining) {
        if (failed_) return fail(&error, failed_code_, saved_error_.c_str());
        error.clear();
        std::unique_lock lk(m_);
        if (!worker_.joinable()) worker_ = std::thread([this] { run(); });
        in_ = static_cast<const char*>(in->src) + in->pos;
        in_left_ = in->size - in->pos;
        in_taken_ = 0;
        end_ = end;
        offered_ = true;
        if (in_left_ > 0 || end_) need_input_ = false;
        cv_.notify_all();
        for (;;) {
            deliver(out);
            if (finished_ || need_input_ || out->pos == out->size) break;
            cv_.wait(lk);
        }
        in->pos += in_taken_;
        in_ = nullptr;
        in_left_ = 0;
        offered_ = false;
        const std::size_t left = pending_.size() - pending_pos_;
        if (finished_ && failure_) {
            failed_ = true;
            failed_code_ = to_result(failure_->code);
            saved_error_ = failure_->message;
            lk.unlock();
            stop();
            return fail(&error, failed_code_, saved_error_.c_str());
        }
        if (finished_ && left == 0) {
            // The frame is complete and delivered: ready for the next one.
            lk.unlock();
            stop();
            *remaining = 0;
            return STEPZIP_OK;
        }
        *remaining = left > 0 ? left : 1;
        return STEPZIP_OK;
    }

    // Abandons the frame being coded (if any) and clears every state.
    void stop() noexcept {
        {
            std::lock_guard lk(m_);
            cancel_ = true;
            cv_.notify_all();
        }
        if (worker_.joinable()) worker_.join();
        std::lock_guard lk(m_);
        in_ = nullptr;
        in_left_ = in_taken_ = 0;
        end_ = offered_ = cancel_ = need_input_ = need_room_ = finished_ = false;
        failure_.reset();
        pending_.clear();
        pending_pos_ = 0;
    }

    void reset() noexcept {
        stop();
        failed_ = false;
        error.clear();
    }

    std::string error;

private:
    static constexpr std::size_t kOutHigh = std::size_t{1} << 20;

    // Moves pending output into `out` (the lock is held).
    void deliver(stepzip_out_buffer* out) {
        const std::size_t n = std::min(pending_.size() - pending_pos_, out->size - out->pos);
        if (n == 0) return;
        std::memcpy(static_cast<char*>(out->dst) + out->pos, pending_.data() + pending_pos_, n);
        out->pos += n;
        pending_pos_ += n;
        if (pending_pos_ == pending_.size()) {
            pending_.clear();
            pending_pos_ = 0;
        }
        if (pending_.size() - pending_pos_ <= kOutHigh && need_room_) {
            need_room_ = false;
            cv_.notify_all();
        }
    }

    void run() {
        const stepzip::ReadFn read = [this](char* buf, std::size_t cap) -> stepzip::Result<std::size_t> {
            std::unique_lock lk(m_);
            while (!cancel_ && !(offered_ && (in_left_ > 0 || end_))) {
                need_input_ = true;
                cv_.notify_all();
                cv_.wait(lk);
            }
            need_input_ = false;
            if (cancel_) return stepzip::make_error(Errc::io, "stream abandoned");
            const std::size_t n = std::min(cap, in_left_);
            if (n) std::memcpy(buf, in_, n);
            in_ += n;
            in_left_ -= n;
            in_taken_ += n;
            return n;  // 0 only at the end the caller announced
        };
        const stepzip::WriteFn write = [this](std::string_view bytes) -> stepzip::Result<void> {
            std::unique_lock lk(m_);
            pending_.append(bytes);
            cv_.notify_all();
            while (!cancel_ && pending_.size() - pending_pos_ > kOutHigh) {
                need_room_ = true;
                cv_.notify_all();
                cv_.wait(lk);
            }
            need_room_ = false;
            if (cancel_) return stepzip::make_error(Errc::io, "stream abandoned");
            return {};
        };
        std::optional<stepzip::Error> failure;
        try {
            auto r = coder_(read, write);
            if (!r) failure = r.error();
        } catch (const std::bad_alloc&) {
            failure = stepzip::Error{Errc::io, "out of memory"};
        } catch (const std::exception& e) {
            failure = stepzip::Error{Errc::io, std::string("internal error: ") + e.what()};
        }
        std::lock_guard lk(m_);
        finished_ = true;
        failure_ = std::move(failure);
        cv_.notify_all();
    }

    Coder coder_;
    std::mutex m_;
    std::condition_variable cv_;
    std::thread worker_;
    const char* in_ = nullptr;  // the input offered by the running call
    std::size_t in_left_ = 0, in_taken_ = 0;
    bool end_ = false, offered_ = false, cancel_ = false;
    bool need_input_ = false;  // the helper waits for input
    bool need_room_ = false;   // the helper waits for its output to be taken
    bool finished_ = false;    // the coder returned
    std::optional<stepzip::Error> failure_;
    std::string pending_;
    std::size_t pending_pos_ = 0;
    bool failed_ = false;  // sticky error, until reset()
    enum stepzip_result failed_code_ = STEPZIP_OK;
    std::string saved_error_;
};

bool valid_buffers(const stepzip_out_buffer* out, const stepzip_in_buffer* in,
                   const size_t* remaining) noexcept {
    return out && in && remaining && out->pos <= out->size && in->pos <= in->size &&
           (out->dst || out->size == 0) && (in->src || in->size == 0);
}

}  // namespace

struct stepzip_cstream {
    explicit stepzip_cstream(stepzip::CompressOptions o)
        : pump([o](const stepzip::ReadFn& r, const stepzip::WriteFn& w) {
              return stepzip::compress_stream(r, w, o);
          }) {}
    Pump pump;
};

struct stepzip_dstream {
    stepzip_dstream()
        : pump([](const stepzip::ReadFn& r, const stepzip::WriteFn& w) {
              return stepzip::decompress_stream(r, w);
          }) {}
    Pump pump;
};

namespace {
}  // namespace

extern "C" {

const char* stepzip_result_name(enum stepzip_result result) {
    switch (result) {
        case STEPZIP_NO_MEMORY: return "no_memory";
        case STEPZIP_SHORT_BUFFER: return "short_buffer";
        case STEPZIP_INTERNAL: return "internal";
        default: break;
    }
    const int v = static_cast<int>(result);
    static const int known[] = {0, 10, 11, 20, 21, 22, 30, 31, 32, 33, 34, 40, 50, 51, 60, 70};
    if (std::find(std::begin(known), std::end(known), v) == std::end(known)) return "unknown";
    return stepzip::errc_name(static_cast<Errc>(v));
}

const char* stepzip_version_string(void) { return stepzip::version_string(); }

stepzip_step stepzip_freeman_step(int code) {
    if (code < 0 || code > 7) return 0;
    return stepzip::freeman_to_step(code);
}

// ----------------------------------------------------------- compression

stepzip_compressor* stepzip_alloc_compressor(int level, enum stepzip_profile profile,
                                             enum stepzip_segmenter_kind segmenter) {
    if (level < 1 || level > 19) return nullptr;
    if (profile != STEPZIP_PROFILE_AUTO && !known_profile(profile)) return nullptr;
    if (segmenter < STEPZIP_SEGMENTER_DEFAULT || segmenter > STEPZIP_SEGMENTER_PATENT) return nullptr;
    try {
        auto* c = new stepzip_compressor;
        c->options.level = level;
        if (profile != STEPZIP_PROFILE_AUTO) c->options.profile = static_cast<stepzip::Profile>(profile);
        if (segmenter != STEPZIP_SEGMENTER_DEFAULT)
            c->options.segmenter = static_cast<stepzip::SegmenterKind>(segmenter);
        return c;
    } catch (...) {
        return nullptr;
    }
}

enum stepzip_result stepzip_compressor_set_source(stepzip_compressor* c, const char* name) {
    if (!c) return STEPZIP_INVALID_ARGUMENT;
    return guarded(&c->error, [&] {
        if (!name) return fail(&c->error, STEPZIP_INVALID_ARGUMENT, "source name is NULL");
        c->options.source = name;
        return STEPZIP_OK;
    });
}

enum stepzip_result stepzip_compress(stepzip_compressor* c, enum stepzip_format format,
                                     const void* in, size_t in_nbytes, void* out,
                                     size_t out_nbytes_avail, size_t* out_nbytes) {
    if (!c) return STEPZIP_INVALID_ARGUMENT;
    return guarded(&c->error, [&] {
        if ((!in && in_nbytes) || !out_nbytes || (!out && out_nbytes_avail))
            return fail(&c->error, STEPZIP_INVALID_ARGUMENT, "NULL buffer");
        stepzip::CompressOptions opt = c->options;
        if (format != STEPZIP_FORMAT_AUTO) {
            if (format < STEPZIP_FORMAT_FREEMAN || format > STEPZIP_FORMAT_STEPS)
                return fail(&c->error, STEPZIP_INVALID_ARGUMENT, "unknown chain format");
            opt.format = static_cast<stepzip::InputFormat>(format);
        }
        const std::string_view input(static_cast<const char*>(in), in_nbytes);
        auto frame = stepzip::compress(input, opt);
        if (!frame) return fail(&c->error, frame.error());
        return copy_out(*frame, out, out_nbytes_avail, out_nbytes, &c->error);
    });
}

size_t stepzip_compress_bound(size_t in_nbytes) {
    return in_nbytes + in_nbytes / 128 + 4096;
}

enum stepzip_result stepzip_profile_from_name(const char* name, enum stepzip_profile* profile) {
    if (!name || !profile) return STEPZIP_INVALID_ARGUMENT;
    if (std::strcmp(name, "auto") == 0) {
        *profile = STEPZIP_PROFILE_AUTO;
        return STEPZIP_OK;
    }
    const auto p = stepzip::parse_profile(name);
    if (!p) return STEPZIP_INVALID_ARGUMENT;
    *profile = static_cast<enum stepzip_profile>(static_cast<int>(*p));
    return STEPZIP_OK;
}

const char* stepzip_profile_name(enum stepzip_profile profile) {
    if (profile == STEPZIP_PROFILE_AUTO) return "auto";
    if (!known_profile(profile)) return "unknown";
    // profile_name() views a string literal: its data is NUL-terminated.
    return stepzip::profile_name(static_cast<stepzip::Profile>(profile)).data();
}

const char* stepzip_compressor_error(const stepzip_compressor* c) {
    return c ? c->error.c_str() : "";
}

void stepzip_free_compressor(stepzip_compressor* c) { delete c; }

// --------------------------------------------------------- decompression

stepzip_decompressor* stepzip_alloc_decompressor(void) {
    return new (std::nothrow) stepzip_decompressor;
}

enum stepzip_result stepzip_inspect(stepzip_decompressor* d, const void* in, size_t in_nbytes,
                                    stepzip_frame_info* info) {
    if (!d) return STEPZIP_INVALID_ARGUMENT;
    return guarded(&d->error, [&] {
        if ((!in && in_nbytes) || !info)
            return fail(&d->error, STEPZIP_INVALID_ARGUMENT, "NULL buffer");
        std::size_t pos = 0;
        const char* bytes = static_cast<const char*>(in);
        stepzip::ReadFn read = [&](char* buf, std::size_t cap) -> stepzip::Result<std::size_t> {
            const std::size_t n = std::min(cap, in_nbytes - pos);
            if (n) std::memcpy(buf, bytes + pos, n);
            pos += n;
            return n;
        };
        auto r = stepzip::inspect_stream(read);
        if (!r) return fail(&d->error, r.error());
        info->format_version = r->format_version;
        info->profile = static_cast<enum stepzip_profile>(static_cast<int>(r->profile));
        info->format = static_cast<enum stepzip_format>(static_cast<int>(r->format));
        info->axes = r->axes;
        info->chains = r->chains;
        info->steps = r->steps;
        info->segments = r->segments;
        info->decoded_bytes = r->decoded_bytes;
        info->compressed_bytes = r->compressed_bytes;
        return STEPZIP_OK;
    });
}

enum stepzip_result stepzip_decompress(stepzip_decompressor* d, const void* in, size_t in_nbytes,
                                       void* out, size_t out_nbytes_avail, size_t* out_nbytes) {
    if (!d) return STEPZIP_INVALID_ARGUMENT;
    return guarded(&d->error, [&] {
        if ((!in && in_nbytes) || !out_nbytes || (!out && out_nbytes_avail))
            return fail(&d->error, STEPZIP_INVALID_ARGUMENT, "NULL buffer");
        auto r = stepzip::decompress(std::string_view(static_cast<const char*>(in), in_nbytes));
        if (!r) return fail(&d->error, r.error());
        return copy_out(*r, out, out_nbytes_avail, out_nbytes, &d->error);
    });
}

const char* stepzip_decompressor_error(const stepzip_decompressor* d) {
    return d ? d->error.c_str() : "";
}

void stepzip_free_decompressor(stepzip_decompressor* d) { delete d; }

// -------------------------------------------------- reverse interpolation

enum stepzip_result stepzip_segment_steps(enum stepzip_profile profile,
                                          enum stepzip_segmenter_kind segmenter, int axes,
                                          const stepzip_step* steps, size_t nsteps,
                                          stepzip_segment* out, size_t out_capacity,
                                          size_t* nsegments) {
    return guarded(nullptr, [&] {
        if ((!steps && nsteps) || (!out && out_capacity) || !nsegments ||
            !known_profile(profile) || segmenter < STEPZIP_SEGMENTER_DEFAULT ||
            segmenter > STEPZIP_SEGMENTER_PATENT)
            return STEPZIP_INVALID_ARGUMENT;
        const auto kind = segmenter == STEPZIP_SEGMENTER_DEFAULT
                              ? stepzip::SegmenterKind::greedy
                              : static_cast<stepzip::SegmenterKind>(segmenter);
        std::vector<stepzip::Segment> segs;
        auto r = stepzip::segment_steps(std::span<const stepzip::Step>(steps, nsteps), axes,
                                        static_cast<stepzip::Profile>(profile), kind, segs);
        if (!r) return to_result(r.error().code);
        *nsegments = segs.size();
        if (segs.size() > out_capacity) return STEPZIP_SHORT_BUFFER;
        for (std::size_t i = 0; i < segs.size(); ++i) out[i] = to_c(segs[i]);
        return STEPZIP_OK;
    });
}

enum stepzip_result stepzip_expand_segments(enum stepzip_profile profile, int axes,
                                            const stepzip_segment* segments, size_t nsegments,
                                            stepzip_step* out, size_t out_capacity,
                                            size_t* nsteps) {
    return guarded(nullptr, [&] {
        if ((!segments && nsegments) || (!out && out_capacity) || !nsteps ||
            !known_profile(profile))
            return STEPZIP_INVALID_ARGUMENT;
        const auto p = static_cast<stepzip::Profile>(profile);
        std::uint64_t total = 0;
        for (std::size_t i = 0; i < nsegments; ++i) {
            const stepzip::Segment s = from_c(segments[i]);
            if (auto r = stepzip::check_segment(p, s, axes); !r) return to_result(r.error().code);
            total += static_cast<std::uint64_t>(
                stepzip::segment_length(s.delta, axes, stepzip::profile_eight_connected(p)));
        }
        *nsteps = static_cast<size_t>(total);
        if (total > out_capacity) return STEPZIP_SHORT_BUFFER;
        std::vector<stepzip::Step> buf;
        std::size_t at = 0;
        for (std::size_t i = 0; i < nsegments; ++i) {
            buf.clear();
            stepzip::expand_segment(p, from_c(segments[i]), axes, buf);
            std::copy(buf.begin(), buf.end(), out + at);
            at += buf.size();
        }
        return STEPZIP_OK;
    });
}

// ------------------------------------------------- streaming segmentation

stepzip_segmenter* stepzip_alloc_segmenter(enum stepzip_profile profile, int axes,
                                           size_t max_held) {
    if (!known_profile(profile)) return nullptr;
    try {
        auto* s = new stepzip_segmenter{
            stepzip::StreamingSegmenter(static_cast<stepzip::Profile>(profile), axes,
                                        max_held ? max_held : stepzip::kStreamingDefaultHold),
            {}, {}, {}};
        if (!s->segmenter.valid()) {
            delete s;
            return nullptr;
        }
        return s;
    } catch (...) {
        return nullptr;
    }
}

enum stepzip_result stepzip_segmenter_push(stepzip_segmenter* s, const stepzip_step* steps,
                                           size_t nsteps) {
    if (!s) return STEPZIP_INVALID_ARGUMENT;
    return guarded(&s->error, [&] {
        if (!steps && nsteps) return fail(&s->error, STEPZIP_INVALID_ARGUMENT, "NULL steps");
        s->scratch.clear();
        auto r = s->segmenter.push(std::span<const stepzip::Step>(steps, nsteps), s->scratch);
        s->queue.insert(s->queue.end(), s->scratch.begin(), s->scratch.end());
        if (!r) return fail(&s->error, r.error());
        return STEPZIP_OK;
    });
}

enum stepzip_result stepzip_segmenter_finish(stepzip_segmenter* s) {
    if (!s) return STEPZIP_INVALID_ARGUMENT;
    return guarded(&s->error, [&] {
        s->scratch.clear();
        s->segmenter.finish(s->scratch);
        s->queue.insert(s->queue.end(), s->scratch.begin(), s->scratch.end());
        return STEPZIP_OK;
    });
}

size_t stepzip_segmenter_read(stepzip_segmenter* s, stepzip_segment* out, size_t capacity) {
    if (!s || !out) return 0;
    const std::size_t n = std::min(capacity, s->queue.size());
    for (std::size_t i = 0; i < n; ++i) out[i] = to_c(s->queue[i]);
    s->queue.erase(s->queue.begin(), s->queue.begin() + static_cast<std::ptrdiff_t>(n));
    return n;
}

size_t stepzip_segmenter_queued(const stepzip_segmenter* s) { return s ? s->queue.size() : 0; }

size_t stepzip_segmenter_held(const stepzip_segmenter* s) { return s ? s->segmenter.held() : 0; }

const char* stepzip_segmenter_error(const stepzip_segmenter* s) {
    return s ? s->error.c_str() : "";
}

void stepzip_free_segmenter(stepzip_segmenter* s) { delete s; }

// --------------------------------------------- streaming (de)compression

stepzip_cstream* stepzip_alloc_cstream(const stepzip_compressor* settings,
                                       enum stepzip_format format) {
    if (!settings) return nullptr;
    if (format != STEPZIP_FORMAT_AUTO && (format < STEPZIP_FORMAT_FREEMAN || format > STEPZIP_FORMAT_STEPS))
        return nullptr;
    try {
        stepzip::CompressOptions o = settings->options;
        if (format != STEPZIP_FORMAT_AUTO) o.format = static_cast<stepzip::InputFormat>(format);
        return new stepzip_cstream(std::move(o));
    } catch (...) {
        return nullptr;
    }
}

enum stepzip_result stepzip_compress_stream(stepzip_cstream* cs, stepzip_out_buffer* out,
                                            stepzip_in_buffer* in, enum stepzip_end_directive end,
                                            size_t* remaining) {
    if (!cs) return STEPZIP_INVALID_ARGUMENT;
    return guarded(&cs->pump.error, [&] {
        if (!valid_buffers(out, in, remaining))
            return fail(&cs->pump.error, STEPZIP_INVALID_ARGUMENT, "NULL or inconsistent buffer");
        return cs->pump.step(out, in, end == STEPZIP_END, remaining);
    });
}

void stepzip_cstream_reset(stepzip_cstream* cs) {
    if (cs) cs->pump.reset();
}

const char* stepzip_cstream_error(const stepzip_cstream* cs) {
    return cs ? cs->pump.error.c_str() : "";
}

void stepzip_free_cstream(stepzip_cstream* cs) { delete cs; }

stepzip_dstream* stepzip_alloc_dstream(void) {
    try {
        return new stepzip_dstream;
    } catch (...) {
        return nullptr;
    }
}

enum stepzip_result stepzip_decompress_stream(stepzip_dstream* ds, stepzip_out_buffer* out,
                                              stepzip_in_buffer* in, enum stepzip_end_directive end,
                                              size_t* remaining) {
    if (!ds) return STEPZIP_INVALID_ARGUMENT;
    return guarded(&ds->pump.error, [&] {
        if (!valid_buffers(out, in, remaining))
            return fail(&ds->pump.error, STEPZIP_INVALID_ARGUMENT, "NULL or inconsistent buffer");
        return ds->pump.step(out, in, end == STEPZIP_END, remaining);
    });
}

void stepzip_dstream_reset(stepzip_dstream* ds) {
    if (ds) ds->pump.reset();
}

const char* stepzip_dstream_error(const stepzip_dstream* ds) {
    return ds ? ds->pump.error.c_str() : "";
}

void stepzip_free_dstream(stepzip_dstream* ds) { delete ds; }

}  // extern "C"
