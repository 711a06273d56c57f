// Tick blocks; see timed_tick.hpp and docs/FORMAT.md "Tick block".
// Complexity: O(ticks · axes · log L) for a block, L the length of the
// digital straight segments followed (at most kMaxLine letters); a break
// of a segment re-reads at most kRebuild letters.
#include "timed_tick.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <vector>

#include "modeled_block.hpp"
#include "mix.hpp"
#include "range_coder.hpp"
#include "../common/bytes.hpp"
#include "../segment/dss.hpp"

namespace stepzip::stz {

namespace {

namespace dss = stepzip::detail::dss;

/// Coding 2: a decision is sure when its context gives the less likely bit
/// at most kSure / 65536 (mix_sure()): the least probability a context
/// reaches after a long run of the same bit (its shift capped at 5), i.e.
/// an axis that has not stepped in such a state for hundreds of ticks.
/// Chosen on corpora/timed/trapezoid-2axis, trapezoid-3axis and the Grbl
/// stream (docs/benchmarks.md "Timed streams at -L 19: sure decisions").
constexpr std::uint32_t kSure = 32;
/// The model byte of subtypes 5 and 6: the planner model (kTickPlanner),
/// and on an interrupt block with a mixed coding the planner model with
/// slot lines (kTickSlots).
constexpr unsigned kPlannerModel = 1;
constexpr unsigned kSlotModel = 2;
/// A segment followed is cut back to its longest suffix of at most
/// kRebuild letters that is straight when it breaks, and when it reaches
/// kMaxLine letters (the hull arithmetic stays far inside 64 bits).
constexpr std::size_t kRebuild = 256;
constexpr std::int64_t kMaxLine = std::int64_t{1} << 16;
/// The letters kept behind a segment's start.
constexpr std::size_t kKeep = 4 * kRebuild;

int clamp_int(std::int64_t v, int lo, int hi) { return static_cast<int>(std::clamp<std::int64_t>(v, lo, hi)); }

/// Guided mixing (the coding flag kTickGuided): the first weight set of
/// each mixer it picks (those of fields 4 and up, which no decision of a
/// tick block selects), the first of mixer 2's sets by the crossing (after
/// those by the trend, whose index tr / 4 is at most 25), the second map's
/// rows (by the guessed letter 0..8, b 0..3, t 1..3 and the rank's 2; then
/// by the crossing context, below 19 · 8), and the rates its predictor
/// learns at. Chosen on the timed streams of docs/benchmarks.md "Timed
/// streams: guided mixing".
constexpr int kGuidedSets = 64;
constexpr int kGuidedCrossSets = kGuidedSets + 26 * 3;
constexpr int kGuidedRows = 9 * 4 * 4 * 2;
constexpr MixGuide kGuide{.rows = kGuidedRows + 19 * 8, .rate = 4, .apm_rate = 6};
static_assert(kGuidedCrossSets + 19 * 3 <= kMixSets);
/// The match flag: mixer 1's sets by the match's state (after those by the
/// guessed letter and b, whose index is at most 8 · 4 + 3).
constexpr int kGuidedMatchSets = kGuidedSets + 36;
static_assert(kGuidedMatchSets + 36 <= kMixSets);
/// The planner model (kTickPlanner) with coding 2: rows of the sure
/// decisions' map (by the planned letter 0..6, the admitted set 1..3, b,
/// whether the axis is the leader and the match's predicted bit).
constexpr int kSureRows = 7 * 4 * 4 * 2 * 3;
/// The planner model: the blocks of at least 2^21 ticks take hashed tables
/// of 2^21 entries (kMixMaxTableBits), the others 2^20.
constexpr std::uint64_t kLargeTicks = std::uint64_t{1} << 21;
/// The predictor of a block of flags `flags` and `ticks` ticks.
MixGuide mix_guide(unsigned flags, std::uint64_t ticks) {
    MixGuide g = (flags & kTickGuided) ? kGuide : MixGuide{};
    if (flags & kTickPlanner) {
        if ((flags & 3u) == static_cast<unsigned>(TickCoding::mixed_sure)) g.sure_rows = kSureRows;
        if (ticks >= kLargeTicks) g.table_bits = kMixMaxTableBits;
    }
    return g;
}

/// A two-letter word read a letter at a time, as WordRecognizer reads it
/// (the hull form of dss.hpp): whether a letter may follow with the word
/// still a digital straight segment, without reading it. Lengths stay below
/// kMaxLine + kRebuild, so 64-bit products suffice.
class Line {
public:
    void reset() {
        zeros_.clear();
        ones_.clear();
        lo_set_ = hi_set_ = false;
        p_ = q_ = 0;
    }
    std::int64_t length() const { return p_ + q_; }
    bool admits(int letter) const { return admits_run(letter, 1); }
    /// Whether k >= 1 letters `letter` may follow: as admits() for the last
    /// of them (a bound moves only by the tangent to the run's last
    /// position, the farthest from the opposite hull).
    bool admits_run(int letter, std::int64_t k) const {
        std::int64_t n, d;
        if (letter == 0) {
            if (!lo_set_ || !dss::min_slope_to<std::int64_t>(ones_, dss::Pt{p_ + k - 1, q_}, n, d)) return true;
            if (hi_set_ && !dss::less<std::int64_t>(n, d, hi_.n, hi_.d)) return true;  // hi unchanged
            return dss::less<std::int64_t>(lo_.n, lo_.d, n, d);
        }
        if (!hi_set_ || !dss::max_slope_to<std::int64_t>(zeros_, dss::Pt{p_, q_ + k - 1}, n, d)) return true;
        if (lo_set_ && !dss::less<std::int64_t>(lo_.n, lo_.d, n, d)) return true;  // lo unchanged
        return dss::less<std::int64_t>(n, d, hi_.n, hi_.d);
    }
    /// The line's rate, ones per letter in units of 1/RateGuess::kOne: the
    /// middle of the rates it admits when both bounds are set, else its
    /// ones over its letters; 0 when empty.
    std::int64_t rate() const;
    bool bounded() const { return lo_set_ && hi_set_; }
    /// Appends a letter that admits() allowed.
    void read(int letter) { read_run(letter, 1); }
    /// Appends k >= 1 letters `letter` that admits_run() allowed, with the
    /// state k calls of read() leave: a run's inner positions are never hull
    /// vertices and never give a bound.
    void read_run(int letter, std::int64_t k) {
        std::int64_t n, d;
        if (letter == 0) {
            const dss::Pt last{p_ + k - 1, q_};
            if (dss::min_slope_to<std::int64_t>(ones_, last, n, d) &&
                (!hi_set_ || dss::less<std::int64_t>(n, d, hi_.n, hi_.d))) {
                hi_ = {n, d};
                hi_set_ = true;
            }
            dss::push_lower<std::int64_t>(zeros_, dss::Pt{p_, q_});
            if (k >= 2) dss::push_lower<std::int64_t>(zeros_, last);
            p_ += k;
        } else {
            const dss::Pt top{p_, q_ + k - 1};
            if (dss::max_slope_to<std::int64_t>(zeros_, top, n, d) &&
                (!lo_set_ || dss::less<std::int64_t>(lo_.n, lo_.d, n, d))) {
                lo_ = {n, d};
                lo_set_ = true;
            }
            dss::push_upper<std::int64_t>(ones_, top);
            q_ += k;
        }
    }

private:
    std::vector<dss::Pt> zeros_, ones_;
    dss::Frac lo_{0, 1}, hi_{0, 1};
    bool lo_set_ = false, hi_set_ = false;
    std::int64_t p_ = 0, q_ = 0;
};

/// The next letter of a line predicted from a rate r (ones per letter,
/// fixed point): the word read since the line's start is the digitization
/// floor(r k + mu) of a line of that rate for the phases mu in [lo, hi];
/// the next letter is 1 for the phases at or above a threshold. Integer
/// arithmetic only (the decoder computes the same on every machine).
class RateGuess {
public:
    static constexpr std::int64_t kOne = std::int64_t{1} << 24;
    /// Buckets of guess(): none, a sure 1, a sure 0, kShares shares of 1.
    static constexpr int kShares = 6;

