// Entry points of reverse interpolation. See segmenter.hpp.
#include "stepzip/segmenter.hpp"

#include <string>

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
    // In pieces of a fixed length, so that the compiler vectorizes the
    // inner loop at -O2 too.
    const unsigned past = axes < kMaxAxes ? ~0u << (2 * axes) : ~0u << (2 * kMaxAxes);
    const unsigned four = eight ? 0u : 1u;
    auto check = [&](unsigned s) {
        const unsigned moves = s & 0x555u;
        return (s & past) | ((s >> 1) & ~s & 0x555u) | static_cast<unsigned>(moves == 0) |
               (four & static_cast<unsigned>((moves & (moves - 1)) != 0));
    };
    constexpr std::size_t kPiece = 64;
    const Step* st = steps.data();
    const std::size_t n = steps.size();
    unsigned bad = 0;
    std::size_t i = 0;
    for (; n - i >= kPiece && bad == 0; i += kPiece)
        for (std::size_t j = 0; j < kPiece; ++j) bad |= check(st[i + j]);
    for (; i < n; ++i) bad |= check(st[i]);
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
    switch (kind) {
        case SegmenterKind::greedy: GreedySegmenter(p, axes).run(steps, out); return {};
        case SegmenterKind::optimal: OptimalSegmenter(p, axes).run(steps, out); return {};
        case SegmenterKind::patent: return PatentSegmenter(p, axes).run(steps, out, stats);
    }
    return make_error(Errc::invalid_argument, "unknown segmenter");
}

}  // namespace stepzip
