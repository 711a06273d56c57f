// Mixed predictions of the strong tier (docs/FORMAT.md "Mixed predictions",
// block type 6): every binary decision of the segment and step models is
// predicted by its own adaptive context (the `Prob` the type 3/4 coder uses)
// and by a few hashed context models that the coder names per item; the
// predictions are mixed in the logistic domain by online-learned weights
// chosen by a small context, and refined by an adaptive probability map.
// The idea is lpaq1's (a mixer of stretched probabilities trained by the
// coding error, then secondary estimation), applied to the models' binary
// decisions instead of bytes. Integer arithmetic only: any decoder that
// follows FORMAT.md reproduces every probability.
//
// `MixEncIo` / `MixDecIo` stand in for `EncIo` / `DecIo`: the same coder
// templates run with either, so a type 6 payload and a type 3/4 payload
// differ only in the probabilities given to the range coder.
// Complexity: O(models) per bit; memory ~ kMixMatchModels * 4 MiB + 4 MiB
// (the hashed tables kept per thread, see thread_tables()).
// Not thread-safe: a predictor is made, used and destroyed by one thread.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif
#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>
#define STEPZIP_MIX_AVX2 1
#endif

#include "range_coder.hpp"

namespace stepzip::stz {

/// Hashed context models of a predictor: kMixBaseModels, or kMixMaxModels
/// with the curvature flag (docs/FORMAT.md 1.11.1), or kMixMatchModels (the
/// tick block's match flag, docs/FORMAT.md 1.13 "Match").
inline constexpr int kMixBaseModels = 6;
inline constexpr int kMixMaxModels = 8;
inline constexpr int kMixMatchModels = 9;
/// log2 of the entries of each hashed table; a predictor may take up to
/// kMixMaxTableBits (MixGuide::table_bits: the tick block's planner model
/// on large blocks, docs/FORMAT.md 1.16).
inline constexpr int kMixTableBits = 20;
inline constexpr int kMixMaxTableBits = 21;
/// Weight sets of each of the two mixers: 16 fields x 16 classes (mixer 1:
/// the slot's low 4 bits; mixer 2: the primary prediction's confidence).
inline constexpr int kMixSets = 256;
/// Rows of the adaptive probability map (by slot).
inline constexpr int kApmRows = 1 << 12;

/// A predictor steered by its coder (the tick block's guided flag,
/// docs/FORMAT.md 1.13 "Guided mixing"): `rows` rows of a second adaptive
/// probability map whose row the coder names per decision (guide()), and
/// the learning rates of the mixers and of both maps. The default is the
/// unguided predictor of every other coder.
struct MixGuide {
    int rows = 0;
    std::int64_t rate = 3;  // a weight moves by input * error * rate / 2^16
    int apm_rate = 7;       // a map's point moves by 1/2^apm_rate of its error
    int table_bits = kMixTableBits;  // log2 of each hashed table's entries used
    int sure_rows = 0;               // rows of the sure decisions' map (sure_row())
};

namespace mixdetail {
// squash(x) = 65536 / (1 + e^(-x/256)) at x = -2048, -1920, ..., 2048.
inline constexpr std::int32_t kSquashPoints[33] = {
    22,    36,    60,    98,    162,   267,   439,   720,   1179,  1921,  3108,
    4971,  7812,  11955, 17625, 24743, 32768, 40793, 47911, 53581, 57724, 60565,
    62428, 63615, 64357, 64816, 65097, 65269, 65374, 65438, 65476, 65500, 65514};

/// squash on -2047..2047: linear interpolation between the 33 points.
constexpr std::int32_t squash_points(std::int32_t x) {
    const std::int32_t i = (x + 2048) >> 7, w = (x + 2048) & 127;
    return (kSquashPoints[i] * (128 - w) + kSquashPoints[i + 1] * w + 64) >> 7;
}

/// squash_points at every x of -2047..2047 (8 KiB: the models call squash
/// up to three times a coded bit; the table is read in L1).
struct SquashTable {
    std::uint16_t v[4095];
    constexpr SquashTable() : v() {
        for (std::int32_t x = -2047; x <= 2047; ++x) v[x + 2047] = static_cast<std::uint16_t>(squash_points(x));
    }
};
inline constexpr SquashTable kSquash{};

/// squash(x) of an x already within -2047..2047.
[[gnu::always_inline]] constexpr std::int32_t squash_within(std::int32_t x) noexcept { return kSquash.v[x + 2047]; }

/// Probability of a 1 (1..65535) of a stretched value x (clamped to +-2047).
constexpr std::int32_t squash(std::int32_t x) {
    if (x > 2047) x = 2047;
    if (x < -2047) x = -2047;
    return squash_within(x);
}

/// Adaptive probability maps (the mixed coders' last stage): a row of 33
/// points over the stretched domain, 128 apart, each a probability of a 1
/// in 1/65536; every row is kApmFirstRow at first. apm_refine() reads row
/// `r` at y (-2048..2047) between its two nearest points and points `at` at
/// the nearer one; apm_train() moves that point toward the bit by 1/2^rate.
inline constexpr std::array<std::uint16_t, 33> kApmFirstRow = [] {
    std::array<std::uint16_t, 33> a{};
    for (int j = 0; j < 33; ++j) a[static_cast<std::size_t>(j)] = static_cast<std::uint16_t>(squash((j - 16) * 128));
    return a;
}();
[[gnu::always_inline]] inline std::int32_t apm_refine(std::uint16_t* r, std::int32_t y, std::uint16_t*& at) noexcept {
    const std::int32_t pos = y + 2048;
    const std::int32_t j = pos >> 7, frac = pos & 127;
    at = &r[j + (frac >> 6)];
    return (r[j] * (128 - frac) + r[j + 1] * frac) >> 7;
}
[[gnu::always_inline]] inline void apm_train(std::uint16_t* at, int bit, int rate) noexcept {
    const std::int32_t target = bit ? 65535 : 0;
    *at = static_cast<std::uint16_t>(*at + ((target - *at) >> rate));
}

/// stretch(p) = the smallest x in -2047..2047 with squash(x) >> 4 >= p >> 4
/// (2047 when none): the inverse of squash on 12-bit probabilities.
struct StretchTable {
    std::int16_t v[4096];
    constexpr StretchTable() : v() {
        int next = 0;
        for (std::int32_t x = -2047; x <= 2047; ++x) {
            const int top = squash(x) >> 4;
            for (; next <= top; ++next) v[next] = static_cast<std::int16_t>(x);
        }
        for (; next < 4096; ++next) v[next] = 2047;
    }
};
inline constexpr StretchTable kStretch{};

/// 2^16 / (n + 1.5) for n = 0..N-1: the rate of an adaptive counter seen n
/// times (lpaq1's StateMap), read by the context-mixing step model and the
/// CM raw block.
template <int N>
struct RecipTable {
    std::int32_t v[N];
    constexpr RecipTable() : v() {
        for (int n = 0; n < N; ++n) v[n] = static_cast<std::int32_t>(131072 / (2 * n + 3));
    }
};

// The hashed models' adaptation: as section 1.4's with the shift capped at
// 6 instead of 5 (they see fewer bits each).
inline constexpr detail::ShiftTable<6> kSlowShift{};

// A hashed model's context: p XOR 0x8000 (so that all-zero memory is the
// initial p = 32768, n = 0, and a table costs only the pages it touches).
struct HashedProb {
    std::uint16_t px;
    std::uint16_t n;
    std::uint32_t p() const noexcept { return px ^ 0x8000u; }
};

[[gnu::always_inline]] inline void update_slow(HashedProb& pr, int bit) noexcept {
    const unsigned shift = kSlowShift.v[pr.n];
    const unsigned p = pr.p();
    pr.px = static_cast<std::uint16_t>((bit ? p - (p >> shift) : p + ((65536u - p) >> shift)) ^ 0x8000u);
    pr.n = static_cast<std::uint16_t>(pr.n + (pr.n < 255));
}

// Fresh zero memory of `bytes`, aligned to 64 bytes; on Linux in 2 MiB
// pages where the kernel allows (madvise; not on every kernel): tables read
// and written anywhere cost a page fault per page first touched and, in
// 4 KiB pages, a TLB miss on most accesses (the mixed predictor's tables,
// step_cm.cpp's rows).
class ZeroPages {
public:
    explicit ZeroPages(std::size_t bytes) {
#if defined(__linux__)
        size_ = bytes + kHuge;
        void* m = mmap(nullptr, size_, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (m == MAP_FAILED) throw std::bad_alloc();
        map_ = m;
        const std::uintptr_t a = (reinterpret_cast<std::uintptr_t>(m) + kHuge - 1) & ~(kHuge - 1);
        madvise(reinterpret_cast<void*>(a), bytes, MADV_HUGEPAGE);
#else
        // (calloc of a fresh block this large maps zero pages that cost
        // only where they are touched)
        map_ = std::calloc(bytes + 64, 1);
        if (!map_) throw std::bad_alloc();
        const std::uintptr_t a = (reinterpret_cast<std::uintptr_t>(map_) + 63) & ~std::uintptr_t{63};
#endif
        data_ = reinterpret_cast<void*>(a);
    }
    ZeroPages(const ZeroPages&) = delete;
    ZeroPages& operator=(const ZeroPages&) = delete;
    ~ZeroPages() {
#if defined(__linux__)
        munmap(map_, size_);
#else
        std::free(map_);
#endif
    }
    void* data() const noexcept { return data_; }

private:
    static constexpr std::uintptr_t kHuge = std::uintptr_t{1} << 21;
    void* map_ = nullptr;
    void* data_ = nullptr;
    std::size_t size_ = 0;
};

// The hashed tables of all models: kMixMatchModels << kMixMaxTableBits entries
// (a predictor of fewer table bits uses the first 2^bits of each model's part),
// all zero (p = 32768, n = 0) when a predictor takes them. Dirty flags of
// 2^kChunkBits entries (4 KiB) tell which parts a predictor wrote, so that
// giving the tables back clears only those: a block dirties at most eight
// 4 KiB parts per mixed decision, where 64 KiB parts made a block of a few
// hundred decisions clear most of the 32 MiB (a library caller compressing
// many small timed logs in one process, the fuzz targets). In 2 MiB pages (ZeroPages): a
// block of a few thousand segments touches every 4 KiB page of the 32 MiB,
// 8192 page faults (most of -L 19's system time on a 25 KB file) against 16.
struct HashedTables {
    static constexpr std::size_t kEntries = static_cast<std::size_t>(kMixMatchModels) << kMixMaxTableBits;
    static constexpr int kChunkBits = 10;
    static constexpr std::size_t kChunks = kEntries >> kChunkBits;

