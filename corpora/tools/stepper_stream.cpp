// Turns a multi-axis polyline (one "x y z [a]" vertex per line, absolute, in
// steps) into the STEP/DIR byte log a grbl-style controller would emit:
// every line segment is interpolated by the leading-axis method at GRBL's
// counter phase (stepzip profile "grbl"), one byte per tick, bit 2i = axis i
// stepped, bit 2i+1 = axis i direction negative.
//
// Usage: stepper_stream < polyline.txt > job.steps
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "stepzip/interpolate/segment.hpp"
#include "stepzip/profile.hpp"

int main() {
    using namespace stepzip;
    std::string line;
    Point cur{};
    bool have = false;
    int axes = 0;
    std::vector<Step> steps;
    while (std::getline(std::cin, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream in(line);
        Point p{};
        int n = 0;
        while (n < kMaxAxes && (in >> p[n])) ++n;
        if (axes == 0) axes = n;
        if (n != axes) {
            std::fprintf(stderr, "inconsistent column count: %s\n", line.c_str());
            return 1;
        }
        if (have) {
            Point d{};
            bool any = false;
            for (int i = 0; i < axes; ++i) {
                d[i] = p[i] - cur[i];
                any = any || d[i] != 0;
            }
            if (any) {
                steps.clear();
                expand_segment(Profile::grbl, default_segment(Profile::grbl, d, axes), axes, steps);
                for (Step s : steps) std::putchar(static_cast<int>(s & 0xFF));
            }
        }
        cur = p;
        have = true;
    }
    return 0;
}