    void clear() { valid_ = false; }
    /// A line of rate r from here on (none when r <= 0).
    void start(std::int64_t r) {
        r_ = std::min(r, kOne);
        lo_ = 0;
        hi_ = kOne - 1;
        k_ = s_ = 0;
        valid_ = r > 0;
    }
    bool valid() const { return valid_; }
    void read(int letter) {
        if (!valid_) return;
        ++k_;
        s_ += letter;
        lo_ = std::max(lo_, s_ * kOne - r_ * k_);
        hi_ = std::min(hi_, s_ * kOne + kOne - 1 - r_ * k_);
        valid_ = lo_ <= hi_;
    }
    /// Where the line's counter r k + mu - s (mu the middle of the phases
    /// left) reaches 1: as a fraction of the next event in 1/kOne, 0..kOne;
    /// -1 when it does not within the next event or there is no line.
    std::int64_t crossing() const {
        if (!valid_) return -1;
        const std::int64_t counter = r_ * k_ + (lo_ + hi_) / 2 - s_ * kOne;
        const std::int64_t left = kOne - counter;
        if (left > r_) return -1;
        return std::max<std::int64_t>(left, 0) * kOne / r_;
    }
    /// The line's counter after the letters read, r k + mu - s with mu the
    /// middle of the phases left: how far the line is past its last 1, in
    /// 1/kOne of a 1 (within [0, kOne) while the line holds).
    std::int64_t counter() const { return r_ * k_ + (lo_ + hi_) / 2 - s_ * kOne; }
    /// The rate r it was started with (ones per letter, in 1/kOne), and
    /// the width hi - lo of the phases left.
    std::int64_t rate() const { return r_; }
    std::int64_t width() const { return hi_ - lo_; }
    /// The share of the phases left that give a 1 next, as a probability of
    /// a 1 in 1/65536 (0 and 65536 when sure); -1 when there is no line.
    std::int64_t p1() const {
        if (!valid_) return -1;
        const std::int64_t theta = threshold();
        if (theta <= lo_) return 65536;
        if (theta > hi_) return 0;
        return (hi_ - theta + 1) * 65536 / (hi_ - lo_ + 1);
    }
    /// The share of the phases left that give a 1 next, in buckets.
    int guess() const {
        if (!valid_) return 0;
        const std::int64_t theta = threshold();
        if (theta <= lo_) return 1;
        if (theta > hi_) return 2;
        return 3 + static_cast<int>((hi_ - theta + 1) * kShares / (hi_ - lo_ + 2));
    }

private:
    // The phase from which the next letter is a 1 (those at or above it).
    std::int64_t threshold() const { return (s_ + 1) * kOne - r_ * (k_ + 1); }

    std::int64_t r_ = 0, lo_ = 0, hi_ = 0, k_ = 0, s_ = 0;
    bool valid_ = false;
};

std::int64_t Line::rate() const {
    const std::int64_t len = p_ + q_;
    if (len == 0) return 0;
    if (!bounded()) return q_ * RateGuess::kOne / len;
    // A slope n/d (ones per zero) is the rate n / (n + d).
    const auto r = [](const dss::Frac& f) { return f.n * RateGuess::kOne / (f.n + f.d); };
    return (r(lo_) + r(hi_) + 1) / 2;
}

/// One binary word (a letter per event) followed as the longest digital
/// straight segment ending at its last letter (docs/FORMAT.md "Tick block":
/// the follower). The context of the next letter: which letters the segment
/// admits, its length, the current run against the last two runs of the
/// same letter and the trend of the runs, a 1 now against the interval between
/// 1s extrapolated from the last three, and the time since the segment last
/// broke against the length of the segment before.
class Follower {
public:
    /// Empties the follower; `restart`: a line that breaks restarts at its
    /// last 1 (the coding flag kTickRestart); `guess`: the line guesses its
    /// next letter (kTickGuess); `clock`: with `guess`, it keeps the segment
    /// clock (the planner model, kTickPlanner).
    void reset(bool restart, bool guess, bool clock = false) {
        restart_ = restart;
        guessing_ = guess;
        clock_ = clock && guess;
        next_.clear();
        for (const std::uint16_t d : counted_) spacings_[d] = 0;  // (a chain's reset costs what it counted)
        counted_.clear();
        seg_ = best_ = 0;
        line_.reset();
        hist_.clear();
        start_ = 0;
        last_ = -1;
        run_ = 0;
        runs_ = {};
        since_break_ = 0;
        period_ = 0;
        ones_.fill(-1);
        n_ = 0;
        recent_ = 0;
        guess_.clear();
        rates_ = {};
        line_start_ = 0;
        retry_ = 0;
    }

    /// The next letter as the line's guessed rate has it (RateGuess::guess()).
    int guess() const { return guess_.guess(); }
    /// The planner model: the next letter as the line that the segment
    /// clock started has it (RateGuess::guess(); 0: none).
    int next_guess() const { return next_.guess(); }
    /// The planner model: the probability of a 1 next (RateGuess::p1()) by
    /// the line the clock started, else by the guess; -1: neither.
    std::int64_t planned_p1() const {
        const std::int64_t p = next_.p1();
        return p >= 0 ? p : guess_.p1();
    }
    /// The planner model: the next letter's distance from the end of the
    /// segment the clock expects, in half intervals between the last two
    /// 1s, clamped, 1..9; 0 without a clock period or two 1s.
    int clock_phase() const {
        if (seg_ == 0 || ones_[1] < 0) return 0;
        const std::int64_t into = n_ - line_start_ - seg_;
        return 5 + clamp_int(dss::floor_div(2 * into, ones_[0] - ones_[1]), -4, 4);
    }
    /// Where in the next event the line's counter crosses to its next 1
    /// (RateGuess::crossing()).
    std::int64_t crossing() const { return guess_.crossing(); }
    /// The line's guessed rate (RateGuess) and the segment's length.
    const RateGuess& guessed() const { return guess_; }
    std::int64_t length() const { return line_.length(); }

    /// The last 64 letters, the latest in bit 0 (mixed coding).
    std::uint64_t recent() const { return recent_; }
    /// The letters since the line last broke and the letters between its
    /// last two breaks, each capped at 1023 (mixed coding 2).
    std::uint64_t breaks() const {
        return (static_cast<std::uint64_t>(std::min<std::int64_t>(since_break_, 1023)) << 10) |
               static_cast<std::uint64_t>(std::min<std::int64_t>(period_, 1023));
    }
    /// The current run (its letter, 0 before any, and length) and the last
    /// complete run of its letter (mixed coding).
    std::uint64_t run_key() const {
        const int c = last_ < 0 ? 0 : last_;
        const auto cap = [](std::int64_t v) { return static_cast<std::uint64_t>(std::min<std::int64_t>(v, 255)); };
        return (cap(run_) << 17) | (cap(runs_[static_cast<std::size_t>(c)][0]) << 9) |
               (cap(runs_[static_cast<std::size_t>(c)][1]) << 1) | static_cast<std::uint64_t>(c);
    }

    /// Letters the segment admits next: 1 zero only, 2 one only, 3 both.
    int admits() const { return (line_.admits(0) ? 1 : 0) | (line_.admits(1) ? 2 : 0); }

    /// Context of the next letter, given admits() == `adm`, below kContexts.
    static constexpr int kContexts = 3 * 6 * 2 * 5 * 5 * 3 * 3 * 3;
    int context(int adm) const {
        const int lb = std::min(bit_length(static_cast<std::uint64_t>(line_.length())), 11) / 2;
        const int c = last_ < 0 ? 0 : last_;
        const auto& r = runs_[static_cast<std::size_t>(c)];
        // The run so far, one longer, against the last complete run of its letter.
        const int e = r[0] == 0 ? 2 : clamp_int(run_ + 1 - r[0], -2, 2) + 2;
        // A one now against the next interval between ones extrapolated
        // from the last three (a line through them: constant acceleration),
        // in thirds of an event.
        int acc = 2;
        if (ones_[3] >= 0) {
            const std::int64_t d1 = ones_[0] - ones_[1], d2 = ones_[1] - ones_[2], d3 = ones_[2] - ones_[3];
            const std::int64_t v = 3 * (n_ - ones_[0]) - (d1 + d2 + d3) - 3 * (d1 - d3);
            acc = clamp_int(dss::floor_div(v + 1, 3), -2, 2) + 2;
        }
        int brk = 0;
        if (period_ > 0) {
            const std::int64_t tol = period_ / 8 + 1;
            brk = since_break_ + tol < period_ ? 0 : since_break_ <= period_ + tol ? 1 : 2;
        }
        const int trend = r[0] == 0 || r[1] == 0 ? 1 : clamp_int(r[0] - r[1], -1, 1) + 1;
        const int e1 = r[1] == 0 ? 1 : clamp_int(run_ + 1 - r[1], -1, 1) + 1;
        return ((((((((adm - 1) * 6 + lb) * 2 + c) * 5 + e) * 5 + acc) * 3 + trend) * 3 + e1) * 3) + brk;
    }

