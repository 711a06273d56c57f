// Arc items of the table block (arc_items.hpp, docs/FORMAT.md 1.10.1).
#include "arc_items.hpp"

#include <cmath>

#include "stepzip/interpolate/segment.hpp"
#include "stepzip/vectors.hpp"

namespace stepzip::stz {

std::uint64_t arc_step_bound(std::int64_t cx, std::int64_t cy) {
    const double r = std::ceil(std::sqrt(static_cast<double>(cx) * static_cast<double>(cx) +
                                         static_cast<double>(cy) * static_cast<double>(cy)));
    return static_cast<std::uint64_t>(9 * r) + 16;
}

bool draw_arc_item(const Segment& s, std::vector<Step>& out) {
    const std::int64_t cx = s.delta[2], cy = s.delta[3];
    return interpolate_arc(arc_method_of(s), -cx, -cy, s.delta[0] - cx, s.delta[1] - cy,
                           arc_ccw(s), out)
        .ok();
}

std::uint64_t item_steps(const Segment& s, Profile p, int axes) {
    if (!is_arc(s, axes))
        return static_cast<std::uint64_t>(segment_length(s.delta, axes, profile_eight_connected(p)));
    std::vector<Step> steps;
    return draw_arc_item(s, steps) ? steps.size() : 0;
}

Result<void> arc_block_cut(const Block& block, Profile p, ArcMethod method,
                           std::vector<std::vector<Segment>>& out, std::uint64_t first_chain,
                           const std::string& source) {
    std::uint64_t total = 0;
    for (const Chain& c : block.chains) total += c.steps.size();
    out.assign(block.chains.size(), {});
    std::vector<ArcCutMove> moves;
    std::vector<Segment> lines;
    for (std::size_t c = 0; c < block.chains.size(); ++c) {
        const Chain& chain = block.chains[c];
        moves.clear();
        auto fail = [&](const Error& e) {
            return make_error(e.code, source + ": chain " + std::to_string(first_chain + c + 1) + ": " +
                                          e.message);
        };
        if (auto r = cut_arcs_and_lines(chain.steps, block.axes, p, method, ArcCutOptions{}, moves); !r)
            return fail(r.error());
        std::size_t at = 0;
        for (const ArcCutMove& m : moves) {
            if (!m.is_arc) {
                out[c].push_back(m.line);
            } else if (arc_step_bound(m.arc.cx, m.arc.cy) <= total) {
                out[c].push_back(arc_item(m.arc, method));
            } else {
                // In a block of fewer steps than its bound an arc may not be
                // declared: lines.
                lines.clear();
                if (auto r = segment_default_phase(std::span<const Step>(chain.steps).subspan(at, m.steps),
                                                   block.axes, p, lines);
                    !r)
                    return fail(r.error());
                out[c].insert(out[c].end(), lines.begin(), lines.end());
            }
            at += m.steps;
        }
    }
    return {};
}

}  // namespace stepzip::stz
