// Streaming greedy segmenter. See streaming.hpp.
//
// Linear profiles: the held steps are read into one SegmentRecognizer, which
// records the longest exact prefix; when a held step cannot extend the
// segment (a hard limit, or the word is no longer a digital straight
// segment) that prefix is final, it is emitted and the steps after it are
// read again into a fresh recognizer, exactly as the batch greedy segmenter
// restarts after its cut. `patent` profile: the batch greedy's candidates
// are bounded by the reach (same signs, at most kPatentMaxSegment steps), so
// a segment is final once a held step lies beyond the reach.
#include "stepzip/streaming.hpp"

#include <algorithm>
#include <string>

#include "internal.hpp"
#include "stepzip/segment/segmenters.hpp"

namespace stepzip {

StreamingSegmenter::StreamingSegmenter(Profile p, int axes, std::size_t max_held)
    : profile_(p), axes_(axes), max_held_(max_held) {
    if (p != Profile::patent && valid()) rec_.emplace(p, axes);
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
    if (rec_) rec_->reset();
    scanned_ = best_ = 0;
    broken_ = false;
    patent_sx_ = patent_sy_ = 0;
    pushed_ = forced_ = 0;
}

void StreamingSegmenter::drain(std::vector<Segment>& out, bool flush) {
    for (;;) {
        if (rec_) {
            while (!broken_ && scanned_ < held_.size()) {
                const Step s = held_[scanned_];
                if (!rec_->can_extend(s)) {
                    broken_ = true;
                    break;
                }
                const bool alive = rec_->extend(s);
                ++scanned_;
                if (rec_->valid()) best_ = scanned_;
                if (!alive) broken_ = true;
            }
        } else {
            while (!broken_ && scanned_ < held_.size()) {
                const Step s = held_[scanned_];
                const int dx = step_axis(s, 0), dy = step_axis(s, 1);
                if ((dx != 0 && patent_sx_ != 0 && dx != patent_sx_) ||
                    (dy != 0 && patent_sy_ != 0 && dy != patent_sy_)) {
                    broken_ = true;
                    break;
                }
                if (dx != 0) patent_sx_ = dx;
                if (dy != 0) patent_sy_ = dy;
                if (++scanned_ >= static_cast<std::size_t>(kPatentMaxSegment)) broken_ = true;
            }
        }
        if (held_.empty() || !(broken_ || flush)) return;
        cut(out);
    }
}

void StreamingSegmenter::cut(std::vector<Segment>& out) {
    const std::span<const Step> held(held_);
    std::size_t m;
    if (rec_)
        m = std::max<std::size_t>(best_, 1);
    else
        m = static_cast<std::size_t>(GreedySegmenter(profile_, axes_).longest(held));
    auto seg = fit_segment(profile_, held.first(m), axes_);
    // As in the batch greedy: never reached when the recognizer is right; a
    // shorter cut keeps the output exact, and one step always fits.
    if (!seg) count_segmenter_fallback();
    while (!seg && m > 1) seg = fit_segment(profile_, held.first(--m), axes_);
    out.push_back(*seg);
    held_.erase(held_.begin(), held_.begin() + static_cast<std::ptrdiff_t>(m));
    if (rec_) rec_->reset();
    scanned_ = best_ = 0;
    broken_ = false;
    patent_sx_ = patent_sy_ = 0;
}

}  // namespace stepzip
