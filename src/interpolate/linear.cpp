// Linear forward interpolators: seed 000 (evaluation function, accelerated),
// seed 002 (multi-axis), seed 004 §6.2.2, patent SU 1089551 forward mode.
#include "stepzip/interpolate/linear.hpp"

#include <cstdlib>

#include "stepzip/segment.hpp"

namespace stepzip {

namespace {
int sign(std::int64_t v) { return (v > 0) - (v < 0); }

// Fast path shared by the two-letter rules below (not normative: it emits
// exactly what the per-step loops emit, tests/interpolate_fast_test.cpp
// compares them over whole ranges). Rule: n ticks, f = f0; f >= 0: letter
// `plain`, f -= s; else letter `other`, f += n - s. For f0 in [-s, n - s)
// the invariant -s <= f < n - s holds, so after t ticks the count of
// `other` letters is ceil((t·s - f0 - s) / n), and the j-th one (j >= 1)
// falls on tick floor(((j - 1)·n + f0 + s) / s) + 1: one division per run.
void emit_two_letter(std::int64_t n, std::int64_t s, std::int64_t f0, Step plain, Step other,
                     std::vector<Step>& out) {
    const std::size_t base = out.size();
    out.resize(base + static_cast<std::size_t>(n), plain);
    Step* o = out.data() + base;
    std::int64_t num = f0 + s;  // (j - 1)·n + f0 + s
    for (std::int64_t j = 0; j < s; ++j, num += n) o[num / s] = other;
}
}  // namespace

void eval_linear(std::int64_t dx, std::int64_t dy, std::int64_t f0, std::vector<Step>& out,
                 std::vector<std::int64_t>* trace, std::int64_t* forced) {
    const std::int64_t a = std::llabs(dx), b = std::llabs(dy);
    const Step sx = make_step2(sign(dx), 0), sy = make_step2(0, sign(dy));
    if (!trace && a > 0 && b > 0 && f0 >= -b && f0 < a) {
        emit_two_letter(a + b, b, f0, sx, sy, out);
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
    if (axes == 2 && variant == MultiAxisVariant::standard) {
        const std::int64_t s = std::llabs(delta[1 - lead]);
        const Step straight = lead == 0 ? make_step2(sign(delta[0]), 0) : make_step2(0, sign(delta[1]));
        const Step diagonal = make_step2(sign(delta[0]), sign(delta[1]));
        if (s == 0 || s == l) {
            out.insert(out.end(), static_cast<std::size_t>(l), s == 0 ? straight : diagonal);
            return;
        }
        if (phases[0] >= -s && phases[0] < l - s) {
            emit_two_letter(l, s, phases[0], straight, diagonal, out);
            return;
        }
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

}  // namespace stepzip
