// Forward interpolation of one segment: the profile picks the interpolator
// (SPEC section 3). The arithmetic here is normative for .stz files.
#include "stepzip/interpolate/segment.hpp"

#include "stepzip/interpolate/linear.hpp"

namespace stepzip {

void expand_segment(Profile p, const Segment& seg, int axes, std::vector<Step>& out) {
    switch (p) {
        case Profile::eval4:
            eval_linear(seg.delta[0], seg.delta[1], seg.phase[0], out);
            return;
        case Profile::patent:
            patent_forward(seg.delta[0], seg.delta[1], seg.phase[0], out);
            return;
        case Profile::eval8:
        case Profile::grbl:
        case Profile::marlin:
            multiaxis_linear(seg.delta, axes, seg.phase.data(), out);
            return;
    }
}

}  // namespace stepzip
