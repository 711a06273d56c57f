// The segment fields shared by the segment model (block types 3 and 6) and
// the table block (type 5), docs/FORMAT.md sections 1.5 and 1.10: how a
// minor total is predicted and checked, and how a total gets its sign.
// Internal to src/container.
#pragma once

#include <algorithm>
#include <cstdint>

namespace stepzip::stz {

/// The prediction of a minor total of a segment whose leading total is `l`:
/// the previous segment's minor total `prev_s` over its leading total
/// `prev_l`, scaled to `l` and rounded, at most `l`.
inline std::int64_t predict_minor(std::int64_t l, std::int64_t prev_s, std::int64_t prev_l) {
    return std::min(l, (l * prev_s + prev_l / 2) / prev_l);
}

/// Whether `v` is a canonical minor total of axis `i` under leading axis
/// `lead` and leading total `l` (0..l, below l on an axis before the lead).
inline bool minor_in_range(std::int64_t v, std::int64_t l, int i, int lead) {
    return v >= 0 && v <= l && !(i < lead && v == l);
}

/// The total `v` of axis `i` signed by `negmask`; false for a sign on a
/// resting axis.
inline bool apply_sign(std::int64_t& v, unsigned negmask, int i) {
    if (((negmask >> i) & 1u) == 0) return true;
    if (v == 0) return false;
    v = -v;
    return true;
}

}  // namespace stepzip::stz
