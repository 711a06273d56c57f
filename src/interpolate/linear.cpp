// Linear forward interpolators: seed 000 (evaluation function, accelerated),
// seed 002 (multi-axis), seed 004 §6.2.2, patent SU 1089551 forward mode.
#include "stepzip/interpolate/linear.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include "expand_into.hpp"

#include "stepzip/segment.hpp"

namespace stepzip {

namespace {
int sign(std::int64_t v) { return (v > 0) - (v < 0); }

using detail::emit_two_letter;
using detail::fill_steps;
using detail::other_ticks;

// The step bits of `axis` moving in the direction of delta[axis].
Step axis_bits(const Point& delta, int axis) {
    return static_cast<Step>((delta[axis] < 0 ? 3u : 1u) << (2 * axis));
}

// Whether a minor axis of s steps under l leading steps, phase f0, is in the
// exact range of the division rule (or its function is degenerate: s = 0 or
// s = l); the same bound as leading_two_axis_into's.
bool phase_exact(std::int64_t l, std::int64_t s, std::int64_t f0) {
    return s == 0 || s == l || (f0 >= -s && f0 < l - s);
}

// Whether multiaxis_fast writes the steps of `delta` with `phases` (a run of
// at most 8 ticks on more than two axes, or every minor phase exact).
bool multiaxis_fast_applies(const Point& delta, int axes, const std::int64_t* phases) {
    const int lead = leading_axis(delta, axes);
    const std::int64_t l = std::llabs(delta[lead]);
    if (axes != 2 && l <= 8) return true;
    for (int i = 0, j = 0; i < axes; ++i) {
        if (i == lead) continue;
        if (!phase_exact(l, std::llabs(delta[i]), phases[j++])) return false;
    }
    return true;
}

// More axes, each minor axis by the rule of emit_two_letter (letter "moves"
// at the ticks found by division, else "rests"): the run of leading-axis
// steps is written at once, then each minor axis's moves are or-ed into
// it. Not normative: exactly the per-step loop of multiaxis_linear when
// every phase is in its exact range or its function is degenerate
// (tests/container_fast_paths_test.cpp compares them); false, and nothing
// written, otherwise.
bool emit_minor_axes(const Point& delta, int lead, std::int64_t l, const int* minor, const std::int64_t* s,
                     const std::int64_t* f0, int nminor, Step* o) {
    for (int j = 0; j < nminor; ++j)
        if (!phase_exact(l, s[j], f0[j])) return false;
    fill_steps(o, l, axis_bits(delta, lead));
    for (int j = 0; j < nminor; ++j) {
        const Step b = axis_bits(delta, minor[j]);
        if (s[j] == 0) continue;
        if (s[j] == l) {
            for (std::int64_t t = 0; t < l; ++t) o[t] = static_cast<Step>(o[t] | b);
            continue;
        }
        other_ticks(l, s[j], f0[j], [&](std::int64_t t) { o[t] = static_cast<Step>(o[t] | b); });
    }
    return true;
}

// The fast paths of multiaxis_linear (standard variant) into o[0, L):
// false, and nothing written, where none applies (a run of more than 8
// ticks with a phase outside its exact range).
bool multiaxis_fast(const Point& delta, int axes, const std::int64_t* phases, Step* o) {
    if (axes == 2) return detail::leading_two_axis_into(delta, phases[0], o);
    const int lead = leading_axis(delta, axes);
    const std::int64_t l = std::llabs(delta[lead]);
    int minor[kMaxAxes];
    std::int64_t s[kMaxAxes];
    int nminor = 0;
    for (int i = 0; i < axes; ++i) {
        if (i == lead) continue;
        minor[nminor] = i;
        s[nminor] = std::llabs(delta[i]);
        ++nminor;
    }
    if (l <= 8) {
        // Short runs: the rule of multiaxis_linear a tick at a time (exact
        // for every phase), cheaper than the divisions.
        std::int64_t f[kMaxAxes];
        Step b[kMaxAxes];
        for (int j = 0; j < nminor; ++j) {
            f[j] = phases[j];
            b[j] = axis_bits(delta, minor[j]);
        }
        const Step lb = axis_bits(delta, lead);
        for (std::int64_t t = 0; t < l; ++t) {
            Step st = lb;
            for (int j = 0; j < nminor; ++j) {
                if (s[j] == 0) continue;
                if (s[j] == l) {
                    st = static_cast<Step>(st | b[j]);
                } else if (f[j] >= 0) {
                    f[j] -= s[j];
                } else {
                    st = static_cast<Step>(st | b[j]);
                    f[j] += l - s[j];
                }
            }
            o[t] = st;
        }
        return true;
    }
    return emit_minor_axes(delta, lead, l, minor, s, phases, nminor, o);
}

// Room for n more steps at the end of `out`.
Step* append_room(std::vector<Step>& out, std::int64_t n) {
    const std::size_t base = out.size();
    out.resize(base + static_cast<std::size_t>(n));
    return out.data() + base;
}
}  // namespace

void eval_linear(std::int64_t dx, std::int64_t dy, std::int64_t f0, std::vector<Step>& out,
                 std::vector<std::int64_t>* trace, std::int64_t* forced) {
    const std::int64_t a = std::llabs(dx), b = std::llabs(dy);
    const Step sx = make_step2(sign(dx), 0), sy = make_step2(0, sign(dy));
    if (!trace && a > 0 && b > 0 && f0 >= -b && f0 < a) {
        emit_two_letter(a + b, b, f0, sx, sy, append_room(out, a + b));
        if (forced) *forced = 0;
        return;
    }
    std::int64_t kox = a, koy = b, f = f0, nforced = 0;
    while (kox > 0 || koy > 0) {
        bool x = f >= 0;
        if (x && kox == 0) { x = false; ++nforced; }
        else if (!x && koy == 0) { x = true; ++nforced; }
        if (x) { out.push_back(sx); --kox; f -= b; }
        else   { out.push_back(sy); --koy; f += a; }
        if (trace) trace->push_back(f);
    }
    if (forced) *forced = nforced;
}

void accelerated_linear(std::int64_t dx, std::int64_t dy, std::int64_t f0, std::vector<Step>& out,
                        std::vector<std::int64_t>* trace) {
    const std::int64_t ax = std::llabs(dx), ay = std::llabs(dy);
    const bool x_leads = ax >= ay;
    const std::int64_t l = x_leads ? ax : ay, s = x_leads ? ay : ax;
    const Step straight = x_leads ? make_step2(sign(dx), 0) : make_step2(0, sign(dy));
    const Step diagonal = make_step2(sign(dx), sign(dy));
    if (!trace && (s == 0 || s == l)) {
        out.insert(out.end(), static_cast<std::size_t>(l), s == 0 ? straight : diagonal);
        return;
    }
    if (!trace && f0 >= -s && f0 < l - s) {
        emit_two_letter(l, s, f0, straight, diagonal, append_room(out, l));
        return;
    }
    std::int64_t f = f0;
    for (std::int64_t t = 0; t < l; ++t) {
        bool diag;
        if (s == 0) diag = false;
        else if (s == l) diag = true;
        else if (f >= 0) { diag = false; f -= s; }
        else { diag = true; f += l - s; }
        out.push_back(diag ? diagonal : straight);
        if (trace) trace->push_back(f);
    }
}

void multiaxis_linear(const Point& delta, int axes, const std::int64_t* phases,
                      std::vector<Step>& out, MultiAxisVariant variant) {
    const int lead = leading_axis(delta, axes);
    const std::int64_t l = std::llabs(delta[lead]);
    // The buffer grows only when a fast path writes it.
    if (variant == MultiAxisVariant::standard && multiaxis_fast_applies(delta, axes, phases)) {
        multiaxis_fast(delta, axes, phases, append_room(out, l));
        return;
    }
    int minor[kMaxAxes];
    std::int64_t s[kMaxAxes], f[kMaxAxes];
    int nminor = 0;
    for (int i = 0; i < axes; ++i) {
        if (i == lead) continue;
        minor[nminor] = i;
        s[nminor] = std::llabs(delta[i]);
        f[nminor] = variant == MultiAxisVariant::standard ? phases[nminor] : 0;
        ++nminor;
    }
    int d[kMaxAxes] = {};
    for (std::int64_t t = 0; t < l; ++t) {
        d[lead] = sign(delta[lead]);
        for (int j = 0; j < nminor; ++j) {
            bool move;
            if (s[j] == 0) move = false;
            else if (s[j] == l) move = true;
            else if (t == 0 && variant == MultiAxisVariant::first_step_all_axes) {
                move = true;
                f[j] += l - s[j];
            } else if (f[j] >= 0) { move = false; f[j] -= s[j]; }
            else { move = true; f[j] += l - s[j]; }
            d[minor[j]] = move ? sign(delta[minor[j]]) : 0;
        }
        out.push_back(make_step(d, axes));
    }
}

void patent_forward(std::int64_t dx, std::int64_t dy, std::int64_t f00, std::vector<Step>& out,
                    std::vector<std::int64_t>* trace) {
    const Step sx = make_step2(sign(dx), 0), sy = make_step2(0, sign(dy));
    std::int64_t x = std::llabs(dx), y = std::llabs(dy), f = f00;
    while (x > 0 || y > 0) {
        const bool xstep = y == 0 || (f < 0 && x > 0);
        if (xstep) { --x; f += y; out.push_back(sx); }
        else       { --y; f -= x; out.push_back(sy); }
        if (trace) trace->push_back(f);
    }
}

namespace detail {

bool expand_segment_into(Profile p, const Segment& seg, int axes, Step* out) {
    if (axes == 2) return expand_two_axis_into(p, seg, out);
    switch (p) {
        case Profile::eval8:
        case Profile::grbl:
        case Profile::marlin:
            return multiaxis_fast(seg.delta, axes, seg.phase.data(), out);
        default:
            return false;
    }
}

}  // namespace detail

}  // namespace stepzip
