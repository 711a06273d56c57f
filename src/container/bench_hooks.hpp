// Bench hook: instrumentation for the measurements of docs/FORMAT.md
// ("Rationale") that the codec itself never runs: other record layouts and
// the cost of each field of the segment model. Used by bench/ only.
// Internal to src/container.
#pragma once

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "block_codec.hpp"
#include "range_coder.hpp"

namespace stepzip::stz {

/// Record layouts measured against the format's (the default). The decoder
/// reads the default only.
struct PayloadVariant {
    bool interleaved = true;      ///< one record per segment (else one stream per field)
    bool start_from_end = true;   ///< chain start relative to the previous chain's end (else start)
    bool octant_delta = true;     ///< 2D direction as the octant turn from the previous segment
};
std::string write_chain_payload_variant(const Block& block, Profile p,
                                        const std::vector<std::vector<Segment>>& segs,
                                        const PayloadVariant& variant);

/// The fields of the segment model, as segment_model_costs() counts them.
inline constexpr int kSegmentModelFields = 9;
inline constexpr const char* kSegmentModelFieldNames[kSegmentModelFields] = {
    "start_hit", "start", "seg_hit", "end", "direction", "lead", "minor", "phase", "shape"};

/// The range encoder counting the bits (-log2 of the coded probability)
/// spent on each field.
struct CostEncIo : EncIo {
    int at = 0;
    double cost[16] = {};
    void field(int k) { at = k; }
    int bit(Prob& p, int b) {
        const double q = p.p / 65536.0;
        cost[at] -= std::log2(b ? 1 - q : q);
        return EncIo::bit(p, b);
    }
};

/// Bits spent on each field by the segment model of `block` cut into `segs`
/// (no window); `timed`: 1 as in a timed frame's block type 3, 2 as in a
/// timed block (type 7 subtype 0; `segs` aligned for it).
std::array<double, kSegmentModelFields> segment_model_costs(const Block& block, Profile p,
                                                            const std::vector<std::vector<Segment>>& segs,
                                                            int timed = 0);

}  // namespace stepzip::stz