    /// Back to all zero: only the chunks flagged dirty are cleared.
    void clear() noexcept {
        for (std::size_t c = 0; c < kChunks; ++c)
            if (dirty[c]) {
                std::memset(static_cast<void*>(entries + (c << kChunkBits)), 0, sizeof(HashedProb) << kChunkBits);
                dirty[c] = 0;
            }
    }

    ZeroPages pages{kEntries * sizeof(HashedProb)};
    HashedProb* entries = static_cast<HashedProb*>(pages.data());
    std::array<std::uint8_t, kChunks> dirty{};
    bool busy = false;
};

// The tables of the calling thread, kept from one predictor to the next
// (a block's trials and its proof build several predictors in turn; new
// tables each time cost a page fault per 4 KiB touched, more than the
// coding of a small block). A predictor made while another of the same
// thread holds them gets tables of its own.
inline HashedTables& thread_tables() {
    thread_local HashedTables tables;
    return tables;
}

#if defined(STEPZIP_MIX_AVX2)
// The loops of mix_dot() and mix_train() eight weights at a time, where the
// CPU has AVX2: the same integers (every product and sum exact, the shift
// arithmetic). N: a multiple of 8.
template <int N>
[[gnu::target("avx2")]] std::int64_t dot_avx2(const std::int32_t* w, const std::int32_t* x) {
    __m256i acc = _mm256_setzero_si256();
    for (int k = 0; k < N; k += 8) {
        const __m256i a = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(w + k));
        const __m256i b = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(x + k));
        // the even lanes' products, then the odd lanes' (signed 32 x 32 -> 64)
        acc = _mm256_add_epi64(acc, _mm256_mul_epi32(a, b));
        acc = _mm256_add_epi64(acc, _mm256_mul_epi32(_mm256_srli_epi64(a, 32), _mm256_srli_epi64(b, 32)));
    }
    const __m128i s = _mm_add_epi64(_mm256_castsi256_si128(acc), _mm256_extracti128_si256(acc, 1));
    return _mm_cvtsi128_si64(s) + _mm_extract_epi64(s, 1);
}
template <int N>
[[gnu::target("avx2")]] void train_avx2(std::int32_t* w, const std::int32_t* x, std::int32_t err, std::int32_t limit) {
    const __m256i e = _mm256_set1_epi32(err), hi = _mm256_set1_epi32(limit), lo = _mm256_set1_epi32(-limit);
    for (int k = 0; k < N; k += 8) {
        const __m256i xv = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(x + k));
        const __m256i v = _mm256_add_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(w + k)),
                                           _mm256_srai_epi32(_mm256_mullo_epi32(xv, e), 16));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(w + k), _mm256_max_epi32(lo, _mm256_min_epi32(v, hi)));
    }
}
inline const bool kHasAvx2 = __builtin_cpu_supports("avx2");
#endif
}  // namespace mixdetail

