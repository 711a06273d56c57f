// stepzip interpolate: vectors (G-code, HP-GL, SVG) -> unit-step chains, by the
// forward interpolators (SPEC §6). One chain per pen-down path.
#include <boost/program_options.hpp>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "commands.hpp"
#include "options.hpp"
#include "stepzip/document.hpp"
#include "stepzip/interpolate/arc.hpp"
#include "stepzip/profile.hpp"
#include "stepzip/vectors.hpp"

namespace po = boost::program_options;

namespace stepzip::cli {

namespace {

/// Largest number of steps one run may produce (2 bytes each in memory).
constexpr std::size_t kMaxOutputSteps = std::size_t{1} << 28;

}  // namespace

int cmd_interpolate(const std::vector<std::string>& args) {
    po::options_description desc(
        "Usage: stepzip interpolate --profile P [IN | -] [OPTIONS]\n"
        "Vectors (G-code, HP-GL or SVG) -> unit-step chains, one chain per pen-down path;\n"
        "with --axes, a G-code machine job -> its STEP/DIR stream, every move stepped.\n"
        "Options");
    std::string profile_arg, from_arg, to_arg = "freeman", out_arg, step_arg, arc_arg,
                             line_arg = "profile", input, axes_arg, spm_arg;
    double tolerance = 0.5;
    desc.add_options()
        ("help,h", "show this help")
        ("profile", po::value(&profile_arg), "forward interpolator for lines: eval4, eval8, "
                                             "patent, grbl, marlin (required)")
        ("from", po::value(&from_arg), "input format: gcode, hpgl or svg (default: detected)")
        ("to", po::value(&to_arg), "output chain format: freeman (default), points, steps")
        ("output,o", po::value(&out_arg), "output file (default: standard output)")
        ("stdout,c", "write to standard output")
        ("force,f", "overwrite an existing output; binary output to a terminal")
        ("step-size", po::value(&step_arg),
         "millimetres per step (default: coordinates are steps); positions are rounded to "
         "the nearest step, halves away from zero")
        ("tolerance", po::value(&tolerance),
         "SVG: largest distance, in steps, of the chords of a flattened curve from the curve "
         "(default 0.5); vertices are then rounded to whole steps")
        ("arc-method", po::value(&arc_arg),
         "G2/G3 interpolator: evaluation, accelerated, dda, prediction, recursion (default: "
         "evaluation for 4-connected profiles, accelerated for 8-connected)")
        ("line-method", po::value(&line_arg),
         "line interpolator: profile (default), dda, carrier")
        ("axes", po::value(&axes_arg),
         "G-code machine job on these axes, 2 to 6 of X Y Z A B C E in output order (e.g. "
         "XYZE): every move stepped, travel included, one chain per run (a G28 that moves "
         "starts a new one); --to steps writes the STEP/DIR bytes with each DIR line held "
         "for the whole move")
        ("steps-per-mm", po::value(&spm_arg),
         "with --axes: steps per mm (per degree for A B C), one value or one per axis, "
         "comma-separated (default: coordinates are steps)")
        ("verbose,v", "with --axes: print what was read (moves, runs, skipped words)");
    po::variables_map vm;
    if (auto exit_code = parse_command("interpolate", args, desc, "input", po::value(&input), 1, vm))
        return *exit_code;
    if (profile_arg.empty()) return usage_error("interpolate: --profile is required");
    const auto profile = parse_profile(profile_arg);
    if (!profile) return usage_error("interpolate: unknown profile '" + profile_arg + "'");
    std::optional<VectorFormat> from;
    if (!from_arg.empty()) {
        from = parse_vector_format(from_arg);
        if (!from) return usage_error("interpolate: unknown input format '" + from_arg + "'");
    }
    const auto to = parse_format(to_arg);
    if (!to) return usage_error("interpolate: unknown output format '" + to_arg + "'");
    VectorReadOptions read_options;
    read_options.source = input_name(input);
    if (!(tolerance > 0) || tolerance > 1e9)
        return usage_error("interpolate: --tolerance must be a positive number of steps");
    read_options.tolerance = tolerance;
    if (!step_arg.empty()) {
        auto s = parse_step_size(step_arg);
        if (!s) return usage_error("interpolate: " + s.error().message);
        read_options.step_size = *s;
    }
    ArcMethod arc_method =
        profile_eight_connected(*profile) ? ArcMethod::accelerated : ArcMethod::evaluation;
    if (!arc_arg.empty()) {
        const auto m = parse_arc_method(arc_arg);
        if (!m) return usage_error("interpolate: unknown arc method '" + arc_arg + "'");
        arc_method = *m;
    }
    std::optional<LineMethod> line_method;
    if (line_arg != "profile") {
        line_method = parse_line_method(line_arg);
        if (!line_method) return usage_error("interpolate: unknown line method '" + line_arg + "'");
    }
    const bool machine = !axes_arg.empty();
    if (!spm_arg.empty() && !machine) return usage_error("interpolate: --steps-per-mm needs --axes");
    if (machine && !step_arg.empty())
        return usage_error("interpolate: --step-size is for drawings; with --axes give --steps-per-mm");
    if (machine && line_method)
        return usage_error("interpolate: --line-method is for drawings, not with --axes");
    if (machine && from && *from != VectorFormat::gcode)
        return usage_error("interpolate: --axes reads G-code");
    MachineReadOptions job_options;
    job_options.source = read_options.source;
    job_options.axes = axes_arg;
    for (std::size_t b = 0; !spm_arg.empty() && b <= spm_arg.size();) {
        const std::size_t e = std::min(spm_arg.find(',', b), spm_arg.size());
        job_options.steps_per_mm.push_back(spm_arg.substr(b, e - b));
        b = e + 1;
    }
    const bool verbose = vm.count("verbose") > 0;
    const std::string out_path = vm.count("stdout") ? std::string("-") : out_arg;
    const bool force = vm.count("force") > 0;
    if (*to == InputFormat::steps && is_dash(out_path) && !force && is_terminal(stdout))
        return report(make_error(Errc::invalid_argument,
                                 "binary output to a terminal refused (use -o FILE or -f)"));

    // Read and parse the vectors.
    auto data = read_input(input);
    if (!data) return report(data.error());
    if (machine) {
        auto job = read_gcode_job(*data, job_options);
        if (!job) {
            if (job.error().code == Errc::invalid_argument)
                return usage_error("interpolate: " + job.error().message);
            return report(job.error());
        }
        JobStepping how;
        how.profile = *profile;
        how.arc_method = arc_method;
        how.max_steps = kMaxOutputSteps;
        how.source = read_options.source;
        auto stepped = step_job(*job, how);
        if (!stepped) return report(stepped.error());
        if (verbose) {
            std::size_t moves = 0, ticks = 0;
            for (const MachineRun& r : job->runs) moves += r.moves.size();
            for (const Chain& c : stepped->chains) ticks += c.steps.size();
            note("axes " + job->letters + ": " + std::to_string(moves) + " move(s) in " +
                 std::to_string(job->runs.size()) + " run(s), " + std::to_string(ticks) +
                 " tick(s); " + std::to_string(job->skipped_words) +
                 " word(s) skipped (M-codes, S, T, other axes, unknown words)");
        }
        auto text = *to == InputFormat::steps ? step_dir_bytes(*stepped)
                                              : write_chains(*to, stepped->chains);
        if (!text) return report(make_error(text.error().code,
                                            read_options.source + ": " + text.error().message));
        auto out = OutputFile::open(out_path, force);
        if (!out) return report(out.error());
        if (auto r = out->write(*text); !r) return report(r.error());
        if (auto r = out->commit(); !r) return report(r.error());
        return 0;
    }
    if (!from) {
        from = detect_vector_format(std::string_view(*data).substr(0, 4096));
        if (!from)
            return report(make_error(Errc::syntax, read_options.source +
                                                       ": neither G-code, HP-GL nor SVG (use --from)"));
    }
    if (vm.count("tolerance") && *from != VectorFormat::svg)
        return usage_error("interpolate: --tolerance is for SVG input");
    auto drawing = read_vectors(*from, *data, read_options);
    if (!drawing) return report(drawing.error());

    // Forward interpolation, one chain per path.
    DrawingInterpolation how;
    how.profile = *profile;
    how.line_method = line_method;
    how.arc_method = arc_method;
    how.max_steps = kMaxOutputSteps;
    how.source = read_options.source;
    std::vector<int> pens;
    auto chains = interpolate_drawing(*drawing, how, &pens);
    if (!chains) return report(chains.error());

    auto text = write_chains_with_pens(*to, *chains, pens);
    if (!text) return report(text.error());
    auto out = OutputFile::open(out_path, force);
    if (!out) return report(out.error());
    if (auto r = out->write(*text); !r) return report(r.error());
    if (auto r = out->commit(); !r) return report(r.error());
    return 0;
}

}  // namespace stepzip::cli