    void push(int letter, int adm) {
        const std::int64_t prev_start = line_start_;
        bool broke = false;
        hist_.push_back(static_cast<std::uint8_t>(letter));
        ++since_break_;
        if (letter == 1) {
            for (int i = 3; i > 0; --i) ones_[i] = ones_[i - 1];
            ones_[0] = n_;
        }
        ++n_;
        recent_ = (recent_ << 1) | static_cast<std::uint64_t>(letter);
        if ((adm >> letter) & 1) {
            line_.read(letter);
            if (guessing_) guess_.read(letter);
            if (line_.length() >= kMaxLine) {
                const std::int64_t r = line_.rate();
                rebuild(false);
                if (guessing_) restart_guess(r);
            } else if (guessing_ && !guess_.valid() && line_.bounded() && line_.length() >= retry_) {
                // A line whose letters the guessed rate no longer gives: its
                // own rate; again only when the line has grown by a quarter,
                // at least 8 letters (a retry reads up to kGuessReplay letters).
                restart_guess(line_.rate());
                retry_ = line_.length() + std::max<std::int64_t>(8, line_.length() / 4);
            }
        } else {
            if (guessing_) {
                // The line that ends (its letters before this one): its rate, at its middle.
                const std::int64_t end = n_ - 1;
                rates_[1] = rates_[0];
                rates_[0] = {line_.rate(), line_start_ + end, end - line_start_};
            }
            rebuild(restart_);
            if (guessing_) restart_guess(predicted_rate());
            period_ = since_break_;
            since_break_ = 0;
            broke = true;
        }
        if (letter == last_) {
            ++run_;
        } else {
            if (last_ >= 0) {
                auto& r = runs_[static_cast<std::size_t>(last_)];
                r[1] = r[0];
                r[0] = run_;
            }
            last_ = letter;
            run_ = 1;
        }
        if (clock_) tick_clock(letter, broke, prev_start);
        if (start_ > 2 * kKeep) {  // forget the letters no rebuild can reach
            const std::size_t drop = start_ - kKeep;
            hist_.erase(hist_.begin(), hist_.begin() + static_cast<std::ptrdiff_t>(drop));
            start_ -= drop;
        }
    }

private:
    struct LineRate {
        std::int64_t rate, mid2, length;  // mid2: twice the middle letter
    };
    /// A guess that restarts reads at most the line's last kGuessReplay
    /// letters (a suffix of a straight word is straight, of the same rate).
    static constexpr std::size_t kGuessReplay = 256;

    // The rate of the line after a break: the last line's, carried on by
    // the change from the line before (constant acceleration: a rate
    // linear in time), when both are known and the change is under half.
    std::int64_t predicted_rate() const {
        const LineRate& a = rates_[0];
        const LineRate& b = rates_[1];
        if (a.length == 0) return 0;
        if (b.length == 0 || a.mid2 <= b.mid2 || 2 * std::abs(a.rate - b.rate) > a.rate) return a.rate;
        // The new line's middle lies a line's length past the last one's.
        const std::int64_t r = a.rate + (a.rate - b.rate) * (2 * a.length) / (a.mid2 - b.mid2);
        return std::clamp<std::int64_t>(r, 1, RateGuess::kOne);
    }
    // The guess restarts with rate r at the line's start, or kGuessReplay
    // letters before its end, and reads the letters since.
    void restart_guess(std::int64_t r) {
        const std::size_t end = hist_.size();
        retry_ = 0;
        line_start_ = n_ - static_cast<std::int64_t>(end - start_);
        guess_.start(r);
        const std::size_t from = end - std::min(end - start_, kGuessReplay);
        for (std::size_t j = from; j < end; ++j) guess_.read(hist_[j]);
    }

    // The planner model's segment clock, after letter `letter` was read
    // (`broke`: its line broke and restarted; `prev_start`: the line's
    // start before). A controller of fixed-time stepper segments (Grbl's
    // 10 ms) changes an axis's rate at one of its steps about a segment
    // after the last change: the clock's period is the most frequent
    // distance between the starts of consecutive lines, and from the step
    // within an interval and a half of that distance on, each step starts
    // the line the next segment would run, at the rate carried on by the
    // change from the last line to this one.
    void tick_clock(int letter, bool broke, std::int64_t prev_start) {
        if (broke) {
            next_.clear();
            const std::int64_t sp = line_start_ - prev_start;
            if (prev_start > 0 && sp > 0 && sp < kMaxSpacing) count_spacing(sp);
            return;
        }
        if (seg_ == 0) return;
        const std::int64_t pos = n_ - 1 - line_start_;
        const std::int64_t tol =
            std::max<std::int64_t>(2, ones_[1] >= 0 ? 3 * (ones_[0] - ones_[1]) / 2 : seg_ / 16);
        if (letter == 1 && pos >= seg_ - tol) {
            const std::int64_t rc = line_.rate(), rp = rates_[0].rate;
            const std::int64_t r =
                rp > 0 && 2 * std::abs(rc - rp) <= rc ? std::clamp<std::int64_t>(2 * rc - rp, 1, RateGuess::kOne) : rc;
            next_.start(r);
            next_.read(1);
        } else {
            next_.read(letter);
        }
    }
    // One more distance `sp` between line starts: the period becomes the
    // mean of the distances within sp / 16 + 1 of it when they are at least
    // as many as those around the period before.
    void count_spacing(std::int64_t sp) {
        if (spacings_.empty()) spacings_.assign(kMaxSpacing, 0);
        if (spacings_[static_cast<std::size_t>(sp)]++ == 0) counted_.push_back(static_cast<std::uint16_t>(sp));
        const std::int64_t w = sp / 16 + 1;
        std::int64_t count = 0, sum = 0;
        for (std::int64_t v = std::max<std::int64_t>(1, sp - w); v <= std::min(kMaxSpacing - 1, sp + w); ++v) {
            count += spacings_[static_cast<std::size_t>(v)];
            sum += v * spacings_[static_cast<std::size_t>(v)];
        }
        if (count >= best_) {
            best_ = count;
            seg_ = (sum + count / 2) / count;
        }
    }
    static constexpr std::int64_t kMaxSpacing = 4096;

    // The segment becomes the longest straight suffix of at most kRebuild
    // letters (a word is straight iff its reverse is: it is read backward);
    // with `at_one`, of those that start no earlier than the last 1. A
    // controller changes an axis's rate between two of its steps: after a
    // break the letters before the last step belong to the old rate, and a
    // line that kept them would break again (on the timed streams of
    // docs/benchmarks.md five times as often as the rate changed).
    void rebuild(bool at_one) {
        const std::size_t end = hist_.size();
        const std::size_t reach = end - std::min(end, kRebuild);  // the earliest letter a rebuild reads
        std::size_t i = end;
        if (at_one) {
            // The letters from the last 1 on hold one 1 and are straight, so
            // the longest straight suffix reaches that 1 whenever it lies
            // within reach: the line starts there, with no backward reading.
            // Without a 1 within reach the suffix is all 0s, to the reach.
            while (i > reach && hist_[i - 1] != 1) --i;
            i = i > reach ? i - 1 : reach;
        } else {
            // Backward, a run at a time: where a run is not admitted whole, the
            // longest admitted part of it (admission only shrinks along a run).
            back_.reset();
            while (i > reach) {
                const int letter = hist_[i - 1];
                std::size_t j = i - 1;
                while (j > reach && hist_[j - 1] == letter) --j;
                const auto k = static_cast<std::int64_t>(i - j);
                if (back_.admits_run(letter, k)) {
                    back_.read_run(letter, k);
                    i = j;
                    continue;
                }
                std::int64_t good = 0, bad = k;
                while (bad - good > 1) {
                    const std::int64_t mid = (good + bad) / 2;
                    (back_.admits_run(letter, mid) ? good : bad) = mid;
                }
                i -= static_cast<std::size_t>(good);
                break;
            }
        }
        line_.reset();
        start_ = i;
        for (std::size_t j = i; j < end;) {
            std::size_t r = j + 1;
            while (r < end && hist_[r] == hist_[j]) ++r;
            line_.read_run(hist_[j], static_cast<std::int64_t>(r - j));
            j = r;
        }
    }

    bool restart_ = false, guessing_ = false;
    Line line_, back_;
    std::vector<std::uint8_t> hist_;
    std::size_t start_ = 0;
    int last_ = -1;
    std::int64_t run_ = 0;
    std::array<std::array<std::int64_t, 2>, 2> runs_{};  // per letter: its last two complete runs
    std::int64_t since_break_ = 0, period_ = 0;
    std::array<std::int64_t, 4> ones_{-1, -1, -1, -1};  // events of the last four ones, latest first
    std::int64_t n_ = 0;                                 // events read
    std::uint64_t recent_ = 0;                           // the last 64 letters, latest in bit 0
    RateGuess guess_;
    std::array<LineRate, 2> rates_{};  // the last two lines that broke, latest first
    std::int64_t line_start_ = 0;      // the event of the line's first letter
    std::int64_t retry_ = 0;           // the line's length from which a guess that fails restarts
    // The planner model (tick_clock()).
    bool clock_ = false;
    RateGuess next_;                      // the line the next segment would start
    std::vector<std::uint32_t> spacings_; // per distance between line starts (1..kMaxSpacing-1), how often
    std::vector<std::uint16_t> counted_;  // the distances whose count is not 0
    std::int64_t seg_ = 0;                // the clock's period (0: none yet)
    std::int64_t best_ = 0;               // the distances counted around it
};

constexpr int kMinor = kMaxAxes - 1;  // axes besides time
constexpr int kSinceBuckets = 16;

/// Every adaptive context of a tick block, in the order of FORMAT.md 1.13
/// "Slots" (a mixed decision's slot is its context's index here): the
/// chain headers' models, then those of each axis besides time, for as many
/// axes as the block has (778 KB an axis). The memory is kept per thread and
/// reused by its next block (TickTablesLease).
class TickTables {
public:
    struct Head {
        UIntModel start, length;
    };
    struct Axis {
        std::array<Prob, std::size_t{8} * Follower::kContexts> step;
        std::array<Prob, kSinceBuckets> dir;
    };
    static_assert(sizeof(Head) % sizeof(Prob) == 0 && sizeof(Axis) % sizeof(Prob) == 0 &&
                  alignof(Head) == alignof(Prob) && alignof(Axis) == alignof(Prob));