/// A mixer's dot product over a weight set of stride N: the sum of w[k]·x[k]
/// for k < n in 64 bits. The inputs from n to N must be 0 (the AVX2 loop
/// reads them when N is a multiple of 8).
template <int N>
[[gnu::always_inline]] inline std::int64_t mix_dot(const std::int32_t* w, const std::int32_t* x, int n) noexcept {
#if defined(STEPZIP_MIX_AVX2)
    if constexpr (N % 8 == 0) {
        if (mixdetail::kHasAvx2) return mixdetail::dot_avx2<N>(w, x);
    }
#endif
    std::int64_t d = 0;
    for (int k = 0; k < n; ++k) d += static_cast<std::int64_t>(w[k]) * x[k];
    return d;
}
/// A mixer's update over the same: w[k] = clamp(w[k] + ((x[k]·err) >> 16),
/// -limit, limit) for k < n. Precondition: every x[k]·err fits in 32 bits
/// (the callers' static_asserts), w[k] + the step too.
template <int N>
[[gnu::always_inline]] inline void mix_train(std::int32_t* w, const std::int32_t* x, std::int32_t err, std::int32_t limit,
                                             int n) noexcept {
#if defined(STEPZIP_MIX_AVX2)
    if constexpr (N % 8 == 0) {
        if (mixdetail::kHasAvx2) return mixdetail::train_avx2<N>(w, x, err, limit);
    }
#endif
    for (int k = 0; k < n; ++k) w[k] = std::clamp(w[k] + ((x[k] * err) >> 16), -limit, limit);
}

