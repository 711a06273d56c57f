// Evaluation function on a constant carrier frequency, linear (seed 004
// §6.2.2.3).
#include "stepzip/interpolate/carrier.hpp"

#include <algorithm>
#include <cstdlib>
#include <string>

#include "stepzip/interpolate/arc.hpp"

namespace stepzip {

Result<void> carrier_linear(std::int64_t dx, std::int64_t dy, std::int64_t periods,
                            std::vector<Step>& out, std::vector<CarrierPeriod>* trace) {
    const std::int64_t lim = kMaxInterpolateCoord;
    const std::string where = "carrier_linear(" + std::to_string(dx) + "," + std::to_string(dy) +
                              ", periods=" + std::to_string(periods) + ")";
    if (dx < -lim || dx > lim || dy < -lim || dy > lim)
        return make_error(Errc::invalid_argument, where + ": coordinate beyond the limit 2^24");
    const std::int64_t a = std::llabs(dx), b = std::llabs(dy);
    const std::int64_t l = std::max(a, b);
    if (periods > 0 && periods < l)
        return make_error(Errc::invalid_argument,
                          where + ": fewer periods than units on the leading axis");
    if (periods > (std::int64_t{1} << 40))
        return make_error(Errc::invalid_argument, where + ": more than 2^40 periods");
    const std::int64_t n = periods > 0 ? periods : l;
    if (n == 0) return {};
    const int sx = (dx > 0) - (dx < 0), sy = (dy > 0) - (dy < 0);
    // Integer parts of the average increments |X|/n, |Y|/n (0, or 1 when n == L).
    const std::int64_t base_x = a / n, base_y = b / n;
    std::int64_t nx = 0, my = 0;  // N_i, M_i (scaled by n)
    for (std::int64_t i = 1; i <= n; ++i) {
        std::int64_t ix = base_x, iy = base_y;
        if (nx + n * ix - a < 0) ++ix;  // error would be negative: add one discrete
        if (my + n * iy - b < 0) ++iy;
        nx += n * ix - a;
        my += n * iy - b;
        if (ix || iy) out.push_back(make_step2(ix ? sx : 0, iy ? sy : 0));
        if (trace) trace->push_back({ix ? sx : 0, iy ? sy : 0, nx, my});
    }
    return {};
}

}  // namespace stepzip