    /// Every context at its initial value, for `minor` (0..kMinor) axes
    /// besides time.
    void reset(int minor) {
        const std::size_t bytes = offset(minor);
        if (bytes > size_) {
            mem_ = std::make_unique<std::byte[]>(bytes);
            size_ = bytes;
        }
        head_ = ::new (mem_.get()) Head{};
        for (int a = 0; a < minor; ++a) axis_[static_cast<std::size_t>(a)] = ::new (mem_.get() + offset(a)) Axis{};
    }
    Head& head() { return *head_; }
    Axis& axis(std::size_t a) { return *axis_[a]; }
    /// The first context (slot 0).
    const Prob* base() const { return reinterpret_cast<const Prob*>(head_); }

    bool busy = false;

private:
    static std::size_t offset(int a) { return sizeof(Head) + static_cast<std::size_t>(a) * sizeof(Axis); }
    std::unique_ptr<std::byte[]> mem_;
    std::size_t size_ = 0;
    Head* head_ = nullptr;
    std::array<Axis*, kMinor> axis_{};
};

/// The tables of one block, reset for `minor` axes besides time: the
/// thread's own when free (a block after another reuses their memory), else
/// tables of its own.
class TickTablesLease {
public:
    explicit TickTablesLease(int minor) {
        thread_local TickTables shared;
        if (shared.busy) {
            own_ = std::make_unique<TickTables>();
            t_ = own_.get();
        } else {
            t_ = &shared;
        }
        t_->busy = true;
        t_->reset(minor);
    }
    TickTablesLease(const TickTablesLease&) = delete;
    TickTablesLease& operator=(const TickTablesLease&) = delete;
    ~TickTablesLease() { t_->busy = false; }
    TickTables& operator*() const { return *t_; }

private:
    std::unique_ptr<TickTables> own_;
    TickTables* t_;
};

/// The match flag (docs/FORMAT.md 1.13 "Match"): the block's ticks so far,
/// each as its step mask, and where the last few step events (each its mask
/// and the ticks since the event before) came before. A controller that
/// draws the same thing again (a job run twice, a glyph drawn twice at the
/// same speeds) repeats its ticks exactly; the tick model's contexts see a
/// few dozen ticks back.
class TickMatch {
public:
    /// Events hashed to find a match, and to find a longer one while
    /// following a match; chosen on the timed streams of docs/benchmarks.md
    /// "Timed streams: the match flag".
    static constexpr int kShortEvents = 4, kLongEvents = 16;
    /// A candidate's agreement with the ticks before it is counted up to
    /// this many ticks.
    static constexpr std::uint64_t kVerify = std::uint64_t{1} << 8;
    /// Match lengths (ticks) from which the guided mixer takes the match's
    /// weight sets, and from which a sure decision it contradicts is mixed.
    static constexpr std::uint64_t kGuideLength = 32, kUnsureLength = 8;

    /// For a block of `ticks` ticks after the ticks of `window` (the window
    /// flag; else null), T ticks in all: tables of 2^clamp(bit_length(T) -
    /// 2, 12, 20) entries each (4 MiB at most). The window's ticks, oldest
    /// first, are pushed as if coded.
    TickMatch(std::uint64_t ticks, const WindowView* window)
        : bits_(std::clamp(bit_length(ticks + window_ticks(window)) - 2, 12, 20)),
          short_pages_((std::size_t{1} << bits_) * sizeof(std::uint32_t)),
          long_pages_((std::size_t{1} << bits_) * sizeof(std::uint32_t)),
          short_(static_cast<std::uint32_t*>(short_pages_.data())),
          long_(static_cast<std::uint32_t*>(long_pages_.data())) {
        hist_.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(ticks + window_ticks(window), kMaxReserve)));
        if (window)
            for (const auto& b : *window)
                for (const std::uint8_t m : b->ticks) push(m);
    }

    /// 0 without a match, else 1 + the bit of axis bit `bit` in the
    /// predicted mask + 2 min(bit_length(length), 17).
    std::uint64_t state(int bit) const {
        if (ptr_ < 0) return 0;
        return 1 + ((hist_[static_cast<std::size_t>(ptr_)] >> bit) & 1u) + 2 * bucket();
    }
    std::uint64_t length() const { return len_; }
    std::uint64_t bucket() const { return static_cast<std::uint64_t>(std::min(bit_length(len_), 17)); }

    /// After a tick of step mask `m`: the match follows or ends, the tick
    /// joins the history, and at a step event the tables are consulted
    /// and updated.
    [[gnu::always_inline]] void push(unsigned m) {
        const std::uint64_t t = hist_.size();
        if (ptr_ >= 0 && hist_[static_cast<std::size_t>(ptr_)] == m) {
            ++ptr_;
            ++len_;
        } else {
            ptr_ = -1;
            len_ = 0;
        }
        hist_.push_back(static_cast<std::uint8_t>(m));
        if (m != 0) event(m, t);
    }

private:
    // A step event of mask m at tick t: the tables.
    void event(unsigned m, std::uint64_t t) {
        events_[count_ % kRing] = (std::min<std::uint64_t>(t - last_, 1023) << 6) | m;
        ++count_;
        last_ = t;
        if (count_ >= kLongEvents) {
            std::uint32_t& e = long_[index(kLongEvents)];
            // A longer match than the one followed (or than none) takes over.
            if (e != 0 && static_cast<std::int64_t>(e) != ptr_ && len_ < kVerify) {
                const std::uint64_t v = agreement(e);
                if (v > len_) {
                    ptr_ = e;
                    len_ = v;
                }
            }
            e = static_cast<std::uint32_t>(t + 1);
        }
        if (count_ >= kShortEvents) {
            std::uint32_t& e = short_[index(kShortEvents)];
            if (ptr_ < 0 && e != 0) {
                ptr_ = e;
                len_ = agreement(e);
            }
            e = static_cast<std::uint32_t>(t + 1);
        }
    }

    static constexpr std::uint64_t kRing = 16;
    static constexpr std::uint64_t kMaxReserve = std::uint64_t{1} << 24;

    static std::uint64_t window_ticks(const WindowView* window) {
        std::uint64_t n = 0;
        if (window)
            for (const auto& b : *window) n += b->ticks.size();
        return n;
    }

    // The table index of the last k events.
    std::size_t index(int k) const {
        std::uint64_t h = 0;
        for (int j = 1; j <= k; ++j) h = (h + events_[(count_ - static_cast<std::uint64_t>(j)) % kRing] + 1) * kHashA;
        return static_cast<std::size_t>(h >> (64 - bits_));
    }
    // How many ticks before position c agree with the last ticks (at most kVerify).
    std::uint64_t agreement(std::uint64_t c) const {
        const std::uint64_t t = hist_.size();
        std::uint64_t n = 0;
        while (n < kVerify && n < c && hist_[static_cast<std::size_t>(c - 1 - n)] == hist_[static_cast<std::size_t>(t - 1 - n)]) ++n;
        return n;
    }

    static constexpr std::uint64_t kHashA = 0x9E3779B97F4A7C15ull;
    int bits_;
    // The tables in fresh zero pages: the pages the coding never writes
    // stay untouched (a block's declared ticks size them, the decoder's
    // before any tick is read).
    mixdetail::ZeroPages short_pages_, long_pages_;
    std::uint32_t* short_;  // per hash, the tick after an event + 1 (0: none)
    std::uint32_t* long_;
    std::vector<std::uint8_t> hist_;  // per tick, its step mask
    std::array<std::uint64_t, kRing> events_{};
    std::uint64_t count_ = 0, last_ = 0;
    std::int64_t ptr_ = -1;  // the tick whose mask is predicted next
    std::uint64_t len_ = 0;  // ticks it has agreed for
};

/// The tick model of one block, shared by the encoder (EncIo) and the
/// decoder (DecIo). Not thread-safe.
template <class Io>
class TickCoder {
public:
    /// `windows`: an interrupt block (subtype 1), whose B[a] follow the
    /// axes per leader step (FORMAT.md 1.14); `coding`: with mixed
    /// predictions, coding 2 leaves the sure decisions to their contexts
    /// and names other hashed models in v0 and v4; `flags`: kTickRestart
    /// (the followers' lines restart at their last 1 when they break) and
    /// kTickGuess (mixed codings: their lines guess the next letter).
    /// kTickMatch (mixed codings: a match model over the block's `ticks`,
    /// after the ticks of `window` with kTickWindow), kTickRefine (the plain
    /// coding: the same match, refining the step decisions' contexts),
    /// kTickPlanner (the planner model), kTickSlots (mixed codings of an
    /// interrupt block: the planner model with slot lines).
    TickCoder(Io& io, TickTables& t, int axes, bool windows, TickCoding coding, unsigned flags, std::uint64_t ticks,
              const WindowView* window)
        : io_(io), t_(t), minor_(axes - 1), windows_(windows), sure_(coding == TickCoding::mixed_sure),
          restart_((flags & kTickRestart) != 0), guessing_((flags & kTickGuess) != 0),
          guided_((flags & kTickGuided) != 0), refine_((flags & kTickRefine) != 0),
          planner_((flags & kTickPlanner) != 0), slots_((flags & kTickSlots) != 0) {
        if constexpr (kMixedIo<Io>) io_.sure = sure_ ? kSure : 0;
        if (flags & (kTickMatch | kTickRefine))
            match_ = std::make_unique<TickMatch>(ticks, (flags & kTickWindow) ? window : nullptr);
    }

