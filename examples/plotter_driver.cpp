// plotter_driver: HP-GL in, step pulses out — what the driver of a stepper
// pen plotter does with a plot file.
//
//   plotter_driver PLOT.hpgl OUT.fc [PROFILE]
//
// Reads the HP-GL drawing (coordinates in plotter units = steps), runs the
// profile's forward interpolator (default eval8, the leading-axis method of
// GRBL-like controllers) over every pen-down path and writes the pulses as a
// freeman chain file, one chain per path. On stderr: paths, vectors, steps,
// and how many steps were diagonal (both motors pulsed in one tick).
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "stepzip/document.hpp"
#include "stepzip/vectors.hpp"

int main(int argc, char** argv) {
    if (argc < 3 || argc > 4) {
        std::cerr << "usage: plotter_driver PLOT.hpgl OUT.fc [PROFILE]\n";
        return 2;
    }
    std::ifstream in(argv[1], std::ios::binary);
    if (!in) {
        std::cerr << "plotter_driver: cannot open " << argv[1] << "\n";
        return 1;
    }
    std::stringstream text;
    text << in.rdbuf();

    stepzip::VectorReadOptions read;
    read.source = argv[1];
    auto drawing = stepzip::read_hpgl(text.str(), read);
    if (!drawing) {
        std::cerr << "plotter_driver: " << drawing.error().message << "\n";
        return 1;
    }

    stepzip::DrawingInterpolation how;
    how.source = argv[1];
    if (argc == 4) {
        auto p = stepzip::parse_profile(argv[3]);
        if (!p) {
            std::cerr << "plotter_driver: unknown profile " << argv[3] << "\n";
            return 2;
        }
        how.profile = *p;
    }
    std::vector<int> pens;  // one per chain: the HP-GL pen (SP) that drew it
    auto chains = stepzip::interpolate_drawing(*drawing, how, &pens);
    if (!chains) {
        std::cerr << "plotter_driver: " << chains.error().message << "\n";
        return 1;
    }

    std::size_t vectors = 0, steps = 0, diagonal = 0;
    for (const auto& path : *drawing) vectors += path.moves.size();
    for (const auto& chain : *chains) {
        steps += chain.steps.size();
        for (stepzip::Step s : chain.steps) diagonal += stepzip::step_weight(s) == 2;
    }

    auto out = stepzip::write_chains_with_pens(stepzip::InputFormat::freeman, *chains, pens);
    if (!out) {
        std::cerr << "plotter_driver: " << out.error().message << "\n";
        return 1;
    }
    std::ofstream file(argv[2], std::ios::binary);
    file << *out;
    if (!file.flush()) {
        std::cerr << "plotter_driver: cannot write " << argv[2] << "\n";
        return 1;
    }
    std::cerr << "plotter_driver: " << chains->size() << " paths, " << vectors << " vectors, "
              << steps << " steps (" << diagonal << " diagonal) under "
              << stepzip::profile_name(how.profile) << "\n";
    return 0;
}
