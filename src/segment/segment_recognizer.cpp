// One segment grown tick by tick under a linear profile. See recognizer.hpp.
#include <cassert>
#include <cstdlib>

#include "stepzip/segment/recognizer.hpp"

namespace stepzip {

SegmentRecognizer::SegmentRecognizer(Profile p, int axes)
    : profile_(p), axes_(axes), eight_(profile_eight_connected(p)) {
    assert(p != Profile::patent);
    assert(axes >= 2 && axes <= profile_max_axes(p));
}

void SegmentRecognizer::reset() noexcept {
    length_ = best_ = 0;
    delta_ = {};
    for (int i = 0; i < kMaxAxes; ++i) {
        sign_[i] = 0;
        words_[i].reset();
    }
    always_ = 0;
}

bool SegmentRecognizer::can_extend(Step s) const noexcept {
    if (length_ >= kMaxSegmentTotal) return false;
    unsigned moving = 0;
    for (int i = 0; i < axes_; ++i) {
        const int d = step_axis(s, i);
        if (d == 0) continue;
        if (sign_[i] != 0 && sign_[i] != d) return false;
        moving |= 1u << i;
    }
    if (eight_) {
        if (length_ > 0 && (always_ & moving) == 0) return false;
        for (int i = 0; i < axes_; ++i)
            if (!words_[i].alive()) return false;
    } else {
        if (!words_[0].alive()) return false;
    }
    return true;
}

bool SegmentRecognizer::extend(Step s) {
    unsigned moving = 0;
    for (int i = 0; i < axes_; ++i) {
        const int d = step_axis(s, i);
        if (d == 0) continue;
        sign_[i] = d;
        delta_[i] += d;
        moving |= 1u << i;
    }
    always_ = length_ == 0 ? moving : (always_ & moving);
    ++length_;
    bool alive = true;
    if (eight_) {
        for (int i = 0; i < axes_; ++i)
            alive = words_[i].extend((moving >> i) & 1u) && alive;
    } else {
        alive = words_[0].extend(step_axis(s, 0) != 0 ? 0 : 1);
    }
    if (valid()) best_ = length_;
    return alive;
}

bool SegmentRecognizer::valid() const noexcept {
    if (length_ == 0) return false;
    if (!eight_) return words_[0].valid();
    if (always_ == 0) return false;
    for (int i = 0; i < axes_; ++i)
        if (!words_[i].valid()) return false;
    return true;
}

ProfileRecognizer make_recognizer(Profile p, int axes) {
    if (p == Profile::patent) return PatentRecognizer{};
    return SegmentRecognizer(p, axes);
}

}  // namespace stepzip