/// Stretched probability of a 1, p1 in 1..65535 (16-bit).
[[gnu::always_inline]] inline std::int32_t stretch(std::uint32_t p1) noexcept {
    return mixdetail::kStretch.v[p1 >> 4];
}

/// The mixing predictor of one block (docs/FORMAT.md "Mixed predictions").
class MixPredictor {
public:
    /// `models` (kMixBaseModels, kMixMaxModels or kMixMatchModels) hashed
    /// context models;
    /// `base`: the coder's table of primary contexts (a decision's slot is
    /// its primary context's index in it).
    /// `guide`: MixGuide's rows and rates.
    MixPredictor(const Prob* base, int models, const MixGuide& guide = {})
        : n_(models), bits_(guide.table_bits), rate_(guide.rate), apm_rate_(guide.apm_rate), base_(base),
          apm_(static_cast<std::size_t>(kApmRows + guide.rows + guide.sure_rows) * 33), rows2_(guide.rows),
          sure_rows_(guide.sure_rows) {
        mixdetail::HashedTables& shared = mixdetail::thread_tables();
        if (shared.busy) {
            own_ = std::make_unique<mixdetail::HashedTables>();
            store_ = own_.get();
        } else {
            store_ = &shared;
        }
        store_->busy = true;
        tables_ = store_->entries;
        dirty_ = store_->dirty.data();
        for (int s = 0; s < 2 * kMixSets; ++s) {
            std::int32_t* w = &weights_[static_cast<std::size_t>(s) * kInputs];
            w[0] = kPrimaryWeight;
            for (int k = 1; k <= n_; ++k) w[k] = kModelWeight;
            for (int k = 0; k < kDirectInputs; ++k) w[kDirect + k] = kModelWeight;
        }
        // Every row of the maps starts the same.
        for (std::size_t r = 0; r < static_cast<std::size_t>(kApmRows + rows2_ + sure_rows_); ++r)
            std::memcpy(&apm_[r * 33], mixdetail::kApmFirstRow.data(), sizeof mixdetail::kApmFirstRow);
    }
    MixPredictor(const MixPredictor&) = delete;
    MixPredictor& operator=(const MixPredictor&) = delete;
    ~MixPredictor() {
        store_->clear();
        store_->busy = false;
    }

