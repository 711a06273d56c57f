// Streaming greedy segmenter. See streaming.hpp.
//
// The held steps are read into the profile's recognizer (make_recognizer():
// a SegmentRecognizer, or the PatentRecognizer), which knows the longest
// exact prefix of what it read; when a held step cannot extend the segment
// (a hard limit, or no longer segment can be exact) that prefix is final, it
// is emitted and the steps after it are read again into a fresh recognizer,
// exactly as the batch greedy segmenter restarts after its cut.
#include "stepzip/streaming.hpp"

#include <algorithm>
#include <string>
#include <variant>

#include "internal.hpp"
#include "stepzip/segment/recognizer.hpp"

namespace stepzip {

StreamingSegmenter::StreamingSegmenter(Profile p, int axes, std::size_t max_held)
    : profile_(p), axes_(axes), max_held_(max_held) {
    if (valid()) rec_ = make_recognizer(p, axes);
}

bool StreamingSegmenter::valid() const noexcept {
    return axes_ >= 2 && axes_ <= profile_max_axes(profile_) && max_held_ >= 1;
}

Result<void> StreamingSegmenter::push(Step s, std::vector<Segment>& out) {
    if (!valid())
        return make_error(Errc::invalid_argument,
                          "streaming segmenter: profile " + std::string(profile_name(profile_)) +
                              " with " + std::to_string(axes_) + " axes and a bound of " +
                              std::to_string(max_held_) + " held steps is not usable");
    if (!step_valid(s, axes_))
        return make_error(Errc::invalid_argument, "step " + std::to_string(pushed_ + 1) +
                                                      " is not a valid step on " +
                                                      std::to_string(axes_) + " axes");
    if (!profile_eight_connected(profile_) && step_weight(s) != 1)
        return make_error(Errc::connectivity,
                          "step " + std::to_string(pushed_ + 1) + " moves " +
                              std::to_string(step_weight(s)) + " axes; profile " +
                              std::string(profile_name(profile_)) + " is 4-connected");
    held_.push_back(s);
    ++pushed_;
    drain(out, false);
    while (held_.size() > max_held_) {
        ++forced_;
        cut(out);
        drain(out, false);
    }
    return {};
}

Result<void> StreamingSegmenter::push(std::span<const Step> steps, std::vector<Segment>& out) {
    for (Step s : steps)
        if (auto r = push(s, out); !r) return r;
    return {};
}

void StreamingSegmenter::finish(std::vector<Segment>& out) {
    if (valid()) drain(out, true);
    held_.clear();
    restart();
    pushed_ = forced_ = 0;
}

void StreamingSegmenter::drain(std::vector<Segment>& out, bool flush) {
    for (;;) {
        std::visit(
            [&](auto& rec) {
                while (!broken_ && scanned_ < held_.size()) {
                    const Step s = held_[scanned_];
                    if (!rec.can_extend(s)) {
                        broken_ = true;
                        break;
                    }
                    const bool alive = rec.extend(s);
                    ++scanned_;
                    if (!alive) broken_ = true;
                }
            },
            *rec_);
        if (held_.empty() || !(broken_ || flush)) return;
        cut(out);
    }
}

void StreamingSegmenter::cut(std::vector<Segment>& out) {
    const std::span<const Step> held(held_);
    auto m = static_cast<std::size_t>(
        std::max<std::int64_t>(std::visit([](const auto& rec) { return rec.longest_valid(); }, *rec_), 1));
    auto seg = fit_segment(profile_, held.first(m), axes_);
    // As in the batch greedy: never reached when the recognizer is right; a
    // shorter cut keeps the output exact, and one step always fits.
    if (!seg) count_segmenter_fallback();
    while (!seg && m > 1) seg = fit_segment(profile_, held.first(--m), axes_);
    out.push_back(*seg);
    held_.erase(held_.begin(), held_.begin() + static_cast<std::ptrdiff_t>(m));
    restart();
}

void StreamingSegmenter::restart() noexcept {
    if (rec_) std::visit([](auto& rec) { rec.reset(); }, *rec_);
    scanned_ = 0;
    broken_ = false;
}

}  // namespace stepzip
