// stepzip — chains cut into circular arcs and lines, as a vector drawing
// (what `stepzip segment --arc-method` writes as G1 and G2 / G3).
#include <string>

#include "drawing_internal.hpp"
#include "stepzip/vectors.hpp"

namespace stepzip {

Result<std::vector<ArcCutChain>> cut_chains_into_arcs(const std::vector<Chain>& chains,
                                                      Profile profile, ArcMethod method,
                                                      const ArcCutOptions& options) {
    std::vector<ArcCutChain> out;
    out.reserve(chains.size());
    for (std::size_t c = 0; c < chains.size(); ++c) {
        ArcCutChain ac;
        ac.chain = chains[c];
        if (auto r = cut_arcs_and_lines(ac.chain.steps, ac.chain.axes, profile, method, options,
                                        ac.moves);
            !r)
            return make_error(r.error().code,
                              "chain " + std::to_string(c + 1) + ": " + r.error().message);
        out.push_back(std::move(ac));
    }
    return out;
}

Result<Drawing> arc_cut_to_drawing(const std::vector<ArcCutChain>& chains) {
    Drawing drawing;
    for (std::size_t c = 0; c < chains.size(); ++c) {
        const ArcCutChain& ac = chains[c];
        if (ac.chain.axes != 2) return not_two_axis(c, ac.chain.axes);
        if (ac.moves.empty()) continue;
        VectorPath path{ac.chain.start[0], ac.chain.start[1], {}};
        std::int64_t x = path.x0, y = path.y0;
        for (const ArcCutMove& am : ac.moves) {
            VectorMove m;
            if (am.is_arc) {
                m.kind = am.arc.ccw ? MoveKind::arc_ccw : MoveKind::arc_cw;
                m.cx = x + am.arc.cx;
                m.cy = y + am.arc.cy;
                x += am.arc.ex;
                y += am.arc.ey;
            } else {
                x += am.line.delta[0];
                y += am.line.delta[1];
            }
            m.x = x;
            m.y = y;
            path.moves.push_back(m);
        }
        drawing.push_back(std::move(path));
    }
    return drawing;
}

}  // namespace stepzip
