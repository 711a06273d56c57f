// The CM raw block; see raw_cm.hpp and docs/FORMAT.md 1.15.
// Complexity: O(kContexts) per bit, one hashed bucket (half a cache line)
// per context per nibble; memory: the hashed buckets (32 B each, 2^12 to
// 2^20 by the declared size), the match table (4 B an entry, 2^10 to 2^22),
// 4.6 MiB of maps and 256 KiB of order-1 counters, all fixed by the declared
// size before anything is decoded.
#include "raw_cm.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "mix.hpp"
#include "range_coder.hpp"
#include "../common/bytes.hpp"


namespace stepzip::stz {

using wire::Cursor;
using wire::put_u8;
using wire::put_varint;

namespace {


constexpr std::uint64_t kRawCmMaxSize = std::uint64_t{kMaxBlockBytes} + 20;
constexpr int kContexts = 7;           // hashed context models
constexpr int kInputs = kContexts + 4; // + order 1, order 0, match, bias
constexpr std::uint64_t kHashA = 0x9E3779B97F4A7C15ull, kHashB = 0xD6E8FEB86659FD93ull;

// Adaptive rate of a counter seen n times: 65536 / (n + 1.5).
constexpr mixdetail::RecipTable<1024> kRate{};

// A 4-bit count n's successor, saturating at `Limit`.
template <unsigned Limit>
struct NextCount {
    std::uint16_t v[16];
    constexpr NextCount() : v() {
        for (unsigned n = 0; n < 16; ++n) v[n] = static_cast<std::uint16_t>(n + (n < Limit));
    }
};

// A counter: probability of a 1 (16 bits, stored XOR 0x8000 so that zero
// memory is p = 32768) and how often it was seen (saturating at `limit`).
// (p XOR 0x8000 is p - 32768 as a signed 16-bit number: the arithmetic
// below works on that, with the same bits stored.)
struct Counter {
    std::uint16_t px;
    std::uint16_t n;
    std::int32_t p() const noexcept { return static_cast<std::int16_t>(px) + 32768; }
    [[gnu::always_inline]] void update(int bit, int limit) noexcept {
        const std::int32_t s = static_cast<std::int16_t>(px);
        const std::int32_t target = bit ? 65535 - 32768 : -32768;
        const std::int32_t q = s + static_cast<std::int32_t>((static_cast<std::int64_t>(target - s) * kRate.v[n]) >> 16);
        px = static_cast<std::uint16_t>(q);
        if (n < limit) ++n;
    }
};

// A hashed context's counter in 16 bits: the probability of a 1 in 1/4096
// (12 bits, stored XOR 0x800 so that zero memory is p = 2048) and how often
// it was seen (4 bits, saturating at `Limit` <= 15). (The stored 12 bits
// are p - 2048 as a signed 12-bit number, the top of a signed 16-bit one.)
struct SmallCounter {
    std::uint16_t v;
    std::int32_t s() const noexcept { return static_cast<std::int16_t>(v) >> 4; }  // p - 2048
    std::int32_t p() const noexcept { return s() + 2048; }
    unsigned n() const noexcept { return v & 15u; }
    template <unsigned Limit>
    [[gnu::always_inline]] void update(int bit) noexcept {
        static constexpr NextCount<Limit> kNext{};
        const std::int32_t s1 = s();
        const std::int32_t target = bit ? 4095 - 2048 : -2048;
        const unsigned n0 = n();
        const std::int32_t q = s1 + (((target - s1) * kRate.v[n0]) >> 16);
        v = static_cast<std::uint16_t>((q << 4) | kNext.v[n0]);
    }
};

// A bucket: the 15 counters of one context's nibble (a binary tree, node
// 1..15) and, in entry 0, the bucket's check. Two buckets share a cache line.
struct Bucket {
    SmallCounter c[16];
};
static_assert(sizeof(Bucket) == 32);

// Adaptive probability map (mix.hpp, mixdetail::apm_refine()): its rows,
// each mixdetail::kApmFirstRow at first. A `Lazy` map writes a row when
// it is first used (a small block touches few of map 1's 65536 rows;
// filling them all cost more than coding it); the others are filled at once.
template <bool Lazy>
class Apm {
public:
    explicit Apm(std::size_t rows) : t_(new std::uint16_t[rows * 33]), ready_(Lazy ? rows : 0, 0) {
        if (!Lazy)
            for (std::size_t row = 0; row < rows; ++row) std::copy(mixdetail::kApmFirstRow.begin(), mixdetail::kApmFirstRow.end(), &t_[row * 33]);
    }
    void prefetch(std::size_t row) const noexcept {
        __builtin_prefetch(&t_[row * 33]);
        __builtin_prefetch(&t_[row * 33 + 32]);
    }
    [[gnu::always_inline]] std::int32_t refine(std::int32_t y, std::size_t row) noexcept {
        std::uint16_t* r = &t_[row * 33];
        if constexpr (Lazy) {
            if (!ready_[row]) [[unlikely]] {
                std::copy(mixdetail::kApmFirstRow.begin(), mixdetail::kApmFirstRow.end(), r);
                ready_[row] = 1;
            }
        }
        return mixdetail::apm_refine(r, y, at_);
    }
    [[gnu::always_inline]] void update(int bit, int rate) noexcept { mixdetail::apm_train(at_, bit, rate); }

private:
    std::unique_ptr<std::uint16_t[]> t_;  // (a lazy map's rows not yet used are not initialized)
    std::vector<std::uint8_t> ready_;
    std::uint16_t* at_ = nullptr;
};

constexpr std::uint64_t join(std::uint64_t h, std::uint64_t v) noexcept { return ctx_join(h, v); }

bool is_word_byte(unsigned c) noexcept {
    return (c >= '0' && c <= '9') || (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '.' || c == '-' ||
           c >= 128;
}
bool is_field_end(unsigned c) noexcept { return c == ',' || c == ';' || c == ' ' || c == '\n' || c == '\t'; }

// The model of a block of `size` bytes; `hist` holds the bytes coded so far.
class RawCmModel {
public:
    // Chosen on a generated HP-GL file (docs/benchmarks.md "CM raw block").
    static constexpr int kLimit = 12;       // hashed counters (orders 4, 6, the line contexts): rate 1/(n + 1.5), n <= 12
    static constexpr int kLimitLow = 60;    // order 1, order 0 and the match counters: n <= 60
    static constexpr int kMixRate = 8;      // weights move by x * err * 8 / 2^16
    static constexpr int kInitWeight = 22000;
    static constexpr int kApmRate = 6;
    static constexpr int kMinLen = 4;       // the match model's hash: the last 4 bytes
    static constexpr int kSkip = 2048;      // no mixer training while |err| < 2048 / 65536
    static constexpr int kVerify = 400;     // a new match is verified back this far at most
    static constexpr int kApm2Bits = 12;

    // `hist`: the block's bytes (the encoder's all of them, the decoder's
    // those decoded so far; rebase() when they move).
    RawCmModel(std::uint64_t size, const char* hist)
        : hist_(hist), apm0_(256), apm1_(65536), apm2_(std::size_t{1} << kApm2Bits) {
        int b = 12;  // (at least 2: a bucket's pair shares 128 aligned bytes)
        while (b < 20 && (std::uint64_t{1} << b) < size * 4) ++b;
        bucket_bits_ = b;
        buckets_ = std::make_unique<mixdetail::ZeroPages>((std::size_t{1} << b) * sizeof(Bucket));
        table_ = static_cast<Bucket*>(buckets_->data());
        int m = 10;
        while (m < 22 && (std::uint64_t{1} << m) < size) ++m;
        match_bits_ = m;
        match_ = std::make_unique<mixdetail::ZeroPages>((std::size_t{1} << m) * sizeof(std::uint32_t));
        mtab_ = static_cast<std::uint32_t*>(match_->data());
        for (auto& w : w1_) w = kInitWeight;
        for (auto& w : w2_) w = kInitWeight;
        for (std::size_t s = 0; s < w1_.size(); s += kInputs) w1_[s + kInputs - 1] = 0;
        for (std::size_t s = 0; s < w2_.size(); s += kInputs) w2_[s + kInputs - 1] = 0;
        byte_contexts();
        byte_finish();
    }

    /// The bytes coded so far have moved to `hist`.
    void rebase(const char* hist) noexcept { hist_ = hist; }

    /// Probability (1..65535) that the next bit is 1.
    [[gnu::always_inline]] std::int32_t predict() noexcept {
        const std::size_t row1 = row1_, row2 = row2_;
        // (a counter never seen is all zero, p = 2048, whose stretch is 0:
        // the input of a context not seen is 0)
        static_assert(mixdetail::kStretch.v[2048] == 0);
        const int node = nibble_node();
        for (int k = 0; k < kContexts; ++k) {
            SmallCounter& c = bucket_[k]->c[node];
            at_[k] = &c;
            x_[static_cast<std::size_t>(k)] = mixdetail::kStretch.v[c.p()];
        }
        o1_at_ = &o1_[((c4_ & 0xFFu) << 8) | c0_];
        x_[kContexts] = stretch(static_cast<std::uint32_t>(o1_at_->p()));
        x_[kContexts + 1] = stretch(static_cast<std::uint32_t>(o0_[c0_].p()));
        // Match model: the bit of the byte after the longest earlier match.
        expect_ = -1;
        if (len_ > 0) {
            const unsigned e = static_cast<unsigned char>(hist_[ptr_]) | 256u;
            if ((e >> (8 - bitpos_)) == c0_) {
                expect_ = static_cast<int>((e >> (7 - bitpos_)) & 1u);
                msm_at_ = &msm_[static_cast<std::size_t>(len_bucket() * 2 + expect_)];
                x_[kContexts + 2] = stretch(static_cast<std::uint32_t>(msm_at_->p()));
            } else {
                len_ = 0;
            }
        }
        if (expect_ < 0) x_[kContexts + 2] = 0;
        x_[kContexts + 3] = 256;
        const int mq = expect_ < 0 ? 0 : len_ < 16 ? 1 : len_ < 32 ? 2 : 3;
        ws1_ = &w1_[static_cast<std::size_t>(c0_) * kInputs];
        // (mixer 2: by the match's length, the field and the place in it)
        const unsigned sel2 = static_cast<unsigned>(std::min(nfield_, 15)) * 16 +
                              std::min<unsigned>(static_cast<unsigned>(pos_ - line_ - fstart_), 15);
        ws2_ = &w2_[(static_cast<std::size_t>(mq) * 256 + sel2) * kInputs];
        dot2(ws1_, ws2_, y1_, y2_);
        const std::int32_t y = (y1_ + y2_) >> 1;
        const std::int32_t mixed = mixdetail::squash_within(y);
        const std::int32_t a0 = apm0_.refine(y, c0_);
        const std::int32_t a1 = apm1_.refine(y, row1);
        const std::int32_t a2 = apm2_.refine(y, row2);
        return std::clamp((mixed + a0 + a1 + a2) >> 2, 1, 65535);
    }

    /// Trains every part on the coded bit (after predict()). The buckets of
    /// the next nibble are asked of memory first, and taken after the
    /// training: the same result, less time waiting.
    [[gnu::always_inline]] void update(int bit) noexcept {
        const unsigned c0 = (c0_ << 1) | static_cast<unsigned>(bit);
        {
            // (the rows of the maps that refine the next bit)
            const bool last = bitpos_ == 7;
            const unsigned next_c0 = last ? 1u : c0;
            const std::uint32_t next_c4 = last ? (c4_ << 8) | (c0 & 0xFFu) : c4_;
            row1_ = apm1_row(next_c0, next_c4);
            row2_ = apm2_row(next_c0, next_c4);
            apm1_.prefetch(row1_);
            apm2_.prefetch(row2_);
        }
        if (bitpos_ == 2) {
            // (the second nibble's buckets for both values of the 4th bit)
            touch_buckets(c0 << 1);
            touch_buckets((c0 << 1) | 1u);
        } else if (bitpos_ == 6) {
            // (the next byte's order-4 and order-6 buckets for both values
            // of its last bit)
            touch_next_orders((c0 << 1) & 0xFFu);
            touch_next_orders(((c0 << 1) | 1u) & 0xFFu);
        } else if (bitpos_ == 3) {
            prefetch_buckets(c0);
        } else if (bitpos_ == 7) {
            // (the byte is in the history now: the encoder's holds the whole
            // input, the decoder's the bytes decoded)
            ++pos_;
            byte_contexts();
        }
        train(ws1_, y1_, bit, kMixRate);
        train(ws2_, y2_, bit, kMixRate);
        for (int k = 0; k < kContexts; ++k) at_[k]->update<kLimit>(bit);
        o1_at_->update(bit, kLimitLow);
        o0_[c0_].update(bit, kLimitLow);
        if (expect_ >= 0) {
            msm_at_->update(bit, kLimitLow);
            if (expect_ != bit) len_ = 0;
        }
        apm0_.update(bit, kApmRate);
        apm1_.update(bit, kApmRate);
        apm2_.update(bit, kApmRate);
        c0_ = c0;
        node_ = (node_ << 1) | static_cast<unsigned>(bit);
        ++bitpos_;
        if (bitpos_ == 4) {
            node_ = 1;
            resolve_buckets();
        } else if (bitpos_ == 8) {
            c0_ = 1;
            node_ = 1;
            bitpos_ = 0;
            byte_finish();
        }
    }

private:
    int nibble_node() const noexcept { return static_cast<int>(node_); }

    // The rows of maps 1 and 2 by the bits of the byte so far (c0) and the
    // bytes before (c4).
    static std::size_t apm1_row(unsigned c0, std::uint32_t c4) noexcept { return c0 | ((c4 & 0xFFu) << 8); }
    static std::size_t apm2_row(unsigned c0, std::uint32_t c4) noexcept {
        return static_cast<std::size_t>(((c4 & 0xFFFFu) * 0x9E3779B1u ^ c0 * 0x85EBCA6Bu) >> (32 - kApm2Bits));
    }

    int len_bucket() const noexcept { return len_ < 16 ? len_ : std::min(16 + ((len_ - 16) >> 3), 31); }

    // The two mixers' outputs: the dot products of their weights with the
    // inputs, in 16.16, clamped to +-2047.
    void dot2(const std::int32_t* w1, const std::int32_t* w2, std::int32_t& y1, std::int32_t& y2) const noexcept {
        std::int64_t d1 = 0, d2 = 0;
        for (int k = 0; k < kInputs; ++k) {
            const std::int64_t x = x_[static_cast<std::size_t>(k)];
            d1 += w1[k] * x;
            d2 += w2[k] * x;
        }
        y1 = static_cast<std::int32_t>(std::clamp<std::int64_t>(d1 >> 16, -2047, 2047));
        y2 = static_cast<std::int32_t>(std::clamp<std::int64_t>(d2 >> 16, -2047, 2047));
    }
    void train(std::int32_t* w, std::int32_t y, int bit, int rate) noexcept {
        const std::int32_t e = (bit << 16) - mixdetail::squash_within(y);
        if (e < kSkip && e > -kSkip) return;
        const std::int64_t err = static_cast<std::int64_t>(e) * rate;
        for (int k = 0; k < kInputs; ++k) {
            const std::int64_t v = w[k] + ((x_[static_cast<std::size_t>(k)] * err) >> 16);
            w[k] = static_cast<std::int32_t>(std::clamp<std::int64_t>(v, -(1 << 22), 1 << 22));
        }
    }

    // The bucket of each context for the nibble starting now (`nib`: 1 for
    // a byte's first nibble, the first nibble's bits with a leading 1 for
    // the second).
    // The two candidate buckets of each context, asked of memory at once.
    // The hash of context k's value v, and of a nibble's bucket of it.
    static std::uint64_t context_hash(std::uint64_t v, int k) noexcept { return (v + static_cast<std::uint64_t>(k + 1)) * kHashA; }
    static std::uint64_t nibble_hash(std::uint64_t h, unsigned nib) noexcept { return (h ^ (nib * kHashB)) * kHashA; }
    std::size_t bucket_of(std::uint64_t g) const noexcept { return static_cast<std::size_t>(g >> (64 - bucket_bits_)); }
    void touch(std::uint64_t g) const noexcept { __builtin_prefetch(&table_[bucket_of(g) & ~std::size_t{1}], 1); }

    void touch_buckets(unsigned nib) const noexcept {
        for (int k = 0; k < kContexts; ++k) touch(nibble_hash(hash_[static_cast<std::size_t>(k)], nib));
    }
    // (contexts 0 and 1 are the orders 4 and 6)
    void touch_next_orders(unsigned c) const noexcept {
        const std::uint64_t c8 = (c8_ << 8) | c;
        touch(nibble_hash(context_hash(c8 & 0xFFFFFFFFu, 0), 1));
        touch(nibble_hash(context_hash(c8 & 0xFFFFFFFFFFFFull, 1), 1));
    }
    void prefetch_buckets(unsigned nib) noexcept {
        for (int k = 0; k < kContexts; ++k) {
            const std::uint64_t g = nibble_hash(hash_[static_cast<std::size_t>(k)], nib);
            const std::size_t i = bucket_of(g);
            slot_[static_cast<std::size_t>(k)] = i;
            check_[static_cast<std::size_t>(k)] = static_cast<std::uint16_t>((g >> 16) | 1u);
            __builtin_prefetch(&table_[i & ~std::size_t{1}], 1);
        }
    }
    // Each context's bucket: the candidate holding its check, else the one
    // less used (node 1's count), emptied.
    void resolve_buckets() noexcept {
        for (int k = 0; k < kContexts; ++k) {
            const std::size_t i = slot_[static_cast<std::size_t>(k)];
            const std::uint16_t check = check_[static_cast<std::size_t>(k)];
            Bucket* a = &table_[i];
            Bucket* b = &table_[i ^ 1];
            Bucket* use;
            if (a->c[0].v == check) use = a;
            else if (b->c[0].v == check) use = b;
            else {
                use = b->c[1].n() < a->c[1].n() ? b : a;
                *use = Bucket{};
                use->c[0].v = check;
            }
            bucket_[k] = use;
        }
    }

    // The match model after byte c: the match goes on or ends; a new one is
    // looked up by the hash of the last kMinLen bytes.
    void match_update(unsigned c) noexcept {
        if (len_ > 0 && static_cast<unsigned char>(hist_[ptr_]) == c) {
            ++ptr_;
            if (len_ < 65535) ++len_;
        } else {
            len_ = 0;
        }
        if (pos_ >= static_cast<std::size_t>(kMinLen)) {
            const std::size_t slot = mslot_;
            if (len_ == 0) {
                const std::uint32_t cand = mtab_[slot];
                if (cand > 0) {
                    std::size_t n = 0;
                    while (n < static_cast<std::size_t>(kVerify) && n < cand && hist_[cand - 1 - n] == hist_[pos_ - 1 - n]) ++n;
                    if (n >= static_cast<std::size_t>(kMinLen)) {
                        len_ = static_cast<int>(n);
                        ptr_ = cand;
                    }
                }
            }
            mtab_[slot] = static_cast<std::uint32_t>(pos_);
        }
    }

    // After each byte (and before the first): the contexts, their buckets
    // and the match table's slot asked of memory.
    void byte_contexts() noexcept {
        if (pos_ > 0) {
            const unsigned c = static_cast<unsigned char>(hist_[pos_ - 1]);
            c8_ = (c8_ << 8) | c;
            c4_ = static_cast<std::uint32_t>(c8_);
            // Lines: column, the byte above, fields.
            if (c == '\n') {
                prev_line_ = line_;
                line_ = pos_;
                if (nfield_ < 31) fields_[static_cast<std::size_t>(nfield_++)] = join(field_, c);
                prev2_fields_ = prev_fields_;
                prev_fields_ = fields_;
                head_fields_[head_] = fields_;
                head_ = 0;
                fstart_ = 0;
                fields_ = {};
                nfield_ = 0;
                field_ = 0;
            } else if (is_field_end(c)) {
                if (nfield_ < 31) fields_[static_cast<std::size_t>(nfield_++)] = join(field_, c);
                field_ = 0;
                fstart_ = pos_ - line_;
            } else {
                field_ = join(field_, c + 1);
            }
            if (pos_ - line_ <= 2 && c != '\n') head_ = (head_ * 31 + c + 1) & 255u;
            if (is_word_byte(c)) {
                word_ = join(word_, c + 1);
            } else if (word_ != 0) {
                word_ = 0;
                sep_ = c;
            } else {
                sep_ = join(sep_, c);
            }
        }
        const std::size_t col = pos_ - line_;
        const std::size_t up = prev_line_ + col;
        const unsigned above = pos_ > 0 && up < line_ ? static_cast<unsigned char>(hist_[up]) : 0u;
        const std::uint64_t v[kContexts] = {
            c8_ & 0xFFFFFFFFu,
            c8_ & 0xFFFFFFFFFFFFull,
            join(join(word_, sep_), c8_ & 0xFFu),
            join(join(above, std::min<std::size_t>(col, 255)), c8_ & 0xFFu),
            join(join(prev_fields_[static_cast<std::size_t>(nfield_)], static_cast<std::uint64_t>(nfield_)), field_),
            join(join(join(head_fields_[pos_ - line_ >= 2 ? head_ : 256][static_cast<std::size_t>(nfield_)], static_cast<std::uint64_t>(nfield_)), field_), head_),
            join(join(join(prev2_fields_[static_cast<std::size_t>(nfield_)], static_cast<std::uint64_t>(nfield_)), field_), prev_fields_[static_cast<std::size_t>(nfield_)]),
        };
        for (int k = 0; k < kContexts; ++k) hash_[static_cast<std::size_t>(k)] = context_hash(v[k], k);
        prefetch_buckets(1);
        if (pos_ >= static_cast<std::size_t>(kMinLen)) {
            const std::uint64_t key = kMinLen >= 8 ? c8_ : c8_ & ((std::uint64_t{1} << (8 * kMinLen)) - 1);
            mslot_ = static_cast<std::size_t>(((key + 1) * kHashA) >> (64 - match_bits_));
            __builtin_prefetch(&mtab_[mslot_], 1);
        }
    }
    // Then (after the last bit's training): the match, the buckets.
    void byte_finish() noexcept {
        if (pos_ > 0) match_update(static_cast<unsigned>(c8_ & 0xFFu));
        resolve_buckets();
    }

    const char* hist_;
    std::size_t pos_ = 0;  // bytes coded so far
    int bucket_bits_ = 12, match_bits_ = 10;
    std::unique_ptr<mixdetail::ZeroPages> buckets_, match_;
    Bucket* table_ = nullptr;
    std::uint32_t* mtab_ = nullptr;
    std::array<std::uint64_t, kContexts> hash_{};
    std::array<Bucket*, kContexts> bucket_{};
    std::array<std::size_t, kContexts> slot_{};
    std::array<std::uint16_t, kContexts> check_{};
    std::array<SmallCounter*, kContexts> at_{};
    std::vector<Counter> o1_ = std::vector<Counter>(65536);  // order 1, direct: c1, c0
    Counter* o1_at_ = nullptr;
    std::array<Counter, 256> o0_{};
    std::array<Counter, 64> msm_{};
    Counter* msm_at_ = nullptr;
    std::array<std::int32_t, kInputs> x_{};
    std::array<std::int32_t, 256 * kInputs> w1_{};
    std::array<std::int32_t, 4 * 256 * kInputs> w2_{};
    std::int32_t* ws1_ = nullptr;
    std::int32_t* ws2_ = nullptr;
    std::int32_t y1_ = 0, y2_ = 0;
    std::size_t row1_ = apm1_row(1, 0), row2_ = apm2_row(1, 0);  // the next bit's rows of maps 1 and 2
    Apm<false> apm0_;
    Apm<true> apm1_;
    Apm<false> apm2_;
    unsigned c0_ = 1;
    unsigned node_ = 1;  // the bits of the nibble so far, after a leading 1
    int bitpos_ = 0;
    std::uint64_t c8_ = 0;
    std::uint32_t c4_ = 0;
    std::size_t line_ = 0, prev_line_ = 0;
    std::array<std::uint64_t, 32> fields_{}, prev_fields_{}, prev2_fields_{};
    std::array<std::array<std::uint64_t, 32>, 257> head_fields_{};  // by the first two bytes of a line
    unsigned head_ = 0;
    std::size_t fstart_ = 0;  // where the field starts in the line
    int nfield_ = 0;
    std::uint64_t field_ = 0, word_ = 0, sep_ = 0;
    int len_ = 0;
    std::size_t ptr_ = 0;
    std::size_t mslot_ = 0;  // the match table's entry of the last kMinLen bytes
    int expect_ = -1;
};

}  // namespace

std::string write_raw_cm_block(std::string_view raw, std::size_t* half) {
    if (raw.size() > kRawCmMaxSize) return {};
    std::string out;
    put_u8(out, kRawCmSubtype);
    put_u8(out, kRawCmCoding);
    put_varint(out, raw.size());
    auto model = std::make_unique<RawCmModel>(raw.size(), raw.data());
    RangeEncoder rc;
    for (std::size_t i = 0; i < raw.size(); ++i) {
        if (half && i == raw.size() / 2) *half = rc.size();
        const unsigned c = static_cast<unsigned char>(raw[i]);
        for (int j = 7; j >= 0; --j) {
            const int bit = static_cast<int>((c >> j) & 1u);
            rc.encode_p(static_cast<std::uint32_t>(65536 - model->predict()), bit);
            model->update(bit);
        }
    }
    out += rc.finish();
    return out;
}

Result<std::string> read_raw_cm_block(std::string_view payload, const std::string& where) {
    Cursor cur(payload);
    unsigned subtype, coding;
    if (!cur.u8(subtype) || subtype != kRawCmSubtype)
        return make_error(Errc::corrupt, where + " byte 0: unknown subtype of an extended block");
    if (!cur.u8(coding) || coding != kRawCmCoding)
        return make_error(Errc::corrupt, where + " byte 1: unknown coding of a CM raw block");
    std::uint64_t size;
    if (!cur.varint(size)) return make_error(Errc::corrupt, where + " byte 2: bad decoded size");
    if (size > kRawCmMaxSize)
        return make_error(Errc::limit, where + " byte 2: decoded size exceeds the raw block limit");
    const std::size_t base = cur.pos();
    RangeDecoder rc(payload.substr(base));
    // (the model reads the bytes decoded in place: it is told where they
    // are whenever the buffer grows; a declared size is not reserved whole
    // before the payload has shown it holds that much)
    std::string out;
    out.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(size, std::uint64_t{1} << 16)));
    auto model = std::make_unique<RawCmModel>(size, out.data());
    auto fail = [&](const char* what) {
        return make_error(Errc::corrupt, where + " byte " + std::to_string(base + rc.pos()) + ": " + what);
    };
    for (std::uint64_t i = 0; i < size; ++i) {
        unsigned c = 0;
        for (int j = 0; j < 8; ++j) {
            const int bit = rc.decode_p(static_cast<std::uint32_t>(65536 - model->predict()));
            c = (c << 1) | static_cast<unsigned>(bit);
            if (j == 7) {
                if (out.size() == out.capacity()) {
                    out.reserve(2 * out.capacity());
                    model->rebase(out.data());
                }
                out.push_back(static_cast<char>(c));
            }
            model->update(bit);
        }
        if (rc.overrun()) return fail("range-coded stream ends early");
    }
    if (!rc.finished()) return fail("range-coded stream does not end at the payload's end");
    return out;
}

}  // namespace stepzip::stz