    /// The context of hashed model k (0 <= k < models) until it is set again.
    void set_context(int k, std::uint64_t v) noexcept {
        hash_[static_cast<std::size_t>(k)] = (v + static_cast<std::uint64_t>(k + 1)) * kHashA;
    }
    /// The field of the next decisions (0..15): selects the weight set;
    /// ends a guide().
    void select(int field) noexcept {
        field_ = field & 15;
        set1_ = set2_ = row2_ = sure_row_ = -1;
        for (int k = 0; k < kDirectInputs; ++k) x_[static_cast<std::size_t>(kDirect + k)] = 0;
    }
    /// Until the next select(): the mixers' direct input k (0 or 1), a
    /// stretched probability of a 1 (-2047..2047) that the coder computed
    /// itself (the tick block's planner model and its slot lines); 0
    /// otherwise, which leaves the mix as without it.
    void direct(int k, std::int32_t stretched) noexcept { x_[static_cast<std::size_t>(kDirect + k)] = stretched; }
    /// Until the next select(): a sure decision (mix_sure()) is coded with
    /// its context's probability and row `row` (0..MixGuide::sure_rows-1)
    /// of the sure decisions' map averaged, and the map learns (sure_p(),
    /// sure_train()); without it, with its context's alone.
    void sure_row(int row) noexcept { sure_row_ = sure_rows_ > 0 ? row % sure_rows_ : -1; }
    bool sure_mapped() const noexcept { return sure_row_ >= 0; }
    /// The probability (1..65535) of a 1 of a sure decision of context
    /// `pr` by sure_row()'s row (when sure_mapped()).
    [[gnu::always_inline]] std::uint32_t sure_p(const Prob& pr) noexcept {
        const std::int32_t p1 = static_cast<std::int32_t>(65536u - pr.p);
        const std::int32_t r = mixdetail::apm_refine(
            &apm_[static_cast<std::size_t>(kApmRows + rows2_ + sure_row_) * 33], stretch(static_cast<std::uint32_t>(p1)), sure_at_);
        return static_cast<std::uint32_t>(std::clamp((p1 + r) >> 1, 1, 65535));
    }
    /// Trains the row sure_p() read, and the context, on the coded bit.
    [[gnu::always_inline]] void sure_train(Prob& pr, int bit) noexcept {
        stz::update(pr, bit);
        mixdetail::apm_train(sure_at_, bit, kSureRate);
    }
    /// Until the next select(): mixer 1 mixes with weight set `set1` and
    /// mixer 2 with `set2` (each 0..kMixSets-1 of its mixer) in place of
    /// the field's sets chosen by the slot and by the confidence, and row
    /// `row` (0..MixGuide::rows-1) of the second map refines the mix too.
    void guide(int set1, int set2, int row) noexcept {
        set1_ = set1 & (kMixSets - 1);
        set2_ = set2 & (kMixSets - 1);
        row2_ = rows2_ > 0 ? row % rows2_ : -1;
    }