    /// A chain's start: every follower forgets.
    void start_chain() {
        for (auto& f : axis_) f.reset(restart_, guessing_, planner_);
        for (auto& f : bres_) f.reset(restart_, bres_guessing());
        moved_.fill(0);
        sign_.fill(1);
        since_.fill(0);
        gap_.fill(0);
        for (auto& g : gaps_) g.fill(0);
        leader_ = -1;
        history_ = 0;
        if (slots_) reset_slots();
    }

    /// One tick: `mask` bit a set when axis a + 1 steps, `neg` bit a when
    /// it steps backward (encoder: given; decoder: filled in).
    void tick(unsigned& mask, unsigned& neg) {
        // The axes in order of their step rate, fastest first: the leader
        // (a controller's Bresenham major axis) is coded first, and the
        // others on the ticks where it steps follow their own line.
        std::array<int, kMinor> order{};
        std::array<std::int64_t, kMinor> keys{};
        for (int a = 0; a < minor_; ++a) {  // insertion: stable, at most five axes
            const std::int64_t k = key(a);
            int i = a;
            for (; i > 0 && keys[static_cast<std::size_t>(i - 1)] > k; --i) {
                keys[static_cast<std::size_t>(i)] = keys[static_cast<std::size_t>(i - 1)];
                order[static_cast<std::size_t>(i)] = order[static_cast<std::size_t>(i - 1)];
            }
            keys[static_cast<std::size_t>(i)] = k;
            order[static_cast<std::size_t>(i)] = a;
        }
        if (order[0] != leader_) {
            leader_ = order[0];
            for (auto& f : bres_) f.reset(restart_, bres_guessing());
            moved_.fill(0);
            if (slots_) reset_slots();
        }
        unsigned m = 0, n = 0;
        int lead_step = 0;
        for (int i = 0; i < minor_; ++i) {
            const int a = order[static_cast<std::size_t>(i)];
            const auto ua = static_cast<std::size_t>(a);
            Follower& f = axis_[ua];
            const int fa = f.admits();
            // Tick block: B[a] reads the axis on the ticks where the leader
            // steps. Interrupt block: B[a] reads per leader step whether the
            // axis stepped since the leader's previous step (its window).
            const int wa = windows_ && i > 0 ? bres_[ua].admits() : 0;
            const int ba = !windows_ ? (i > 0 && lead_step ? bres_[ua].admits() : 0) : window_context(i, wa, lead_step, ua);
            const std::size_t ctx = static_cast<std::size_t>((f.context(fa) * 2 + (m != 0)) * 4 + ba);
            // The match or refine flag: the match's state for this axis.
            const std::uint64_t ms = match_ ? match_->state(a) : 0;
            // The planner model: the axis's planned probability of a step
            // (the mixed codings' direct input, sure map and sure rule).
            // With slot lines, a follower's is its slot line's (slot_p1())
            // where it has one: the mixers see both.
            [[maybe_unused]] const std::int64_t own = kMixedIo<Io> && planner_ ? f.planned_p1() : -1;
            [[maybe_unused]] const std::int64_t slot = kMixedIo<Io> && slots_ && i > 0 ? slot_p1(ua) : -1;
            [[maybe_unused]] const std::int64_t pp = slot >= 0 ? slot : own;
            if constexpr (kMixedIo<Io>) {
                const std::uint64_t ax = static_cast<std::uint64_t>(a);
                io_.field(i == 0 ? 0 : 1);
                if (sure_) {
                    // Coding 2: the time since the leader's last step and its last
                    // interval (for the leader: of the axis ranked next), with
                    // the time since this axis's last step.
                    const auto ub = static_cast<std::size_t>(i > 0 ? leader_ : minor_ > 1 ? order[1] : a);
                    mix_context(io_, 0, ctx_join(ctx_join(ax, 1), (capped(since_[ub]) << 20) | (capped(gap_[ub]) << 10) |
                                                                      capped(since_[ua])));
                } else {
                    mix_context(io_, 0, ctx_join(ctx_join(ax, 1), f.recent() & 0xFFFFu));
                }
                mix_context(io_, 1, ctx_join(ctx_join(ax, 2), f.run_key()));
                const auto uf = static_cast<std::uint64_t>(fa);
                const auto guess = guessing_ ? static_cast<std::uint64_t>(f.guess()) : 0u;  // (models 2, 3 and 6)
                const bool crossing = guessing_ && windows_ && i > 0;
                // The planner model: model 2 takes the leader's segment
                // clock and an interrupt block's follower's interrupt grid
                // (with slot lines, its slots) in place of the last ticks' masks.
                if (planner_ && i == 0)
                    mix_context(io_, 2, ctx_join(ctx_join(ax, 13), (static_cast<std::uint64_t>(f.next_guess()) << 12) |
                                                                   (guess << 8) |
                                                                   (static_cast<std::uint64_t>(f.clock_phase()) << 4) | uf));
                else if (slots_ && i > 0)
                    mix_context(io_, 2, ctx_join(ctx_join(ax, 14), slot_context(ua, fa, lead_step)));
                else if (planner_ && crossing)
                    mix_context(io_, 2, ctx_join(ctx_join(ax, 12), grid_context(ua, fa)));
                else
                    mix_context(io_, 2, ctx_join(ctx_join(ax, 3), ((history_ & 0xFFFFFu) << 5) | m));
                // The guess flag: the axis's guessed next letter with the time
                // since its last step, in place of its last interval.
                mix_context(io_, 3, guessing_ ? ctx_join(ctx_join(ax, 9), (guess << 22) | (capped(since_[ua]) << 12) | uf)
                                           : ctx_join(ctx_join(ax, 4), (capped(since_[ua]) << 10) | capped(gap_[ua])));
                // Coding 2: where the axis's line broke, in place of its admitted set
                // and b (which the primary context holds). The guess flag, on an
                // interrupt block's axis that follows the leader: where in the
                // leader's interval its Bresenham line steps (crossing()).
                const std::uint64_t cross = crossing ? crossing_context(ua, fa) : 0;
                if (crossing)
                    mix_context(io_, 4, ctx_join(ctx_join(ax, 10), cross));
                else
                    mix_context(io_, 4, ctx_join(ctx_join(ax, 5), sure_ ? (f.breaks() << 2) | uf : (uf << 2) | static_cast<std::uint64_t>(ba)));
                mix_context(io_, 5, ctx_join(ctx_join(ax, 6), ((bres_[ua].recent() & 0xFFu) << 1) | static_cast<std::uint64_t>(lead_step)));
                const auto& g = gaps_[ua];
                const std::uint64_t tr = static_cast<std::uint64_t>(trend(since_[ua] + 1, g));
                mix_context(io_, 6, ctx_join(ctx_join(ax, 7), guessing_ ? (tr << 12) | (guess << 4) | uf
                                                                     : (tr << 4) | uf));
                mix_context(io_, 7, ctx_join(ctx_join(ax, 8), pattern(since_[ua] + 1, g)));
                // The match flag: the match's state with t.
                if (match_) mix_context(io_, 8, ctx_join(ctx_join(ax, 11), (ms << 2) | uf));
                if (planner_) {
                    // The planned probability (the axis's own line's and its
                    // slot line's) as the mixers' direct inputs and, with
                    // coding 2, with the match's bit, a, b and i, the sure
                    // decisions' row.
                    const auto st = [](std::int64_t p) {
                        return stretch(static_cast<std::uint32_t>(std::clamp<std::int64_t>(p, 128, 65536 - 128)));
                    };
                    if (own >= 0) io_.m->direct(0, st(own));
                    if (slot >= 0) io_.m->direct(1, st(slot));
                    if (sure_) {
                        const int pg = pp < 0 ? 0 : pp == 0 ? 1 : pp == 65536 ? 2 : 3 + static_cast<int>(pp * 4 / 65536);
                        const int mb = ms == 0 ? 0 : 1 + static_cast<int>((ms - 1) & 1u);
                        io_.m->sure_row(((((pg * 4 + fa) * 4 + ba) * 2 + (i > 0)) * 3) + mb);
                    }
                }
                if (guided_) {
                    // The guessed letter with b picks mixer 1's weight set; the
                    // step against the trend with t mixer 2's and the letter,
                    // b, t and i the second map's row, or on an axis that
                    // follows the leader of an interrupt block where its
                    // Bresenham line crosses (d = cross >> 3) and that context.
                    // With the match flag, a match of kGuideLength ticks or
                    // more picks mixer 1's set by its state instead.
                    const int gb = static_cast<int>(guess) * 4 + ba;
                    const bool matched = ms != 0 && match_->length() >= TickMatch::kGuideLength;
                    const int set1 = matched ? kGuidedMatchSets + static_cast<int>(ms) - 1 : kGuidedSets + gb;
                    if (crossing)
                        io_.m->guide(set1, kGuidedCrossSets + static_cast<int>(cross >> 3) * 3 + fa - 1,
                                     kGuidedRows + static_cast<int>(cross));
                    else
                        io_.m->guide(set1, kGuidedSets + static_cast<int>(tr >> 2) * 3 + fa - 1,
                                     (gb * 4 + fa) * 2 + (i > 0));
                }
            }
            Prob& pr = t_.axis(ua).step[ctx];
            // The refine flag (the plain coding): under a match of
            // kGuideLength ticks or more the decision is coded in a context
            // of the match's state and of its own context's probability (in
            // sixteenths of the stretched domain), and both adapt.
            Prob* coded = &pr;
            if (refine_ && ms != 0 && match_->length() >= TickMatch::kGuideLength) {
                const auto q = static_cast<std::uint64_t>((stretch(65536u - pr.p) + 2048) >> 8);
                coded = &refined_[ua][static_cast<std::size_t>((ms - 1) * 16 + q)];
            }
            // The match flag with coding 2: a sure decision that a match of
            // kUnsureLength ticks or more contradicts is mixed.
            bool unsure = false;
            if constexpr (kMixedIo<Io>) {
                if (sure_ && match_ && match_->length() >= TickMatch::kUnsureLength) {
                    unsure = ms != 0 && static_cast<int>((ms - 1) & 1u) != (pr.p < 32768 ? 1 : 0);
                    if (unsure) io_.sure = 0;
                }
                // The planner model: one that the planned letter contradicts too.
                if (sure_ && planner_ && !unsure) {
                    unsure = pp >= 0 && (pp >= 32768) != (pr.p < 32768);
                    if (unsure) io_.sure = 0;
                }
            }
            const int step = io_.bit(*coded, static_cast<int>((mask >> a) & 1u));
            if (coded != &pr) update(pr, step);
            if constexpr (kMixedIo<Io>) {
                if (unsure) io_.sure = kSure;
            }
            f.push(step, fa);
            if (windows_) {
                if (i > 0 && lead_step) {
                    bres_[ua].push(moved_[ua] | step, wa);
                    moved_[ua] = 0;
                } else if (i > 0 && step) {
                    moved_[ua] = 1;
                }
            } else if (ba != 0) {
                bres_[ua].push(step, ba);
            }
            if (i == 0) lead_step = step;
            if (slots_) {
                if (i == 0) count_slots(step);
                else push_slots(ua, step);
            }
            if (step) {
                const int sb = std::min(bit_length(static_cast<std::uint64_t>(since_[ua])), kSinceBuckets - 1);
                if constexpr (kMixedIo<Io>) {
                    io_.field(2);
                    for (int k = 0; k < (match_ ? kMixMatchModels : kMixMaxModels); ++k)
                        mix_context(io_, k, ctx_join(ctx_join(static_cast<std::uint64_t>(a), 16 + static_cast<std::uint64_t>(k)),
                                                     capped(since_[ua])));
                }
                const int flip = io_.bit(t_.axis(ua).dir[static_cast<std::size_t>(sb)],
                                         static_cast<int>(((neg >> a) & 1u) != (sign_[ua] < 0)));
                if (flip) sign_[ua] = -sign_[ua];
                m |= 1u << a;
                if (sign_[ua] < 0) n |= 1u << a;
            }
        }
        for (int a = 0; a < minor_; ++a) {
            const auto ua = static_cast<std::size_t>(a);
            if ((m >> a) & 1u) {
                gap_[ua] = since_[ua] + 1;
                auto& g = gaps_[ua];
                for (std::size_t j = g.size() - 1; j > 0; --j) g[j] = g[j - 1];
                g[0] = gap_[ua];
                since_[ua] = 0;
            } else {
                ++since_[ua];
            }
        }
        history_ = (history_ << minor_) | m;
        if (match_) match_->push(m);
        mask = m;
        neg = n;
    }

private:
    // Interrupt blocks, the `b` term of axis a of rank i (0 for the
    // leader): 1 when the axis has stepped in the current window or its
    // window follower admits no step, 2 when it admits only a step and the
    // window closes now (the leader steps), 3 otherwise.
    int window_context(int i, int wa, int lead_step, std::size_t ua) const {
        if (i == 0) return 0;
        if (moved_[ua] || wa == 1) return 1;
        return wa == 2 && lead_step ? 2 : 3;
    }

