// stepzip — forward interpolation of a vector drawing (what `stepzip
// interpolate` does): one chain per pen-down path.
#include <algorithm>
#include <string>

#include "stepzip/vectors.hpp"

namespace stepzip {

namespace {

std::string move_place(const std::string& source, const VectorMove& m) {
    if (m.line == 0) return source;
    return source + ":" + std::to_string(m.line) + ":" + std::to_string(m.column);
}

}  // namespace

Result<std::vector<Chain>> interpolate_drawing(const Drawing& drawing,
                                               const DrawingInterpolation& options,
                                               std::vector<int>* pens) {
    const Profile profile = options.profile;
    const ArcMethod arc_method = options.arc_method.value_or(
        profile_eight_connected(profile) ? ArcMethod::accelerated : ArcMethod::evaluation);
    std::vector<Chain> chains;
    if (pens) pens->clear();
    std::size_t total = 0;
    auto fail = [&](const VectorMove& m, const Error& e) {
        return make_error(e.code, move_place(options.source, m) + ": " + e.message);
    };
    for (const VectorPath& path : drawing) {
        Chain chain;
        chain.axes = 2;
        chain.start = {path.x0, path.y0};
        std::int64_t x = path.x0, y = path.y0;
        for (const VectorMove& m : path.moves) {
            const std::size_t before = chain.steps.size();
            if (m.kind == MoveKind::line) {
                if (options.line_method) {
                    auto r = interpolate_line(*options.line_method, m.x - x, m.y - y, chain.steps);
                    if (!r) return fail(m, r.error());
                } else {
                    const Segment seg = default_segment(profile, Point{m.x - x, m.y - y}, 2);
                    if (auto r = check_segment(profile, seg, 2); !r) return fail(m, r.error());
                    const auto n = static_cast<std::size_t>(
                        segment_length(seg.delta, 2, profile_eight_connected(profile)));
                    if (total + n > options.max_steps)
                        return fail(m, make_error(Errc::limit, "output would exceed " +
                                                                   std::to_string(options.max_steps) +
                                                                   " steps"));
                    expand_segment(profile, seg, 2, chain.steps);
                }
            } else {
                auto r = interpolate_arc(arc_method, x - m.cx, y - m.cy, m.x - m.cx, m.y - m.cy,
                                         m.kind == MoveKind::arc_ccw, chain.steps);
                if (!r) return fail(m, r.error());
            }
            total += chain.steps.size() - before;
            if (total > options.max_steps)
                return fail(m, make_error(Errc::limit, "output would exceed " +
                                                           std::to_string(options.max_steps) +
                                                           " steps"));
            x = m.x;
            y = m.y;
        }
        if (!chain.steps.empty()) {
            chains.push_back(std::move(chain));
            if (pens) pens->push_back(path.pen);
        }
    }
    return chains;
}

Result<void> check_redraw(const Drawing& drawing, const std::vector<Chain>& chains,
                          Profile profile, std::optional<ArcMethod> arc_method) {
    DrawingInterpolation how;
    how.profile = profile;
    how.arc_method = arc_method;
    how.source = "redrawn vectors";
    auto redrawn = interpolate_drawing(drawing, how);
    if (!redrawn) return std::move(redrawn).error();
    std::size_t r = 0;
    for (std::size_t c = 0; c < chains.size(); ++c) {
        const Chain& want = chains[c];
        if (want.steps.empty()) continue;
        const std::string which = "chain " + std::to_string(c + 1) + ": profile " +
                                  std::string(profile_name(profile)) + " redraws the vectors ";
        if (r == redrawn->size()) return make_error(Errc::mismatch, which + "into no chain");
        const Chain& got = (*redrawn)[r++];
        if (got.start != want.start)
            return make_error(Errc::mismatch, which + "from another start");
        const auto diff = std::mismatch(got.steps.begin(), got.steps.end(), want.steps.begin(),
                                        want.steps.end());
        if (diff.first != got.steps.end() || diff.second != want.steps.end())
            return make_error(Errc::mismatch,
                              which + "differently from step " +
                                  std::to_string(diff.second - want.steps.begin() + 1));
    }
    if (r != redrawn->size())
        return make_error(Errc::mismatch, "the vectors redraw into more chains than the input has");
    return {};
}

}  // namespace stepzip
