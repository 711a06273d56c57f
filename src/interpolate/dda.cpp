// Digital differential analyzer on a constant carrier frequency, linear and
// circular (seed 004 §6.2.2.4 Fig. 6.28; seed 000: N_cycles = 2^p).
#include "stepzip/interpolate/dda.hpp"

#include <algorithm>
#include <cstdlib>
#include <string>

#include "arc_walk.hpp"
#include "stepzip/interpolate/arc.hpp"

namespace stepzip {

namespace {
int sign(std::int64_t v) { return (v > 0) - (v < 0); }

int bits_for(std::int64_t v) {
    int p = 0;
    while ((std::int64_t{1} << p) < v) ++p;
    return p;
}
}  // namespace

Result<void> dda_linear(std::int64_t dx, std::int64_t dy, int p, std::vector<Step>& out,
                        DdaTrace* trace) {
    const std::int64_t lim = kMaxInterpolateCoord;
    const std::string where =
        "dda_linear(" + std::to_string(dx) + "," + std::to_string(dy) + ", p=" + std::to_string(p) + ")";
    if (dx < -lim || dx > lim || dy < -lim || dy > lim)
        return make_error(Errc::invalid_argument, where + ": coordinate beyond the limit 2^24");
    const std::int64_t a = std::llabs(dx), b = std::llabs(dy);
    if (p <= 0) p = bits_for(std::max(a, b));
    if (p > kMaxDdaBits)
        return make_error(Errc::invalid_argument, where + ": register wider than 40 bits");
    const std::int64_t w = std::int64_t{1} << p;
    if (w < std::max(a, b))
        return make_error(Errc::invalid_argument, where + ": 2^p below the larger total");
    if (trace) {
        trace->p = p;
        trace->cycles = 0;
        trace->step_cycle.clear();
        trace->points.clear();
    }
    if (a == 0 && b == 0) return {};
    std::int64_t rx = 0, ry = 0;  // the fractional remainders, in units of 2^-p
    const int sx = sign(dx), sy = sign(dy);
    for (std::int64_t c = 1; c <= w; ++c) {
        rx += a;
        ry += b;
        const bool cx = rx >= w, cy = ry >= w;
        if (cx) rx -= w;
        if (cy) ry -= w;
        if (cx || cy) {
            out.push_back(make_step2(cx ? sx : 0, cy ? sy : 0));
            if (trace) trace->step_cycle.push_back(static_cast<std::uint64_t>(c));
        }
    }
    if (trace) trace->cycles = static_cast<std::uint64_t>(w);
    return {};
}

Result<void> dda_circular(std::int64_t x0, std::int64_t y0, std::int64_t x1, std::int64_t y1,
                          bool ccw, std::vector<Step>& out, DdaTrace* trace) {
    if (auto r = detail::check_arc(x0, y0, x1, y1, "dda_circular"); !r) return r;
    detail::ArcState s =
        detail::make_state(x0, y0, out, trace ? &trace->points : nullptr);
    if (trace) {
        trace->points.clear();
        trace->step_cycle.clear();
    }
    const int p = bits_for(s.rr + 2);
    const std::int64_t w = std::int64_t{1} << p;
    std::int64_t rx = 0, ry = 0;
    std::uint64_t cycle = 0;
    auto piece = [&](detail::ArcState& st, detail::Piece& pc) {
        const std::int64_t cap = 8 * w + 8;
        rx = ry = w / 2;  // each quadrant is a new frame; half a step: round, not truncate
        for (std::int64_t n = 0; n < cap && (pc.cx > 0 || pc.cy > 0); ++n) {
            // Euler-Cromer: the y register sums |x| after this cycle's x move,
            // so the error does not enter twice (seed 004) and the orbit closes.
            const std::int64_t vx = std::llabs(st.y);
            const bool x_stuck = pc.cx == 0 || vx == 0;
            const bool y_stuck = pc.cy == 0 || (st.x == 0 && x_stuck);
            if (x_stuck && y_stuck) break;  // stalled: the correction run finishes
            ++cycle;
            rx += vx;
            const bool cx = rx >= w;
            if (cx) rx -= w;
            const int dx = (cx && pc.cx > 0) ? 1 : 0;
            ry += std::llabs(st.x + dx * pc.mx);
            const bool cy = ry >= w;
            if (cy) ry -= w;
            const int dy = (cy && pc.cy > 0) ? 1 : 0;
            if (dx || dy) {
                st.step(dx * pc.mx, dy * pc.my);
                pc.cx -= dx;
                pc.cy -= dy;
                if (trace) trace->step_cycle.push_back(cycle);
            }
        }
    };
    const std::size_t before = out.size();
    detail::walk_arc(s, x1, y1, ccw, true, piece);
    if (trace) {
        // Correction steps take one cycle each after the DDA's own.
        while (trace->step_cycle.size() < out.size() - before) trace->step_cycle.push_back(++cycle);
        trace->p = p;
        trace->cycles = cycle;
    }
    return {};
}

}  // namespace stepzip
