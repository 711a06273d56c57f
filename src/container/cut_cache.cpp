// The frame writer's cache of chain cuts. See cut_cache.hpp.
#include "cut_cache.hpp"

#include <algorithm>
#include <xxhash.h>

#include "../segment/accepted_cut.hpp"

namespace stepzip::stz {

std::uint32_t CutCache::key_of(BlockCut kind, Profile p, int axes) noexcept {
    return static_cast<std::uint32_t>(kind) | static_cast<std::uint32_t>(p) << 8 |
           static_cast<std::uint32_t>(axes) << 16;
}

std::uint64_t CutCache::hash(std::span<const Step> steps, BlockCut kind, Profile p, int axes) noexcept {
    return XXH3_64bits_withSeed(steps.data(), steps.size_bytes(), key_of(kind, p, axes));
}

std::size_t CutCache::bytes_of(const Entry& e) noexcept {
    return e.steps.size() * sizeof(Step) + e.cut.size() * sizeof(std::int64_t);
}

bool CutCache::find(std::uint64_t h, std::span<const Step> steps, BlockCut kind, Profile p, int axes,
                    std::vector<Segment>& out) const {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto it = map_.find(h);
    if (it == map_.end()) return false;
    const Entry& e = it->second;
    if (e.key != key_of(kind, p, axes) || !std::equal(steps.begin(), steps.end(), e.steps.begin(), e.steps.end()))
        return false;
    const auto per = static_cast<std::size_t>(2 * axes - 1);
    out.clear();
    out.reserve(e.cut.size() / per);
    for (const std::int64_t* v = e.cut.data(); v != e.cut.data() + e.cut.size();) {
        Segment& seg = out.emplace_back();  // zeros: the axes beyond `axes`
        for (int a = 0; a < axes; ++a) seg.delta[a] = *v++;
        for (int a = 0; a + 1 < axes; ++a) seg.phase[a] = *v++;
    }
    return true;
}

void CutCache::insert(std::uint64_t h, std::span<const Step> steps, BlockCut kind, Profile p, int axes,
                      const std::vector<Segment>& cut) {
    const auto per = static_cast<std::size_t>(2 * axes - 1);
    const std::size_t bytes = steps.size_bytes() + cut.size() * per * sizeof(std::int64_t);
    if (bytes > budget_ / 4) return;
    // Only what find() restores (a segment with more is not kept), written
    // before the lock.
    std::vector<std::int64_t> flat(cut.size() * per);
    std::int64_t* v = flat.data();
    for (const Segment& seg : cut) {
        for (int a = 0; a < axes; ++a) *v++ = seg.delta[a];
        for (int a = 0; a + 1 < axes; ++a) *v++ = seg.phase[a];
        for (int a = axes; a < kMaxAxes; ++a)
            if (seg.delta[a] != 0 || seg.phase[a - 1] != 0) return;
    }
    const std::lock_guard<std::mutex> lock(mutex_);
    auto [it, added] = map_.try_emplace(h);
    if (!added) return;
    it->second.steps.assign(steps.begin(), steps.end());
    it->second.cut = std::move(flat);
    it->second.key = key_of(kind, p, axes);
    order_.push_back(h);
    bytes_ += bytes;
    while (bytes_ > budget_) {
        const auto old = map_.find(order_.front());
        bytes_ -= bytes_of(old->second);
        map_.erase(old);
        order_.pop_front();
    }
}

std::size_t CutCache::size() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return bytes_;
}

Result<void> cut_block_cached(std::span<const Chain> chains, int axes, Profile p, BlockCut kind,
                              std::vector<std::vector<Segment>>& out, CutCache* cache, SegmentStats* stats,
                              std::uint64_t first_chain, bool accepted) {
    auto cut = accepted ? cut_accepted_block : cut_block;
    if (!cache || (kind != BlockCut::greedy && kind != BlockCut::default_phase))
        return cut(chains, axes, p, kind, out, stats, first_chain);
    out.assign(chains.size(), {});
    std::vector<std::vector<Segment>> one;
    // Chain by chain, so that a chain repeated within the block finds the
    // cut of its first copy.
    for (std::size_t c = 0; c < chains.size(); ++c) {
        const std::span<const Step> steps = chains[c].steps;
        const bool cached = steps.size() >= kCutCacheMinSteps;
        const std::uint64_t h = cached ? CutCache::hash(steps, kind, p, axes) : 0;
        if (cached && cache->find(h, steps, kind, p, axes, out[c])) continue;
        if (auto r = cut(chains.subspan(c, 1), axes, p, kind, one, stats, first_chain + c); !r) return r;
        out[c] = std::move(one[0]);
        if (cached) cache->insert(h, steps, kind, p, axes, out[c]);
    }
    return {};
}

}  // namespace stepzip::stz
