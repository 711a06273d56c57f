// stepzip — a machine job (G-code on up to six axes) as the STEP/DIR
// signals a controller would put out: every move stepped, travel included.
#include <cstdlib>
#include <string>

#include "stepzip/vectors.hpp"

namespace stepzip {

namespace {

std::string move_place(const std::string& source, const MachineMove& m) {
    return source + ":" + std::to_string(m.line) + ":" + std::to_string(m.column);
}

constexpr std::uint16_t dir_bit(int axis) { return static_cast<std::uint16_t>(2u << (2 * axis)); }

}  // namespace

Result<SteppedJob> step_job(const MachineJob& job, const JobStepping& how) {
    const int axes = job.axes;
    const Profile p = how.profile;
    if (axes > profile_max_axes(p))
        return make_error(Errc::invalid_argument,
                          how.source + ": profile " + std::string(profile_name(p)) + " takes " +
                              std::to_string(profile_max_axes(p)) + " axes, the job has " +
                              std::to_string(axes) + " (" + job.letters + ")");
    const ArcMethod arc_method = how.arc_method.value_or(
        profile_eight_connected(p) ? ArcMethod::accelerated : ArcMethod::evaluation);
    const int ix = static_cast<int>(job.letters.find('X'));
    const int iy = static_cast<int>(job.letters.find('Y'));
    SteppedJob out;
    std::size_t total = 0;
    std::vector<Step> arc, spread;
    for (const MachineRun& run : job.runs) {
        Chain chain;
        chain.axes = axes;
        chain.start = run.start;
        std::vector<std::uint16_t> dir;
        Point at = run.start;
        for (const MachineMove& m : run.moves) {
            auto fail = [&](const Error& e) {
                return make_error(e.code, move_place(how.source, m) + ": " + e.message);
            };
            Point delta{};
            std::uint16_t mask = 0;  // DIR lines held for the whole move
            for (int a = 0; a < axes; ++a) {
                delta[static_cast<std::size_t>(a)] = m.to[static_cast<std::size_t>(a)] - at[static_cast<std::size_t>(a)];
                if (delta[static_cast<std::size_t>(a)] < 0) mask |= dir_bit(a);
            }
            const std::size_t before = chain.steps.size();
            if (m.kind == MoveKind::line) {
                const Segment seg = default_segment(p, delta, axes);
                if (auto r = check_segment(p, seg, axes); !r) return fail(r.error());
                const auto n = static_cast<std::size_t>(
                    segment_length(delta, axes, profile_eight_connected(p)));
                if (total + n > how.max_steps)
                    return fail(make_error(Errc::limit, "output would exceed " +
                                                            std::to_string(how.max_steps) + " steps"));
                expand_segment(p, seg, axes, chain.steps);
                dir.resize(chain.steps.size(), mask);
            } else {
                const auto kx = static_cast<std::size_t>(ix), ky = static_cast<std::size_t>(iy);
                arc.clear();
                auto r = interpolate_arc(arc_method, at[kx] - m.cx, at[ky] - m.cy, m.to[kx] - m.cx,
                                         m.to[ky] - m.cy, m.kind == MoveKind::arc_ccw, arc);
                if (!r) return fail(r.error());
                const auto n = static_cast<std::int64_t>(arc.size());
                if (total + arc.size() > how.max_steps)
                    return fail(make_error(Errc::limit, "output would exceed " +
                                                            std::to_string(how.max_steps) + " steps"));
                // X and Y from the arc; the other axes spread over its ticks
                // by the profile's rule for a line of n ticks.
                std::vector<Step> ticks(arc.size(), 0);
                for (std::size_t t = 0; t < arc.size(); ++t) {
                    int d[kMaxAxes] = {};
                    d[ix] = step_axis(arc[t], 0);
                    d[iy] = step_axis(arc[t], 1);
                    ticks[t] = make_step(d, axes);
                }
                for (int a = 0; a < axes; ++a) {
                    if (a == ix || a == iy || delta[static_cast<std::size_t>(a)] == 0) continue;
                    const std::int64_t s = delta[static_cast<std::size_t>(a)];
                    if (std::llabs(s) > n || !profile_eight_connected(p))
                        return fail(make_error(
                            Errc::unsupported,
                            "helix: axis " + std::string(1, job.letters[static_cast<std::size_t>(a)]) +
                                " moves " + std::to_string(std::llabs(s)) +
                                " steps over an arc of " + std::to_string(n) + " ticks"));
                    spread.clear();
                    expand_segment(p, default_segment(p, Point{n, s}, 2), 2, spread);
                    for (std::size_t t = 0; t < arc.size(); ++t)
                        if (const int v = step_axis(spread[t], 1); v != 0)
                            ticks[t] = static_cast<Step>(ticks[t] | (v > 0 ? 1u : 3u) << (2 * a));
                }
                // DIR of X and Y follows their steps; before an axis's first
                // step in the arc, the direction of that step.
                for (const int a : {ix, iy}) {
                    mask = static_cast<std::uint16_t>(mask & ~dir_bit(a));
                    for (const Step s : arc)
                        if (const int v = step_axis(s, a == ix ? 0 : 1); v != 0) {
                            if (v < 0) mask |= dir_bit(a);
                            break;
                        }
                }
                for (const Step s : ticks) {
                    for (const int a : {ix, iy})
                        if (const int v = step_axis(s, a); v != 0)
                            mask = static_cast<std::uint16_t>(v < 0 ? mask | dir_bit(a)
                                                                    : mask & ~dir_bit(a));
                    chain.steps.push_back(s);
                    dir.push_back(mask);
                }
            }
            total += chain.steps.size() - before;
            at = m.to;
        }
        if (!chain.steps.empty()) {
            out.chains.push_back(std::move(chain));
            out.dir.push_back(std::move(dir));
        }
    }
    return out;
}

Result<std::string> step_dir_bytes(const SteppedJob& job) {
    std::string out;
    for (std::size_t c = 0; c < job.chains.size(); ++c) {
        const Chain& chain = job.chains[c];
        if (chain.axes > 4)
            return make_error(Errc::unsupported, "a STEP/DIR log (steps format) holds 4 axes; the "
                                                 "job has " + std::to_string(chain.axes));
        for (std::size_t t = 0; t < chain.steps.size(); ++t)
            out.push_back(static_cast<char>((chain.steps[t] & 0x55u) | job.dir[c][t]));
    }
    return out;
}

}  // namespace stepzip
