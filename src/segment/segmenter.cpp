// Entry points of reverse interpolation. See segmenter.hpp.
#include "stepzip/segmenter.hpp"

#include <algorithm>
#include <string>

#include "accepted_cut.hpp"
#include "stepzip/segment/segmenters.hpp"

namespace stepzip {

std::string_view segmenter_name(SegmenterKind k) noexcept {
    switch (k) {
        case SegmenterKind::greedy: return "greedy";
        case SegmenterKind::optimal: return "optimal";
        case SegmenterKind::patent: return "patent";
    }
    return "?";
}

std::optional<SegmenterKind> parse_segmenter(std::string_view name) noexcept {
    for (auto k : {SegmenterKind::greedy, SegmenterKind::optimal, SegmenterKind::patent})
        if (segmenter_name(k) == name) return k;
    return std::nullopt;
}

Result<void> profile_accepts(Profile p, std::span<const Step> steps, int axes) {
    if (axes < 2 || axes > profile_max_axes(p))
        return make_error(Errc::invalid_argument, "profile " + std::string(profile_name(p)) +
                                                      " does not take " + std::to_string(axes) +
                                                      " axes");
    const bool eight = profile_eight_connected(p);
    // Fast check, branch-free per step: no bit past the axes, no DIR bit on
    // a resting axis, some axis moving, one moving axis when 4-connected.
    // The loop below names the first offending step.
    // In 16-bit lanes and pieces of a fixed length, so that the compiler
    // vectorizes the inner loop at -O2 too; a chain's last piece overlaps
    // the one before it (short chains are the common case on contours).
    const auto past = static_cast<std::uint16_t>(0xFFFFu << (2 * std::min(axes, kMaxAxes)));
    const std::uint16_t four = eight ? 0 : 0xFFFF;
    auto check = [&](std::uint16_t s) -> std::uint16_t {
        const auto moves = static_cast<std::uint16_t>(s & 0x555u);
        const auto multi = static_cast<std::uint16_t>(moves & (moves - 1u));
        return static_cast<std::uint16_t>((s & past) | ((s >> 1) & ~s & 0x555u) | (moves == 0 ? 0xFFFFu : 0u) |
                                          (multi != 0 ? four : 0u));
    };
    constexpr std::size_t kPiece = 16;
    const Step* st = steps.data();
    const std::size_t n = steps.size();
    std::uint16_t bad = 0;
    auto piece = [&](const Step* at) {
        std::uint16_t b = 0;
        for (std::size_t j = 0; j < kPiece; ++j) b |= check(at[j]);
        return b;
    };
    std::size_t i = 0;
    for (; n - i >= kPiece && bad == 0; i += kPiece) bad |= piece(st + i);
    if (i < n && bad == 0) {
        if (n >= kPiece) bad |= piece(st + n - kPiece);
        else
            for (; i < n; ++i) bad |= check(st[i]);
    }
    if (bad == 0) return {};
    for (std::size_t i = 0; i < steps.size(); ++i) {
        if (!step_valid(steps[i], axes))
            return make_error(Errc::invalid_argument,
                              "step " + std::to_string(i + 1) + " is not a valid step on " +
                                  std::to_string(axes) + " axes");
        if (!eight && step_weight(steps[i]) != 1)
            return make_error(Errc::connectivity,
                              "step " + std::to_string(i + 1) + " moves " +
                                  std::to_string(step_weight(steps[i])) + " axes; profile " +
                                  std::string(profile_name(p)) + " is 4-connected");
    }
    return {};
}

Result<void> segment_steps(std::span<const Step> steps, int axes, Profile p, SegmenterKind kind,
                           std::vector<Segment>& out, SegmentStats* stats) {
    if (auto r = profile_accepts(p, steps, axes); !r) return r;
    return segment_accepted_steps(steps, axes, p, kind, out, stats);
}

Result<void> segment_accepted_steps(std::span<const Step> steps, int axes, Profile p, SegmenterKind kind,
                                    std::vector<Segment>& out, SegmentStats* stats) {
    switch (kind) {
        case SegmenterKind::greedy: GreedySegmenter(p, axes).run(steps, out); return {};
        case SegmenterKind::optimal: OptimalSegmenter(p, axes).run(steps, out); return {};
        case SegmenterKind::patent: return PatentSegmenter(p, axes).run(steps, out, stats);
    }
    return make_error(Errc::invalid_argument, "unknown segmenter");
}

}  // namespace stepzip
