// The recognizer the greedy and optimal drivers cut with. See internal.hpp.
#include "internal.hpp"

namespace stepzip::detail {

ProfileCut::ProfileCut(Profile p, int axes) : profile_(p), axes_(axes) {
    if (p == Profile::patent) {
        patent_.emplace();
        return;
    }
    runs_.emplace(p, axes);
    if (axes == 2) two_.emplace(p);
}

std::int64_t ProfileCut::longest_other(std::span<const Step> steps) {
    if (steps.empty()) return 0;
    if (runs_) return longest_exact_prefix(*runs_, steps);
    PatentRecognizer& rec = *patent_;
    rec.read(steps);
    return std::max<std::int64_t>(rec.longest_valid(), 1);
}

std::int64_t ProfileCut::window() const noexcept {
    return patent_ ? kPatentOptimalWindow : kOptimalWindow;
}

void ProfileCut::prepare(std::span<const Step> steps) {
    steps_ = steps;
    if (!runs_) return;
    const std::size_t n = steps.size();
    run_end_.resize(n);
    for (std::size_t i = n; i-- > 0;)
        run_end_[i] = static_cast<std::uint32_t>(
            i + 1 < n && steps[i + 1] == steps[i] ? run_end_[i + 1] : i + 1);
}

}  // namespace stepzip::detail
