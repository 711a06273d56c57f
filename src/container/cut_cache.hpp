// The frame writer's cache of chain cuts: a chain whose steps were cut
// before in the same frame (the same glyph contour traced again, under an
// accent or in another block; a plot repeated) takes the earlier cut
// instead of being segmented again. A cut of the greedy and default-phase
// kinds is a function of the chain's steps, the profile and the axes only
// (cut_block(), one chain at a time), so the cut taken is the cut that
// segmenting would make and the output bytes do not depend on the cache.
// Internal to src/container.
#pragma once

#include <cstdint>
#include <deque>
#include <mutex>
#include <span>
#include <unordered_map>
#include <vector>

#include "stepzip/profile.hpp"
#include "stepzip/segment.hpp"
#include "stepzip/segment/block_cut.hpp"
#include "stepzip/step.hpp"

namespace stepzip::stz {

/// Cuts of chains by their steps, under (cut kind, profile, axes). Holds at
/// most `budget` bytes of steps and segments (the oldest entries leave
/// first); a chain that alone exceeds a quarter of it is not kept.
/// Thread-safe (one lock per call; the frame's jobs share one cache).
class CutCache {
public:
    explicit CutCache(std::size_t budget) : budget_(budget) {}

    /// Hash of `steps` under the key (kind, p, axes); the key for find() and insert().
    static std::uint64_t hash(std::span<const Step> steps, BlockCut kind, Profile p, int axes) noexcept;

    /// When a cut of exactly `steps` under the key is held: copies it into
    /// `out` and returns true. `h` = hash(steps, kind, p, axes).
    bool find(std::uint64_t h, std::span<const Step> steps, BlockCut kind, Profile p, int axes,
              std::vector<Segment>& out) const;

    /// Keeps `cut` as the cut of `steps` under the key (no change when an
    /// entry of that hash is held).
    void insert(std::uint64_t h, std::span<const Step> steps, BlockCut kind, Profile p, int axes,
                const std::vector<Segment>& cut);

    /// Bytes held (steps and segments).
    std::size_t size() const;

private:
    // The cut as the first `axes` moves and `axes - 1` phases of each
    // segment (the rest of a Segment is zero on fewer axes than kMaxAxes).
    struct Entry {
        std::vector<Step> steps;
        std::vector<std::int64_t> cut;
        std::uint32_t key = 0;
    };
    static std::uint32_t key_of(BlockCut kind, Profile p, int axes) noexcept;
    static std::size_t bytes_of(const Entry& e) noexcept;

    mutable std::mutex mutex_;
    std::unordered_map<std::uint64_t, Entry> map_;
    std::deque<std::uint64_t> order_;  // hashes held, oldest first
    std::size_t bytes_ = 0;
    std::size_t budget_;
};

/// cut_block() of every chain of `chains` of the kinds greedy and
/// default_phase, taking from `cache` the cut of a chain of at least
/// kCutCacheMinSteps steps cut before and keeping the new ones there; the
/// other kinds, or a null cache: cut_block() itself. Same results and
/// errors as cut_block(). `accepted`: the caller has checked every chain
/// with profile_accepts(p, steps, axes), which is not done again
/// (cut_accepted_block()). Thread-safe (the cache locks).
Result<void> cut_block_cached(std::span<const Chain> chains, int axes, Profile p, BlockCut kind,
                              std::vector<std::vector<Segment>>& out, CutCache* cache,
                              SegmentStats* stats = nullptr, std::uint64_t first_chain = 0, bool accepted = false);

/// Shorter chains are cut again (a look-up costs about what their cut costs).
inline constexpr std::size_t kCutCacheMinSteps = 32;

}  // namespace stepzip::stz