    // Whether the followers B[a] keep a guess: only an interrupt block's
    // crossing context reads it (a tick block's would be work unread).
    bool bres_guessing() const { return guessing_ && windows_; }

    // The guess flag, axis `ua` of an interrupt block that follows the
    // leader: a step now against the tick where its Bresenham line
    // (bres_) crosses to its next step, that line's crossing() as a share
    // of the leader's last interval after the leader's last step, in
    // quarter ticks and clamped (18: no crossing in this interval); with
    // whether the axis has stepped in the interval and its admitted set.
    std::uint64_t crossing_context(std::size_t ua, int fa) const {
        const std::int64_t cr = bres_[ua].crossing();
        const auto ul = static_cast<std::size_t>(leader_);
        int d = 18;
        if (cr >= 0 && gap_[ul] > 0)
            d = clamp_int(4 * (since_[ul] + 1) - 4 * cr * gap_[ul] / RateGuess::kOne, -8, 8) + 8;
        return static_cast<std::uint64_t>((d * 2 + moved_[ua]) * 4 + fa);
    }

    // The planner model, axis `ua` of an interrupt block that follows the
    // leader: the tick of a step now against the ticks where its Bresenham
    // line would step if the leader's last interval g held 2^L interrupts,
    // for L = 3, 2, 1 (a controller steps at its interrupts: Grbl's AMASS
    // runs 2, 4 or 8 of them a leader step), the step at the first
    // interrupt at or after the line's crossing() and on the first tick at
    // or after that interrupt, each clamped to +-3 ticks; with g, the
    // ticks since the leader's last step, whether the axis has stepped in
    // the interval and its admitted set.
    std::uint64_t grid_context(std::size_t ua, int fa) const {
        const std::int64_t cr = bres_[ua].crossing();
        const auto ul = static_cast<std::size_t>(leader_);
        const std::int64_t g = gap_[ul], now = since_[ul] + 1;
        std::uint64_t q = std::uint64_t{1} << 15;  // no crossing in this interval, or no interval
        if (cr >= 0 && g > 0) {
            q = 0;
            for (int L = 3; L >= 1; --L) {
                const std::int64_t k = ((cr << L) + RateGuess::kOne - 1) / RateGuess::kOne;
                const std::int64_t at = ((k * g) + (std::int64_t{1} << L) - 1) >> L;
                q = q * 8 + static_cast<std::uint64_t>(clamp_int(now - at, -3, 3) + 3);
            }
            q = q * 64 + static_cast<std::uint64_t>(std::min<std::int64_t>(g, 63));
        }
        return (q << 16) | (static_cast<std::uint64_t>(std::min<std::int64_t>(now, 63)) << 10) |
               (static_cast<std::uint64_t>(std::min<std::int64_t>(g, 63)) << 4) | (static_cast<std::uint64_t>(moved_[ua]) << 2) |
               static_cast<std::uint64_t>(fa);
    }

    // Slot lines (kTickSlots): an interrupt block's axis that follows the
    // leader steps at one of the controller's interrupts, which run 2^L
    // times per leader step at step smoothing level L (Grbl's AMASS, L
    // from 1 to 3), and on that grid of slots its Bresenham line is
    // exact. The slots are placed by the leader's line: at a tick, those
    // of level L between its counter (RateGuess::counter()) before and
    // after the tick, or, while it has no line, the share of its last
    // interval elapsed. Each axis reads one slot line a level, a letter a
    // slot: whether it stepped there. A slot that the counter crossed
    // within its uncertainty of the tick's end may come out on the next
    // tick: its letter waits a tick.

