// Uniform entry points for the forward arc and line interpolators (called by
// the G-code reader for G1/G2/G3 and by the CLI).
#include "stepzip/interpolate/arc.hpp"

#include "stepzip/interpolate/carrier.hpp"
#include "stepzip/interpolate/circular.hpp"
#include "stepzip/interpolate/dda.hpp"
#include "stepzip/interpolate/prediction.hpp"
#include "stepzip/interpolate/recursion.hpp"

namespace stepzip {

std::string_view arc_method_name(ArcMethod method) noexcept {
    switch (method) {
        case ArcMethod::evaluation: return "evaluation";
        case ArcMethod::accelerated: return "accelerated";
        case ArcMethod::dda: return "dda";
        case ArcMethod::prediction_correction: return "prediction";
        case ArcMethod::double_recursion: return "recursion";
    }
    return "?";
}

std::optional<ArcMethod> parse_arc_method(std::string_view name) noexcept {
    for (ArcMethod m : {ArcMethod::evaluation, ArcMethod::accelerated, ArcMethod::dda,
                        ArcMethod::prediction_correction, ArcMethod::double_recursion})
        if (arc_method_name(m) == name) return m;
    return std::nullopt;
}

Result<void> interpolate_arc(ArcMethod method, std::int64_t x0, std::int64_t y0,
                             std::int64_t x1, std::int64_t y1, bool ccw,
                             std::vector<Step>& out) {
    switch (method) {
        case ArcMethod::evaluation: return eval_circular(x0, y0, x1, y1, ccw, out);
        case ArcMethod::accelerated: return accelerated_circular(x0, y0, x1, y1, ccw, out);
        case ArcMethod::dda: return dda_circular(x0, y0, x1, y1, ccw, out);
        case ArcMethod::prediction_correction:
            return prediction_circular(x0, y0, x1, y1, ccw, out);
        case ArcMethod::double_recursion: return recursion_circular(x0, y0, x1, y1, ccw, out);
    }
    return make_error(Errc::invalid_argument, "interpolate_arc: unknown method");
}

std::string_view line_method_name(LineMethod method) noexcept {
    switch (method) {
        case LineMethod::dda: return "dda";
        case LineMethod::carrier: return "carrier";
    }
    return "?";
}

std::optional<LineMethod> parse_line_method(std::string_view name) noexcept {
    if (name == "dda") return LineMethod::dda;
    if (name == "carrier") return LineMethod::carrier;
    return std::nullopt;
}

Result<void> interpolate_line(LineMethod method, std::int64_t dx, std::int64_t dy,
                              std::vector<Step>& out) {
    switch (method) {
        case LineMethod::dda: return dda_linear(dx, dy, 0, out);
        case LineMethod::carrier: return carrier_linear(dx, dy, 0, out);
    }
    return make_error(Errc::invalid_argument, "interpolate_line: unknown method");
}

}  // namespace stepzip
