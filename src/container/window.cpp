// Contributions of a block to the window (docs/FORMAT.md "Window").
#include "window.hpp"

#include <array>

#include "arc_items.hpp"

#include "../common/bytes.hpp"

namespace stepzip::stz {

std::vector<std::uint8_t> step_symbols(const Block& block) {
    std::vector<std::uint8_t> out;
    if (block.axes != 2) return out;
    // Freeman code of each step value below 16 (step_to_freeman()), 0xFF
    // where it is none; steps of 16 and above are never two-axis steps.
    static constexpr auto kCode = [] {
        std::array<std::uint8_t, 16> t{};
        for (unsigned v = 0; v < 16; ++v) {
            const int c = step_to_freeman(static_cast<Step>(v));
            t[v] = c < 0 ? 0xFF : static_cast<std::uint8_t>(c);
        }
        return t;
    }();
    std::size_t n = 0;
    for (const Chain& c : block.chains) n += c.steps.size() + 1;
    out.resize(n);
    std::uint8_t* o = out.data();
    unsigned bad = 0;  // bit 7 and above: a step with no Freeman code
    for (const Chain& c : block.chains) {
        for (Step s : c.steps) {
            const std::uint8_t code = kCode[s & 15u];
            bad |= code | (static_cast<unsigned>(s >> 4) << 7);
            *o++ = code;
        }
        *o++ = 8;
    }
    if (bad & ~127u) return {};
    return out;
}

std::vector<std::uint8_t> tick_masks(const Block& block) {
    std::vector<std::uint8_t> out;
    std::size_t n = 0;
    for (const Chain& chain : block.chains) n += chain.steps.size();
    out.reserve(n);
    for (const Chain& chain : block.chains)
        for (const Step s : chain.steps) {
            unsigned m = 0;
            for (int a = 1; a < block.axes; ++a)
                if (step_axis(s, a) != 0) m |= 1u << (a - 1);
            out.push_back(static_cast<std::uint8_t>(m));
        }
    return out;
}

std::vector<Point> start_deltas(const Block& block) {
    std::vector<Point> out;
    out.reserve(block.chains.size());
    Point ref{};
    for (const Chain& chain : block.chains) {
        Point d{};
        for (int a = 0; a < block.axes; ++a) d[a] = wrap_sub(chain.start[a], ref[a]);
        out.push_back(d);
        ref = chain.end();
    }
    return out;
}

void add_steps(WindowBlock& w, const Block& block) {
    w.symbols = step_symbols(block);
    if (!w.symbols.empty()) w.starts = start_deltas(block);
}

void add_steps_lent(WindowBlock& w, Block& block) {
    const bool lent = block.chains.empty() && !w.chains.empty();
    if (lent) block.chains.swap(w.chains);
    add_steps(w, block);
    if (lent) w.chains.swap(block.chains);
}

SegmentItems segment_items(const Block& block, const std::vector<std::vector<Segment>>& segs) {
    SegmentItems out;
    out.starts.reserve(block.chains.size());
    out.counts.reserve(block.chains.size());
    std::size_t n = 0;
    for (std::size_t i = 0; i < block.chains.size(); ++i) n += segs[i].size();
    out.segments.reserve(n);
    Point ref{};
    for (std::size_t i = 0; i < block.chains.size(); ++i) {
        const Chain& chain = block.chains[i];
        Point d{};
        for (int a = 0; a < block.axes; ++a) d[a] = wrap_sub(chain.start[a], ref[a]);
        out.starts.push_back(d);
        out.counts.push_back(static_cast<std::uint32_t>(segs[i].size()));
        ref = chain.start;
        if (block.axes == 2) {
            for (const Segment& s : segs[i]) {
                out.segments.push_back(s);
                out.arcs = out.arcs || is_arc(s, 2);
                ref[0] = wrap_add(ref[0], s.delta[0]);
                ref[1] = wrap_add(ref[1], s.delta[1]);
            }
        } else {
            for (const Segment& s : segs[i]) {
                out.segments.push_back(s);
                for (int a = 0; a < block.axes; ++a) ref[a] = wrap_add(ref[a], s.delta[a]);
            }
        }
    }
    return out;
}

}  // namespace stepzip::stz