    // Every slot line empty, no slot counted.
    void reset_slots() {
        for (auto& lines : slot_lines_)
            for (Follower& f : lines) f.reset(true, true);
        for (auto& a : ahead_) a.fill(0);
        for (auto& a : pending_) a.fill(0);
        slot_at_.fill(0);
    }
    // After the leader's decision at a tick (`lead_step`: it stepped), the
    // slots of each level the tick crosses, and whether the counter has
    // moved on from the last of them by less than half its uncertainty:
    // with the leader's guess, the larger of its phases' width and half
    // its rate (a quarter tick); else the leader's advance a tick by its
    // last interval (half a tick).
    void count_slots(int lead_step) {
        const auto ul = static_cast<std::size_t>(leader_);
        const RateGuess& lg = axis_[ul].guessed();
        std::int64_t c = 0;
        if (lg.valid())
            c = lg.counter();
        else if (gap_[ul] > 0)
            c = lead_step ? 0 : (since_[ul] + 1) * RateGuess::kOne / gap_[ul];
        c = std::clamp<std::int64_t>(c, 0, RateGuess::kOne - 1);
        const std::int64_t band = lg.valid()     ? std::max(lg.width(), lg.rate() / 2)
                                  : gap_[ul] > 0 ? RateGuess::kOne / gap_[ul]
                                                 : RateGuess::kOne;
        for (std::size_t j = 0; j < kSlotLevels; ++j) {
            const int level = static_cast<int>(kSlotLevels - j);
            const int at = static_cast<int>((c << level) / RateGuess::kOne);
            crossed_[j] = std::max(lead_step ? at + (1 << level) - slot_at_[j] : at - slot_at_[j], 0);
            slot_at_[j] = at;
            late_[j] = 2 * (c - ((static_cast<std::int64_t>(at) * RateGuess::kOne) >> level)) < band;
        }
    }
    // The slots of level j this tick crosses that axis ua has not read yet.
    int slots_left(std::size_t ua, std::size_t j) const { return std::max(crossed_[j] - ahead_[ua][j], 0); }
    // Axis ua's decision `step` on its slot lines: a slot pending from
    // the tick before is read first, as the decision; then the slots
    // crossed are read as 0s but the last, read as the decision when the
    // pending slot did not take it, else left pending when it lies near
    // the tick's end (count_slots()), else read as 0. A step where no slot is left
    // is read on the next slot, which the ticks after then skip.
    void push_slots(std::size_t ua, int step) {
        for (std::size_t j = 0; j < kSlotLevels; ++j) {
            Follower& f = slot_lines_[ua][j];
            int& pending = pending_[ua][j];
            int x = step;  // the decision, until a slot takes it
            if (pending) {
                f.push(x, f.admits());
                pending = 0;
                x = 0;
            }
            const int n = crossed_[j] - ahead_[ua][j];
            if (n <= 0) {
                ahead_[ua][j] = -n;
                if (x) {
                    f.push(1, f.admits());
                    ++ahead_[ua][j];
                }
                continue;
            }
            ahead_[ua][j] = 0;
            for (int k = 1; k < n; ++k) f.push(0, f.admits());
            if (x || !late_[j])
                f.push(x, f.admits());
            else
                pending = 1;
        }
    }
    // Model 2 of axis ua: per level, none when the tick crosses no slot
    // left and none is pending, else its slot line's next letter
    // (Follower::guess()), apart for a pending slot alone; with whether the
    // leader steps now, whether the axis has stepped since it did and the
    // admitted set.
    std::uint64_t slot_context(std::size_t ua, int fa, int lead_step) const {
        std::uint64_t v = 0;
        for (std::size_t j = 0; j < kSlotLevels; ++j) {
            const int g = slot_lines_[ua][j].guess();
            v = v * 32 + static_cast<std::uint64_t>(slots_left(ua, j) > 0 ? 1 + g : pending_[ua][j] ? 10 + g : 0);
        }
        return (v << 4) | (static_cast<std::uint64_t>(lead_step) << 3) | (static_cast<std::uint64_t>(moved_[ua]) << 2) |
               static_cast<std::uint64_t>(fa);
    }
    // The planned probability of a step of axis ua by the longest of its
    // slot lines whose guess holds, once kSlotLine letters long: 0 when the
    // tick crosses no slot left of its level and none is pending, else that
    // line's probability of a 1 next; -1 without such a line.
    std::int64_t slot_p1(std::size_t ua) const {
        std::size_t best = 0;
        std::int64_t length = -1;
        for (std::size_t j = 0; j < kSlotLevels; ++j) {
            const Follower& f = slot_lines_[ua][j];
            const std::int64_t len = f.planned_p1() < 0 ? -1 : f.length();
            if (len > length) {
                length = len;
                best = j;
            }
        }
        if (length < kSlotLine) return -1;
        return slots_left(ua, best) == 0 && !pending_[ua][best] ? 0 : slot_lines_[ua][best].planned_p1();
    }
    static constexpr std::size_t kSlotLevels = 3;  // L = 3, 2, 1
    static constexpr std::int64_t kSlotLine = 4;

    static std::uint64_t capped(std::int64_t v) { return static_cast<std::uint64_t>(std::min<std::int64_t>(v, 1023)); }
    // Mixed coding, the intervals of an axis `g` (latest first, 0: none):
    // a step now (after `next` ticks) against the next interval
    // extrapolated from the last eight (two means of four and their
    // change: constant acceleration), in quarter ticks and clamped, with
    // the extrapolation's fraction of a tick in quarters; 0 before eight.
    static int trend(std::int64_t next, const std::array<std::int64_t, 8>& g) {
        if (g[7] == 0) return 0;
        const std::int64_t s1 = g[0] + g[1] + g[2] + g[3], s2 = g[4] + g[5] + g[6] + g[7];
        const std::int64_t pred = 8 * s1 + 5 * (s1 - s2);  // in 1/32 tick
        const int d = clamp_int(dss::floor_div(32 * next - pred, 8), -12, 12) + 12;
        const int frac = static_cast<int>((pred & 31) / 8);  // pred mod 32, in quarters
        return 1 + d * 4 + frac;
    }
    // The shape of the last intervals, whatever the rate (a jitter that
    // repeats): a step now (after `next` ticks) against the last interval,
    // and each of the last four intervals against the one before, clamped.
    static std::uint64_t pattern(std::int64_t next, const std::array<std::int64_t, 8>& g) {
        std::uint64_t v = static_cast<std::uint64_t>(clamp_int(next - g[0], -8, 8) + 8);
        for (std::size_t j = 0; j + 1 < 4; ++j)
            v = v * 8 + static_cast<std::uint64_t>(g[j + 1] == 0 ? 7 : clamp_int(g[j] - g[j + 1], -3, 3) + 3);
        return v;
    }
    // Ticks per step of axis a, in eighths: its last interval, or the time
    // it has rested when longer; with the planner model, once it has four
    // intervals, their mean, or that of the last three and the time it has
    // rested when longer (a leader that changes less often, nearer the
    // controller's Bresenham major axis of a move); unknown before its
    // second step.
    std::int64_t key(int a) const {
        const auto ua = static_cast<std::size_t>(a);
        if (gap_[ua] == 0) return INT64_MAX;
        const auto& g = gaps_[ua];
        if (planner_ && g[3] != 0) return 2 * (g[0] + g[1] + g[2] + std::max(g[3], since_[ua]));
        return 8 * std::max(gap_[ua], since_[ua]);
    }

    Io& io_;
    TickTables& t_;
    int minor_;
    bool windows_;
    bool sure_;     // coding 2
    bool restart_;  // the coding flag kTickRestart
    bool guessing_;  // the coding flag kTickGuess
    bool guided_;    // the coding flag kTickGuided
    bool refine_;    // the coding flag kTickRefine
    bool planner_;   // the planner model (kTickPlanner)
    bool slots_;     // its slot lines (kTickSlots)
    std::unique_ptr<TickMatch> match_;  // the coding flag kTickMatch (mixed codings) or kTickRefine (plain)
    // kTickRefine: per axis, the contexts by the match's state (1..36) and q (0..15).
    std::array<std::array<Prob, 36 * 16>, kMinor> refined_{};
    std::array<int, kMinor> moved_{};    // interrupt blocks: the axis stepped since the leader's last step
    std::array<Follower, kMinor> axis_;  // each axis over every tick
    std::array<Follower, kMinor> bres_;  // each axis over the ticks where the leader steps
    // Slot lines: per axis and level (L = 3, 2, 1), the line over its
    // slots, the slots it has read ahead of the ticks and whether a slot
    // waits for the next tick; per level, the slot the leader's counter is
    // in, the slots the tick crossed and whether the last lies near the
    // tick's end.
    std::array<std::array<Follower, kSlotLevels>, kMinor> slot_lines_;
    std::array<std::array<int, kSlotLevels>, kMinor> ahead_{}, pending_{};
    std::array<int, kSlotLevels> slot_at_{}, crossed_{};
    std::array<bool, kSlotLevels> late_{};
    int leader_ = -1;
    std::uint64_t history_ = 0;  // the step masks of the last ticks, the latest in the low bits
    std::array<int, kMinor> sign_{};
    std::array<std::int64_t, kMinor> since_{}, gap_{};
    std::array<std::array<std::int64_t, 8>, kMinor> gaps_{};  // each axis's last eight intervals, latest first
};


}  // namespace

