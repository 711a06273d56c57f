// The longest digital straight segment ending at a chain's last step, kept
// step by step for the context-mixing step model (docs/FORMAT.md 1.11.4):
// what each next step would do to it is a question of O(1) arithmetic.
// Arithmetic recognition after Debled-Rennesson & Reveillès (1995): a word
// over two adjacent Freeman codes is a DSS iff its points in the naive
// frame (x: letters read, y: letters of the second code read) lie in a
// strip mu <= a x - b y < mu + b, 0 <= a <= b; a new point one outside
// the strip (r = mu - 1 or mu + b) turns the slope about the first leaning
// point of the other side. A 4-connected pair (codes 90 degrees apart) is
// the same word under the shear (x, y) -> (x + y, y), so one recognizer
// serves both connectivities. (The segmenters' recognizers, src/segment/,
// answer other questions: the longest segment from a point, by hulls.)
// Complexity: O(1) a step and a query; when a step ends the word the
// longest suffix is read again (back, then forward: a reversed DSS is one),
// amortized O(1) a step on curves, at most kCap letters.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

namespace stepzip::stz {

/// A DSS word in arithmetic form. l0 is its first code, l1 the other (-1
/// until read; it is 45 or 90 degrees from l0).
struct DssWord {
    struct Pt {
        std::int64_t x, y;
    };
    int l0 = -1, l1 = -1;
    std::int64_t len = 0;  // letters
    int brk = 0;           // DssSuffix's last three break sides (0..26)
    std::int64_t a = 0, b = 1, mu = 0;
    Pt m{0, 0};                                   // the last point
    Pt u{0, 0}, uq{0, 0}, lo{0, 0}, loq{0, 0};    // first and last upper, lower leaning points

    static bool adjacent(int c, int d) {
        const int t = (d - c) & 7;
        return t == 1 || t == 7 || t == 2 || t == 6;
    }
    /// Code `sym` as a letter: 0 (l0), 1 (l1), -1 (neither can it be).
    int value(int sym) const {
        if (len == 0 || sym == l0) return 0;
        if (l1 >= 0) return sym == l1 ? 1 : -1;
        return adjacent(l0, sym) ? 1 : -1;
    }
    /// a x - b y at the point after the last, for a letter of value v.
    std::int64_t next_remainder(int v) const { return a * (m.x + 1) - b * (m.y + v); }
    /// What `sym` next does: 0 ends the word, 1 keeps it a DSS of another
    /// slope, 2 keeps it within its strip.
    int status(int sym) const {
        const int v = value(sym);
        if (v < 0) return 0;
        const std::int64_t r = next_remainder(v);
        if (r >= mu && r < mu + b) return 2;
        return r == mu - 1 || r == mu + b ? 1 : 0;
    }
    /// Where the curve turned when `sym` ended the word (status 0): 0
    /// counter-clockwise, 1 clockwise (the word ran out of its strip on that
    /// side), 2 a corner (a code outside the pair).
    int side(int sym) const {
        const int v = value(sym);
        if (v < 0) return 2;
        const std::int64_t r = next_remainder(v);
        const int t = (l1 - l0) & 7;  // (a run is ended by a corner only: l1 >= 0)
        return (r < mu) == (t == 1 || t == 2) ? 0 : 1;
    }
    /// Appends `sym`; false, the word unchanged, when it would be no DSS.
    bool push(int sym) {
        const int v = value(sym);
        if (v < 0) return false;
        const Pt M{m.x + 1, m.y + v};
        const std::int64_t r = next_remainder(v);
        if (r >= mu && r < mu + b) {
            if (r == mu) uq = M;
            if (r == mu + b - 1) loq = M;
        } else if (r == mu - 1) {
            lo = loq;
            uq = M;
            a = M.y - u.y;
            b = M.x - u.x;
            mu = a * M.x - b * M.y;
        } else if (r == mu + b) {
            u = uq;
            loq = M;
            a = M.y - lo.y;
            b = M.x - lo.x;
            mu = a * M.x - b * M.y - b + 1;
        } else {
            return false;
        }
        if (len == 0) l0 = sym;
        else if (v == 1) l1 = sym;
        m = M;
        ++len;
        return true;
    }
};

/// The longest DSS ending at the chain's last step (at most kCap - 1
/// letters; past that, the longest of at most kCap / 2).
class DssSuffix {
public:
    static constexpr int kCap = 1024;

    void start_chain() {
        n_ = 0;
        brk_ = 0;
        w_ = DssWord{};
    }
    /// After a step of code `sym`.
    void push(int sym) {
        ring_[n_ & (kCap - 1)] = static_cast<std::uint8_t>(sym);
        ++n_;
        std::uint64_t most = kCap / 2;
        if (w_.len < kCap - 1) {
            if (w_.push(sym)) return;
            brk_ = (brk_ * 3 + w_.side(sym)) % 27;
            most = kCap - 1;
        }
        most = std::min<std::uint64_t>(most, n_);
        DssWord back;
        std::uint64_t k = 0;
        while (k < most && back.push(ring_[(n_ - 1 - k) & (kCap - 1)])) ++k;
        w_ = DssWord{};
        for (std::uint64_t i = k; i > 0; --i) w_.push(ring_[(n_ - i) & (kCap - 1)]);
        w_.brk = brk_;
    }
    const DssWord& word() const { return w_; }

private:
    std::array<std::uint8_t, kCap> ring_{};
    std::uint64_t n_ = 0;  // steps of the chain
    int brk_ = 0;
    DssWord w_;
};

/// The word as seen from its last code `prev`: 0 no word (a chain's start),
/// 1 a run of prev, else 2 + 9·c + 3·status(prev) + status(other), with c
/// = 0, 1, 2, 3 for the other code at a turn of +45, -45, +90, -90 degrees
/// from prev. (38 values.)
inline int dss_state(const DssWord& w, int prev) {
    if (w.len == 0) return 0;
    if (w.l1 < 0) return 1;
    const int other = prev == w.l0 ? w.l1 : w.l0;
    const int t = (other - prev) & 7;
    const int c = t == 1 ? 0 : t == 7 ? 1 : t == 2 ? 2 : 3;
    return 2 + (c * 3 + w.status(prev)) * 3 + w.status(other);
}
inline constexpr int kDssStates = 38;

}  // namespace stepzip::stz