    /// Probability (1..65535) that the decision of primary context `pr` is 1.
    [[gnu::always_inline]] std::uint32_t predict(const Prob& pr) noexcept {
        if (n_ == kMixMatchModels) return predict_n<kMixMatchModels>(pr);
        return n_ == kMixMaxModels ? predict_n<kMixMaxModels>(pr) : predict_n<kMixBaseModels>(pr);
    }

    /// Trains every part on the coded bit (after predict()).
    [[gnu::always_inline]] void update(Prob& pr, int bit) noexcept {
        if (n_ == kMixMatchModels) update_n<kMixMatchModels>(pr, bit);
        else if (n_ == kMixMaxModels) update_n<kMixMaxModels>(pr, bit);
        else update_n<kMixBaseModels>(pr, bit);
    }

private:
    template <int N>
    [[gnu::always_inline]] std::uint32_t predict_n(const Prob& pr) noexcept {
        const std::uint64_t slot =
            (reinterpret_cast<std::uintptr_t>(&pr) - reinterpret_cast<std::uintptr_t>(base_)) / sizeof(Prob);
        const std::uint64_t group = slot >> 4;
        const std::size_t low = static_cast<std::size_t>(slot & 15);
        x_[0] = stretch(65536u - pr.p);
        for (int k = 0; k < N; ++k) {
            const std::uint64_t h = (hash_[static_cast<std::size_t>(k)] ^ (group * kHashB)) * kHashA;
            const std::size_t i = ((static_cast<std::size_t>(k) << kMixMaxTableBits) |
                                   (static_cast<std::size_t>(h >> (64 - (bits_ - 4))) << 4)) | low;
            entry_[static_cast<std::size_t>(k)] = &tables_[i];
            dirty_[i >> mixdetail::HashedTables::kChunkBits] = 1;
            x_[static_cast<std::size_t>(k) + 1] = stretch(65536u - tables_[i].p());
        }
        x_[static_cast<std::size_t>(N) + 1] = 256;
        // Two mixers, each its weight set's dot product; their outputs averaged.
        const std::size_t set1 = set1_ >= 0 ? static_cast<std::size_t>(set1_) : static_cast<std::size_t>(field_) * 16 + low;
        const std::size_t set2 = set2_ >= 0 ? static_cast<std::size_t>(set2_)
                                            : static_cast<std::size_t>(field_ * 16) + static_cast<std::size_t>((x_[0] + 2048) >> 8 >> 1);
        w1_ = &weights_[set1 * kInputs];
        w2_ = &weights_[(kMixSets + set2) * kInputs];
        const std::int32_t s1 = dot<N>(w1_), s2 = dot<N>(w2_);
        // (dot() clamps to +-2047)
        out1_ = mixdetail::squash_within(s1);
        out2_ = mixdetail::squash_within(s2);
        const std::int32_t s = (s1 + s2) >> 1;
        const std::int32_t mixed = mixdetail::squash_within(s);
        // Adaptive probability map on the slot: interpolated between the two
        // nearest of 33 points; the nearer one is trained.
        const std::int32_t refined = mixdetail::apm_refine(&apm_[static_cast<std::size_t>(slot & (kApmRows - 1)) * 33], s, apm_at_);
        std::int32_t p = (mixed + 3 * refined) >> 2;
        apm2_at_ = nullptr;
        if (row2_ >= 0) {
            // guide(): the second map's row, at the same points; the mix a
            // quarter, the first map a quarter, the second a half.
            const std::int32_t refined2 = mixdetail::apm_refine(&apm_[static_cast<std::size_t>(kApmRows + row2_) * 33], s, apm2_at_);
            p = (mixed + refined + 2 * refined2) >> 2;
        }
        if (p < 1) p = 1;
        if (p > 65535) p = 65535;
        return static_cast<std::uint32_t>(p);
    }