namespace {

// The chains of `block` (every step advancing time) coded through `io`.
template <class Io>
void write_ticks(Io& io, TickTables& t, const Block& block, bool windows, TickCoding coding, unsigned flags,
                 const WindowView* window) {
    const int axes = block.axes;
    std::uint64_t ticks = 0;
    for (const Chain& chain : block.chains) ticks += chain.steps.size();
    TickCoder<Io> coder(io, t, axes, windows, coding, flags, ticks, window);
    Point ref{};
    for (const Chain& chain : block.chains) {
        io.field(3);
        for (int a = 0; a < axes; ++a)  // modulo 2^64, as the decoder adds it back
            code_sint(io, t.head().start,
                      static_cast<std::int64_t>(static_cast<std::uint64_t>(chain.start[a]) -
                                                static_cast<std::uint64_t>(ref[a])));
        code_uint(io, t.head().length, chain.steps.size());
        coder.start_chain();
        for (const Step s : chain.steps) {
            unsigned mask = 0, neg = 0;
            for (int a = 1; a < axes; ++a) {
                const int d = step_axis(s, a);
                if (d != 0) mask |= 1u << (a - 1);
                if (d < 0) neg |= 1u << (a - 1);
            }
            coder.tick(mask, neg);
        }
        ref = chain.end();
    }
}

std::string write_ticks_payload(const Block& block, TickCoding coding, unsigned flags, unsigned subtype,
                                const WindowView* window) {
    const int axes = block.axes;
    if (axes < 2 || axes > kMaxAxes) return {};
    std::uint64_t nsteps = 0;
    for (const Chain& chain : block.chains) {
        for (const Step s : chain.steps)
            if (step_axis(s, 0) != 1) return {};
        nsteps += chain.steps.size();
    }
    std::string out;
    flags &= tick_flags(coding);
    if (!(flags & (kTickMatch | kTickRefine)) || !window || !has_ticks(*window)) flags &= ~kTickWindow;
    const bool planner = (flags & kTickPlanner) != 0;
    if (!planner || subtype != kInterruptSubtype) flags &= ~kTickSlots;
    put_u8(out, !planner ? subtype : subtype == kInterruptSubtype ? kInterruptPlannerSubtype : kTickPlannerSubtype);
    put_u8(out, static_cast<unsigned>(coding) | (flags & ~(kTickPlanner | kTickSlots)));
    if (planner) put_u8(out, (flags & kTickSlots) ? kSlotModel : kPlannerModel);
    put_varint(out, block.chains.size());
    put_varint(out, nsteps);
    put_layout(out, block.layout);
    const TickTablesLease tables(axes - 1);
    if (coding != TickCoding::plain) {
        MixPredictor pred((*tables).base(), (flags & kTickMatch) ? kMixMatchModels : kMixMaxModels,
                          mix_guide(static_cast<unsigned>(coding) | flags, nsteps));
        MixEncIo io;
        io.m = &pred;
        write_ticks(io, *tables, block, subtype == kInterruptSubtype, coding, flags, window);
        out += io.rc.finish();
    } else {
        EncIo io;
        write_ticks(io, *tables, block, subtype == kInterruptSubtype, coding, flags, window);
        out += io.rc.finish();
    }
    return out;
}

}  // namespace

unsigned tick_model_flags(std::string_view payload) {
    if (payload.size() < 3 || !has_model_byte(static_cast<unsigned char>(payload[0]))) return 0;
    return kTickPlanner | (static_cast<unsigned char>(payload[2]) == kSlotModel ? kTickSlots : 0u);
}

bool has_ticks(const WindowView& window) {
    return std::any_of(window.begin(), window.end(), [](const auto& b) { return !b->ticks.empty(); });
}

std::string write_tick_block(const Block& block, TickCoding coding, unsigned flags, const WindowView* window) {
    return write_ticks_payload(block, coding, flags, kTickSubtype, window);
}

std::string write_interrupt_block(const Block& block, TickCoding coding, unsigned flags, const WindowView* window) {
    return write_ticks_payload(block, coding, flags, kInterruptSubtype, window);
}

namespace {

template <class Io>
Result<void> read_ticks(std::string_view payload, int axes, bool expand, Block& out, BlockCounts& counts,
                        const std::string& where, const WindowView* window) {
    Cursor cur(payload);
    unsigned subtype, coding;
    if (!cur.u8(subtype) || !is_tick_subtype(subtype))
        return make_error(Errc::corrupt, where + " byte 0: unknown subtype of an extended block");
    const bool windows = is_interrupt_subtype(subtype);
    const auto is = [&](TickCoding c) { return (coding & ~tick_flags(c)) == static_cast<unsigned>(c); };
    if (!cur.u8(coding) || (kMixedIo<Io> ? !is(TickCoding::mixed) && !is(TickCoding::mixed_sure) : !is(TickCoding::plain)) ||
        ((coding & kTickWindow) && !(coding & (kTickMatch | kTickRefine))))
        return make_error(Errc::corrupt, where + " byte 1: unknown coding of " +
                                             (windows ? "an interrupt block" : "a tick block"));
    if ((coding & kTickWindow) && !window)
        return make_error(Errc::corrupt, where + " byte 1: the match reads the window of a block not flagged window");
    if (has_model_byte(subtype)) {
        // Slot lines: an interrupt block with a mixed coding only.
        unsigned model;
        if (!cur.u8(model) || (model != kPlannerModel && (model != kSlotModel || !windows || !kMixedIo<Io>)))
            return make_error(Errc::corrupt, where + " byte 2: unknown model of " +
                                                 (windows ? "an interrupt block" : "a tick block"));
        coding |= tick_model_flags(payload);
    }
    const std::size_t header = cur.pos();
    std::uint64_t nchains, nsteps;
    if (!cur.varint(nchains) || !cur.varint(nsteps))
        return make_error(Errc::corrupt, where + " byte " + std::to_string(cur.pos()) + ": bad payload header");
    if (nchains > kMaxBlockChains || nsteps > kMaxBlockSteps)
        return make_error(Errc::limit, where + " byte " + std::to_string(header) +
                                           ": payload declares more chains or steps than the limits");
    auto layout = get_layout(cur, where);
    if (!layout) return std::move(layout).error();
    const std::size_t base = cur.pos();
    const TickTablesLease tables(std::clamp(axes - 1, 0, kMinor));
    std::unique_ptr<MixPredictor> pred;
    if constexpr (kMixedIo<Io>)
        pred = std::make_unique<MixPredictor>((*tables).base(), (coding & kTickMatch) ? kMixMatchModels : kMixMaxModels,
                                              mix_guide(coding, nsteps));
    Io io = [&] {
        if constexpr (kMixedIo<Io>) return Io(payload.substr(base), pred.get());
        else return Io(payload.substr(base));
    }();
    TickTables& t = *tables;
    TickCoder<Io> coder(io, t, axes, windows, static_cast<TickCoding>(coding & ~kTickAllFlags), coding & kTickAllFlags,
                        nsteps, window);
    start_output(out, expand, axes, std::move(*layout));
    auto fail = [&](const char* what) {
        return make_error(Errc::corrupt, where + " byte " + std::to_string(base + io.rc.pos()) + ": " + what);
    };
    Point ref{};
    std::uint64_t seen = 0;
    for (std::uint64_t i = 0; i < nchains; ++i) {
        Point d{};
        io.field(3);
        for (int a = 0; a < axes; ++a) d[a] = code_sint(io, t.head().start, 0);
        const std::uint64_t n = code_uint(io, t.head().length, 0);
        if (io.failed || io.rc.overrun()) return fail("bad chain header");
        Chain chain;
        chain.axes = axes;
        if (!rebuild_start(ref, d, axes, chain.start)) return fail("chain start out of range");
        if (n > nsteps - seen) return fail("more steps than declared");
        seen += n;
        coder.start_chain();
        if (expand) chain.steps.reserve(static_cast<std::size_t>(n));
        Point pos = chain.start;
        for (std::uint64_t k = 0; k < n; ++k) {
            unsigned mask = 0, neg = 0;
            coder.tick(mask, neg);
            if (io.rc.overrun()) return fail("range-coded stream ends early");
            int dd[kMaxAxes] = {1};
            for (int a = 1; a < axes; ++a)
                dd[a] = ((mask >> (a - 1)) & 1u) ? (((neg >> (a - 1)) & 1u) ? -1 : 1) : 0;
            const Step s = make_step(dd, axes);
            apply_step(pos, s, axes);
            if (expand) chain.steps.push_back(s);
        }
        ref = pos;
        if (expand) out.chains.push_back(std::move(chain));
    }
    if (seen != nsteps) return fail("declared step count does not match");
    if (!io.rc.finished()) return fail("range-coded stream does not end at the payload's end");
    counts.chains += nchains;
    counts.steps += nsteps;
    return {};
}

}  // namespace

Result<void> read_tick_block(std::string_view payload, int axes, bool expand, Block& out, BlockCounts& counts,
                             const std::string& where, const WindowView* window) {
    // The coding byte picks the coder (an unknown one is reported by the plain reader).
    const unsigned coding =
        payload.size() >= 2 ? static_cast<unsigned char>(payload[1]) & ~kTickAllFlags : 0;
    if (coding == static_cast<unsigned>(TickCoding::mixed) || coding == static_cast<unsigned>(TickCoding::mixed_sure))
        return read_ticks<MixDecIo>(payload, axes, expand, out, counts, where, window);
    return read_ticks<DecIo>(payload, axes, expand, out, counts, where, window);
}

}  // namespace stepzip::stz
