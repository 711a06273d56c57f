// stepzip interpolate: vectors (G-code, HP-GL) -> unit-step chains, by the
// forward interpolators (SPEC §6). One chain per pen-down path.
#include <boost/program_options.hpp>

#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "commands.hpp"
#include "stepzip/document.hpp"
#include "stepzip/interpolate/arc.hpp"
#include "stepzip/profile.hpp"
#include "stepzip/vectors.hpp"

namespace po = boost::program_options;

namespace stepzip::cli {

namespace {

/// Largest number of steps one run may produce (2 bytes each in memory).
constexpr std::size_t kMaxOutputSteps = std::size_t{1} << 28;

std::string move_place(const std::string& source, const VectorMove& m) {
    return source + ":" + std::to_string(m.line) + ":" + std::to_string(m.column);
}

}  // namespace

int cmd_interpolate(const std::vector<std::string>& args) {
    po::options_description desc(
        "Usage: stepzip interpolate --profile P [IN | -] [OPTIONS]\n"
        "Vectors (G-code or HP-GL) -> unit-step chains, one chain per pen-down path.\n"
        "Options");
    std::string profile_arg, from_arg, to_arg = "freeman", out_arg, step_arg, arc_arg,
                             line_arg = "profile", input;
    desc.add_options()
        ("help,h", "show this help")
        ("profile", po::value(&profile_arg), "forward interpolator for lines: eval4, eval8, "
                                             "patent, grbl, marlin (required)")
        ("from", po::value(&from_arg), "input format: gcode or hpgl (default: detected)")
        ("to", po::value(&to_arg), "output chain format: freeman (default), points, steps")
        ("output,o", po::value(&out_arg), "output file (default: standard output)")
        ("stdout,c", "write to standard output")
        ("force,f", "overwrite an existing output; binary output to a terminal")
        ("step-size", po::value(&step_arg),
         "millimetres per step (default: coordinates are steps); positions are rounded to "
         "the nearest step, halves away from zero")
        ("arc-method", po::value(&arc_arg),
         "G2/G3 interpolator: evaluation, accelerated, dda, prediction, recursion (default: "
         "evaluation for 4-connected profiles, accelerated for 8-connected)")
        ("line-method", po::value(&line_arg),
         "line interpolator: profile (default), dda, carrier");
    po::options_description hidden;
    hidden.add_options()("input", po::value(&input));
    po::options_description all;
    all.add(desc).add(hidden);
    po::positional_options_description pos;
    pos.add("input", 1);

    po::variables_map vm;
    try {
        po::store(po::command_line_parser(std::vector<std::string>(args.begin() + 1, args.end()))
                      .options(all)
                      .positional(pos)
                      .run(),
                  vm);
        po::notify(vm);
    } catch (const po::error& e) {
        return usage_error(std::string("interpolate: ") + e.what());
    }
    if (vm.count("help")) {
        std::cout << desc << "\n";
        return 0;
    }
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
    const std::string out_path = vm.count("stdout") ? std::string("-") : out_arg;
    const bool force = vm.count("force") > 0;
    if (*to == InputFormat::steps && is_dash(out_path) && !force && is_terminal(stdout))
        return report(make_error(Errc::invalid_argument,
                                 "binary output to a terminal refused (use -o FILE or -f)"));

    // Read and parse the vectors.
    auto data = read_input(input);
    if (!data) return report(data.error());
    if (!from) {
        from = detect_vector_format(std::string_view(*data).substr(0, 4096));
        if (!from)
            return report(make_error(Errc::syntax, read_options.source +
                                                       ": neither G-code nor HP-GL (use --from)"));
    }
    auto drawing = read_vectors(*from, *data, read_options);
    if (!drawing) return report(drawing.error());

    // Forward interpolation, one chain per path.
    std::vector<Chain> chains;
    std::size_t total = 0;
    Progress progress("interpolate", drawing->size());
    for (std::size_t p = 0; p < drawing->size(); ++p) {
        progress.update(p);
        const VectorPath& path = (*drawing)[p];
        Chain chain;
        chain.axes = 2;
        chain.start = {path.x0, path.y0};
        std::int64_t x = path.x0, y = path.y0;
        for (const VectorMove& m : path.moves) {
            const std::size_t before = chain.steps.size();
            if (m.kind == MoveKind::line) {
                if (line_method) {
                    auto r = interpolate_line(*line_method, m.x - x, m.y - y, chain.steps);
                    if (!r)
                        return report(make_error(r.error().code,
                                                 move_place(read_options.source, m) + ": " +
                                                     r.error().message));
                } else {
                    const Segment seg = default_segment(*profile, Point{m.x - x, m.y - y}, 2);
                    auto r = check_segment(*profile, seg, 2);
                    if (!r)
                        return report(make_error(r.error().code,
                                                 move_place(read_options.source, m) + ": " +
                                                     r.error().message));
                    if (total + static_cast<std::size_t>(
                                    segment_length(seg.delta, 2,
                                                   profile_eight_connected(*profile))) >
                        kMaxOutputSteps)
                        return report(make_error(Errc::limit,
                                                 move_place(read_options.source, m) +
                                                     ": output would exceed 2^28 steps"));
                    expand_segment(*profile, seg, 2, chain.steps);
                }
            } else {
                auto r = interpolate_arc(arc_method, x - m.cx, y - m.cy, m.x - m.cx, m.y - m.cy,
                                         m.kind == MoveKind::arc_ccw, chain.steps);
                if (!r)
                    return report(make_error(r.error().code, move_place(read_options.source, m) +
                                                                 ": " + r.error().message));
            }
            total += chain.steps.size() - before;
            if (total > kMaxOutputSteps)
                return report(make_error(Errc::limit, move_place(read_options.source, m) +
                                                          ": output would exceed 2^28 steps"));
            x = m.x;
            y = m.y;
        }
        if (!chain.steps.empty()) chains.push_back(std::move(chain));
    }
    progress.finish();

    auto text = write_chains(*to, chains);
    if (!text) return report(text.error());
    auto out = OutputFile::open(out_path, force);
    if (!out) return report(out.error());
    if (auto r = out->write(*text); !r) return report(r.error());
    if (auto r = out->commit(); !r) return report(r.error());
    return 0;
}

}  // namespace stepzip::cli