    template <int N>
    [[gnu::always_inline]] void update_n(Prob& pr, int bit) noexcept {
        train<N>(w1_, out1_, bit);
        train<N>(w2_, out2_, bit);
        stz::update(pr, bit);
        for (int k = 0; k < N; ++k) mixdetail::update_slow(*entry_[static_cast<std::size_t>(k)], bit);
        mixdetail::apm_train(apm_at_, bit, apm_rate_);
        if (apm2_at_) mixdetail::apm_train(apm2_at_, bit, apm_rate_);
    }

    // A mixer's output, stretched: the dot product of its weights (16.16
    // fixed point) and the inputs, clamped to +-2047.
    template <int N>
    [[gnu::always_inline]] std::int32_t dot(const std::int32_t* w) const noexcept {
        std::int64_t d = 0;
        for (int k = 0; k <= N + 1; ++k) d += static_cast<std::int64_t>(w[k]) * x_[static_cast<std::size_t>(k)];
        for (int k = kDirect; k < kInputs; ++k) d += static_cast<std::int64_t>(w[k]) * x_[static_cast<std::size_t>(k)];
        d >>= 16;
        return static_cast<std::int32_t>(d > 2047 ? 2047 : d < -2047 ? -2047 : d);
    }
    // Each weight moves by input * error * rate_ / 2^16, the error that of
    // the mixer's own output; weights stay within +-kMaxWeight.
    template <int N>
    [[gnu::always_inline]] void train(std::int32_t* w, std::int32_t out, int bit) noexcept {
        const std::int64_t err = ((static_cast<std::int64_t>(bit) << 16) - out) * rate_;
        const auto step = [&](int k) {
            std::int64_t v = w[k] + ((x_[static_cast<std::size_t>(k)] * err) >> 16);
            if (v > kMaxWeight) v = kMaxWeight;
            if (v < -kMaxWeight) v = -kMaxWeight;
            w[k] = static_cast<std::int32_t>(v);
        };
        for (int k = 0; k <= N + 1; ++k) step(k);
        for (int k = kDirect; k < kInputs; ++k) step(k);
    }

    // Inputs: the primary, the models, the bias, and the direct inputs last
    // (their weights from kDirect on whatever the models).
    static constexpr int kDirectInputs = 2;
    static constexpr int kDirect = kMixMatchModels + 2;
    static constexpr int kInputs = kDirect + kDirectInputs;
    // The sure decisions' map learns at 1/2^kSureRate (chosen on the timed
    // streams of docs/benchmarks.md "Timed streams: the planner model").
    static constexpr int kSureRate = 8;
    // Chosen on corpora/glyphs/dejavu-8.fc, plotter/hershey-grbl.fc and
    // random/walk-8.fc (docs/benchmarks.md).
    static constexpr std::int32_t kPrimaryWeight = 40960;  // 0.625
    static constexpr std::int32_t kModelWeight = 12288;    // 0.1875
    static constexpr std::int32_t kMaxWeight = 1 << 22;
    static constexpr std::uint64_t kHashA = 0x9E3779B97F4A7C15ull, kHashB = 0xD6E8FEB86659FD93ull;

    int n_;     // hashed models in use
    int bits_;  // MixGuide::table_bits
    std::int64_t rate_;  // MixGuide
    int apm_rate_;

