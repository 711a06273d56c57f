#include "stepzip/chain.hpp"

#include <cstdlib>

#include "stepzip/segment.hpp"

namespace stepzip {

Point Chain::end() const noexcept {
    // Axis by axis, a branch-free sum: a STEP/DIR pair adds
    // STEP - 2·(STEP and DIR): 01 -> +1, 11 -> -1, 00 and 10 -> 0, as
    // step_axis() reads it. Pieces of a fixed length, so that the compiler
    // vectorizes the inner loop at -O2 too.
    Point p = start;
    const Step* s = steps.data();
    const std::size_t n = steps.size();
    constexpr std::size_t kPiece = 64;
    auto move = [](unsigned b) {
        return static_cast<std::int32_t>(b & 1u) - 2 * static_cast<std::int32_t>(b & (b >> 1) & 1u);
    };
    for (int a = 0; a < axes && a < kMaxAxes; ++a) {
        const unsigned shift = 2u * static_cast<unsigned>(a);
        std::int64_t total = 0;
        std::size_t i = 0;
        for (; n - i >= kPiece; i += kPiece) {
            std::int32_t sum = 0;
            for (std::size_t j = 0; j < kPiece; ++j) sum += move(static_cast<unsigned>(s[i + j]) >> shift);
            total += sum;
        }
        for (; i < n; ++i) total += move(static_cast<unsigned>(s[i]) >> shift);
        p[a] += total;
    }
    return p;
}

bool Chain::four_connected() const noexcept {
    for (Step s : steps)
        if (step_weight(s) != 1) return false;
    return true;
}

Result<std::string> to_freeman(const Chain& chain) {
    if (chain.axes != 2)
        return make_error(Errc::invalid_argument, "Freeman codes need a two-axis chain");
    std::string codes;
    codes.reserve(chain.steps.size());
    for (std::size_t i = 0; i < chain.steps.size(); ++i) {
        const int c = step_to_freeman(chain.steps[i]);
        if (c < 0)
            return make_error(Errc::invalid_argument,
                              "step " + std::to_string(i + 1) + " has no Freeman code");
        codes.push_back(static_cast<char>('0' + c));
    }
    return codes;
}

Result<Chain> from_freeman(std::int64_t x0, std::int64_t y0, std::string_view codes) {
    Chain chain;
    chain.axes = 2;
    chain.start[0] = x0;
    chain.start[1] = y0;
    chain.steps.reserve(codes.size());
    for (std::size_t i = 0; i < codes.size(); ++i) {
        const char c = codes[i];
        if (c < '0' || c > '7')
            return make_error(Errc::syntax, "character " + std::to_string(i + 1) +
                                                " is not a Freeman code 0-7");
        chain.steps.push_back(freeman_to_step(c - '0'));
    }
    return chain;
}

std::vector<Point> chain_points(const Chain& chain) {
    std::vector<Point> pts;
    pts.reserve(chain.steps.size() + 1);
    Point p = chain.start;
    pts.push_back(p);
    for (Step s : chain.steps) {
        apply_step(p, s, chain.axes);
        pts.push_back(p);
    }
    return pts;
}

}  // namespace stepzip