    const Prob* base_;
    std::unique_ptr<mixdetail::HashedTables> own_;  // when the thread's tables are taken
    mixdetail::HashedTables* store_ = nullptr;
    mixdetail::HashedProb* tables_ = nullptr;
    std::uint8_t* dirty_ = nullptr;
    // kApmRows rows by slot, then MixGuide::rows for guide(), then
    // MixGuide::sure_rows for sure_row()
    std::vector<std::uint16_t> apm_;
    int rows2_;
    int sure_rows_;
    std::array<std::int32_t, static_cast<std::size_t>(2 * kMixSets) * kInputs> weights_{};
    std::array<std::uint64_t, kMixMatchModels> hash_{};
    std::array<std::int32_t, kInputs> x_{};
    std::array<mixdetail::HashedProb*, kMixMatchModels> entry_{};
    std::int32_t* w1_ = nullptr;
    std::int32_t* w2_ = nullptr;
    std::int32_t out1_ = 32768, out2_ = 32768;
    std::uint16_t* apm_at_ = nullptr;
    std::uint16_t* apm2_at_ = nullptr;
    std::uint16_t* sure_at_ = nullptr;
    int field_ = 0;
    int set1_ = -1, set2_ = -1, row2_ = -1;  // guide()
    int sure_row_ = -1;                       // sure_row()
};

/// Sure decisions (the tick block's coding 2, docs/FORMAT.md 1.13): with
/// `sure` > 0, a decision whose primary context gives its less likely bit
/// a probability of at most sure / 65536 is coded in that context alone,
/// as in a type 3 block, and nothing of the mixer sees it. On a controller's
/// log most ticks are such decisions (an axis that cannot step yet), and
/// mixing them costs most of the coding's time.
[[gnu::always_inline]] inline bool mix_sure(const Prob& p, std::uint32_t sure) noexcept {
    return p.p <= sure || p.p >= 65536u - sure;
}

/// Range encoder driven by a MixPredictor (the predictor outlives it).
struct MixEncIo {
    static constexpr bool kDecode = false;
    static constexpr bool kMixed = true;
    RangeEncoder rc;
    bool failed = false;
    MixPredictor* m = nullptr;
    bool curvature = false;  // the coder adds the curvature models (FORMAT.md 1.11.1)
    std::uint32_t sure = 0;  // see mix_sure()
    void field(int k) { m->select(k); }
    [[gnu::always_inline]] int bit(Prob& p, int b) {
        if (mix_sure(p, sure)) {
            if (m->sure_mapped()) {
                rc.encode_p(65536u - m->sure_p(p), b);
                m->sure_train(p, b);
            } else {
                rc.encode(p, b);
            }
            return b;
        }
        rc.encode_p(65536u - m->predict(p), b);
        m->update(p, b);
        return b;
    }
};

/// Range decoder driven by a MixPredictor. Copies share the predictor.
struct MixDecIo {
    static constexpr bool kDecode = true;
    static constexpr bool kMixed = true;
    MixDecIo(std::string_view in, MixPredictor* pred) : rc(in), m(pred) {}
    RangeDecoder rc;
    bool failed = false;
    MixPredictor* m = nullptr;
    bool curvature = false;  // the coder adds the curvature models (FORMAT.md 1.11.1)
    std::uint32_t sure = 0;  // see mix_sure()
    void field(int k) { m->select(k); }
    [[gnu::always_inline]] int bit(Prob& p, int) {
        if (mix_sure(p, sure)) {
            if (!m->sure_mapped()) return rc.decode(p);
            const int b = rc.decode_p(65536u - m->sure_p(p));
            m->sure_train(p, b);
            return b;
        }
        const int b = rc.decode_p(65536u - m->predict(p));
        m->update(p, b);
        return b;
    }
};

/// Whether `Io` codes with mixed predictions (block type 6).
template <class Io>
inline constexpr bool kMixedIo = requires { Io::kMixed; };

/// The coders name their hashed contexts through this; a no-op for the
/// type 3/4 Io types.
template <class Io>
[[gnu::always_inline]] inline void mix_context(Io& io, int k, std::uint64_t v) {
    if constexpr (kMixedIo<Io>) io.m->set_context(k, v);
}

/// A context value made of several parts (any deterministic combination
/// would do; this one is FORMAT.md's).
inline constexpr std::uint64_t ctx_join(std::uint64_t h, std::uint64_t v) noexcept {
    return (h ^ v) * 0x100000001B3ull + 0x9E37u;
}

}  // namespace stepzip::stz
