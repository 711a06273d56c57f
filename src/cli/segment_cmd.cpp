// stepzip segment: unit-step chains -> vectors (G-code, HP-GL, SVG, JSON) by
// reverse interpolation (SPEC §6).
#include <boost/program_options.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "commands.hpp"
#include "options.hpp"
#include "stepzip/document.hpp"
#include "stepzip/profile.hpp"
#include "stepzip/segmenter.hpp"
#include "stepzip/timed.hpp"
#include "stepzip/vectors.hpp"

namespace po = boost::program_options;

namespace stepzip::cli {

namespace {

enum class VectorOut { gcode, hpgl, svg, json };

std::optional<VectorOut> parse_vector_out(const std::string& s) {
    if (s == "gcode") return VectorOut::gcode;
    if (s == "hpgl") return VectorOut::hpgl;
    if (s == "svg") return VectorOut::svg;
    if (s == "json") return VectorOut::json;
    return std::nullopt;
}

// Cuts every chain under `profile`. `vectors`: the default-phase cut that
// vectors can carry (segment_default_phase); otherwise the segmenter's own
// exact cut, phases included (JSON). The patent mode keeps the approximation
// mode's read-out (end points only) and collects its deviation statistics.
Result<std::vector<SegmentedChain>> cut(const std::vector<Chain>& chains, Profile profile,
                                        SegmenterKind kind, bool vectors,
                                        const std::string& source, SegmentStats& stats) {
    std::vector<SegmentedChain> out;
    out.reserve(chains.size());
    for (std::size_t c = 0; c < chains.size(); ++c) {
        const Chain& chain = chains[c];
        const std::string where = source + ": chain " + std::to_string(c + 1) + ": ";
        SegmentedChain sc;
        sc.chain = chain;
        auto r = vectors && kind != SegmenterKind::patent
                     ? segment_default_phase(chain.steps, chain.axes, profile, sc.segments, kind)
                     : segment_steps(chain.steps, chain.axes, profile, kind, sc.segments, &stats);
        if (!r) return make_error(r.error().code, where + r.error().message);
        if (kind == SegmenterKind::patent) {
            std::vector<Point> ends;
            auto a = patent_approximate(chain.steps, ends);
            if (!a) return make_error(a.error().code, where + a.error().message);
            sc.segments.clear();
            for (const Point& e : ends) sc.segments.push_back(default_segment(profile, e, 2));
        }
        out.push_back(std::move(sc));
    }
    return out;
}

// The drawing of a timed log's moves (two-axis paths): per chain with
// steps one path from its start through the end of each move; with `feed`,
// each move's F is its cruise speed (steps/min, or mm/min with a step size).
Drawing timed_drawing(const std::vector<TimedReading>& readings, bool feed, const std::optional<StepSize>& step_size) {
    const double per_step = step_size ? static_cast<double>(step_size->mm_e12) * 1e-12 : 1.0;
    Drawing d;
    for (const TimedReading& r : readings) {
        if (r.moves.empty()) continue;
        VectorPath vp;
        vp.x0 = r.path.path.start[0];
        vp.y0 = r.path.path.start[1];
        std::int64_t x = vp.x0, y = vp.y0;
        for (const TimedMove& m : r.moves) {
            VectorMove mv;
            x += m.delta[0];
            y += m.delta[1];
            mv.x = x;
            mv.y = y;
            if (feed) mv.feed = m.speeds.cruise * 60 * per_step;
            vp.moves.push_back(mv);
        }
        d.push_back(std::move(vp));
    }
    return d;
}

std::string json_number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f", v);
    return buf;
}

// JSON of the moves of timed chains: per chain its path's start, per axis
// what its own steps say (estimate_axis_motion()) and per move its steps,
// ticks, totals, length and speeds (docs/cli.md).
std::string write_timed_json(const std::vector<TimedReading>& readings, double tick_us) {
    std::string out = "{\"tick_us\":" + json_number(tick_us) + ",\"units\":\"steps, steps/s and steps/s^2 (moves: along the path; axes: along the axis)\",\"chains\":[";
    for (std::size_t c = 0; c < readings.size(); ++c) {
        const Chain& path = readings[c].path.path;
        out += c ? ",\n{" : "\n{";
        out += "\"start\":[";
        for (int i = 0; i < path.axes; ++i) out += (i ? "," : "") + std::to_string(path.start[static_cast<std::size_t>(i)]);
        out += "],\"steps\":" + std::to_string(path.steps.size()) + ",\"axes\":[";
        for (std::size_t i = 0; i < readings[c].axes.size(); ++i) {
            const AxisMotion& a = readings[c].axes[i];
            out += i ? ",\n" : "\n";
            out += "{\"steps\":";
            out += std::to_string(a.steps);
            out += ",\"max_rate\":";
            out += json_number(a.max_rate);
            out += ",\"acceleration\":";
            out += json_number(a.acceleration);
            out += ",\"windows\":";
            out += std::to_string(a.windows);
            out += "}";
        }
        out += "],\"moves\":[";
        for (std::size_t k = 0; k < readings[c].moves.size(); ++k) {
            const TimedMove& m = readings[c].moves[k];
            out += k ? ",\n" : "\n";
            out += "{\"delta\":[";
            for (int i = 0; i < path.axes; ++i) {
                if (i) out += ',';
                out += std::to_string(m.delta[static_cast<std::size_t>(i)]);
            }
            out += "],\"ticks\":[" + std::to_string(m.first_tick) + "," + std::to_string(m.last_tick) + "]";
            out += ",\"length\":" + json_number(m.length);
            out += ",\"entry\":" + json_number(m.speeds.entry);
            out += ",\"cruise\":" + json_number(m.speeds.cruise);
            out += ",\"exit\":" + json_number(m.speeds.exit);
            out += ",\"acceleration\":" + json_number(m.speeds.acceleration);
            out += ",\"ramp_steps\":" + std::to_string(m.speeds.ramp_steps) + "}";
        }
        out += "]}";
    }
    out += "]}\n";
    return out;
}

// Writes `text` to the output (or reports its error, naming the source); the exit code.
int write_text(const Result<std::string>& text, const std::string& source, const std::string& out_path,
               bool force) {
    if (!text) return report(make_error(text.error().code, source + ": " + text.error().message));
    auto out = OutputFile::open(out_path, force);
    if (!out) return report(out.error());
    if (auto r = out->write(*text); !r) return report(r.error());
    if (auto r = out->commit(); !r) return report(r.error());
    return 0;
}

// The cut with the fewest moves over every profile: `cut(p)` gives a Result
// of cut chains, `moves(chain)` counts a chain's moves; sets `profile` to the
// winner (the first on a tie). The first profile's error when none cuts.
template <class Cut, class Moves>
auto fewest_moves(std::optional<Profile>& profile, Cut cut, Moves moves) -> decltype(cut(Profile{})) {
    std::optional<Error> first_error;
    std::optional<decltype(cut(Profile{}))> best;
    std::size_t fewest = 0;
    for (Profile p : kAllProfiles) {
        auto r = cut(p);
        if (!r) {
            if (!first_error) first_error = r.error();
            continue;
        }
        std::size_t n = 0;
        for (const auto& c : *r) n += moves(c);
        if (!best || n < fewest) {
            profile = p;
            fewest = n;
            best = std::move(r);
        }
    }
    if (!best) return *first_error;
    return std::move(*best);
}

// Cuts every chain into arcs drawn by `method` and default-phase lines under
// `profile`, or under each profile when it is unset (the fewest moves win;
// it is then set).
Result<std::vector<ArcCutChain>> cut_arcs(const std::vector<Chain>& chains,
                                          std::optional<Profile>& profile, ArcMethod method,
                                          const ArcCutOptions& options,
                                          const std::string& source) {
    if (profile) {
        auto r = cut_chains_into_arcs(chains, *profile, method, options);
        if (!r) return make_error(r.error().code, source + ": " + r.error().message);
        return r;
    }
    return fewest_moves(profile, [&](Profile p) -> Result<std::vector<ArcCutChain>> {
        auto r = cut_chains_into_arcs(chains, p, method, options);
        if (!r) return make_error(r.error().code, source + ": " + r.error().message);
        return r;
    }, [](const ArcCutChain& ac) { return ac.moves.size(); });
}

}  // namespace

int cmd_segment(const std::vector<std::string>& args) {
    po::options_description desc(
        "Usage: stepzip segment [IN | -] --to gcode|hpgl|svg|json [OPTIONS]\n"
        "Unit-step chains -> vectors by reverse interpolation.\n"
        "Options");
    std::string input, format_arg, segmenter_arg = "greedy", profile_arg, to_arg, out_arg,
                                   step_arg, feed_arg, feed_factor_arg = "seed", tick_arg, arc_arg;
    std::size_t min_arc = ArcSearchOptions{}.min_length;
    desc.add_options()
        ("help,h", "show this help")
        ("to", po::value(&to_arg), "output: gcode, hpgl, svg or json (required)")
        ("format", po::value(&format_arg),
         "input chain format: freeman, points, steps, timed (default: detected)")
        ("segmenter", po::value(&segmenter_arg),
         "greedy (default), optimal, or patent (SU 1089551 approximation mode: end points "
         "only, its deviation reported)")
        ("profile", po::value(&profile_arg),
         "eval4, eval8, patent, grbl, marlin, or auto: the profile giving the fewest "
         "segments (default: auto; patent under --segmenter patent)")
        ("output,o", po::value(&out_arg), "output file (default: standard output)")
        ("stdout,c", "write to standard output")
        ("force,f", "overwrite an existing output")
        ("relative", "G-code: incremental coordinates (G91)")
        ("step-size", po::value(&step_arg), "G-code: write millimetres at this many mm per step")
        ("feed", po::value(&feed_arg),
         "G-code: F words from the feed-rate block at V steps per second (each segment's "
         "length over the time its steps take; steps/min, or mm/min with --step-size); "
         "'timed' with --format timed: each move's cruise speed read out of the log")
        ("tick-us", po::value(&tick_arg),
         "--format timed: the log's tick in microseconds; vectors then draw the path "
         "(time dropped) and JSON lists its moves with their speeds and each axis's "
         "rate and acceleration")
        ("feed-factor", po::value(&feed_factor_arg),
         "G-code with --feed: interval after a diagonal step, seed (x1.41, default) or exact "
         "(x sqrt 2)")
        ("arc-method", po::value(&arc_arg),
         "G-code: also recover circular arcs drawn by this interpolator (evaluation, "
         "accelerated, dda, prediction, recursion; as `interpolate --arc-method`), written "
         "as G2/G3 X Y I J; lines elsewhere")
        ("min-arc", po::value(&min_arc),
         "with --arc-method: shortest arc taken, in steps (default 8)")
        ("overlay", "SVG: the diagnostic picture (unit steps, segments coloured by shape, end "
                    "points) instead of plain paths")
        ("verbose,v", "name the profile chosen on stderr")
        ("quiet,q", "no notes on stderr");
    po::variables_map vm;
    if (auto exit_code = parse_command("segment", args, desc, "input", po::value(&input), 1, vm))
        return *exit_code;
    if (to_arg.empty()) return usage_error("segment: --to is required");
    const auto to = parse_vector_out(to_arg);
    if (!to) return usage_error("segment: unknown output '" + to_arg + "'");
    const auto kind = parse_segmenter(segmenter_arg);
    if (!kind) return usage_error("segment: unknown segmenter '" + segmenter_arg + "'");
    if (profile_arg.empty()) profile_arg = *kind == SegmenterKind::patent ? "patent" : "auto";
    std::optional<Profile> profile;
    if (profile_arg != "auto") {
        profile = parse_profile(profile_arg);
        if (!profile) return usage_error("segment: unknown profile '" + profile_arg + "'");
    }
    std::optional<InputFormat> format;
    if (!format_arg.empty()) {
        format = parse_format(format_arg);
        if (!format) return usage_error("segment: unknown input format '" + format_arg + "'");
    }
    GcodeWriteOptions gcode_options;
    gcode_options.relative = vm.count("relative") > 0;
    if (!step_arg.empty()) {
        auto s = parse_step_size(step_arg);
        if (!s) return usage_error("segment: " + s.error().message);
        gcode_options.step_size = *s;
    }
    std::optional<FeedOptions> feed;
    const bool timed = format == InputFormat::timed;
    double tick_us = 0;
    if (!tick_arg.empty()) {
        if (!timed) return usage_error("segment: --tick-us needs --format timed");
        char* end = nullptr;
        tick_us = std::strtod(tick_arg.c_str(), &end);
        if (end == tick_arg.c_str() || *end != '\0' || !(tick_us > 0) || !std::isfinite(tick_us))
            return usage_error("segment: --tick-us wants a positive number of microseconds, not '" +
                               tick_arg + "'");
    } else if (timed) {
        return usage_error("segment: --format timed needs --tick-us");
    }
    const bool timed_feed = feed_arg == "timed";
    if (timed_feed) {
        if (*to != VectorOut::gcode) return usage_error("segment: --feed needs --to gcode");
        if (!timed) return usage_error("segment: --feed timed needs --format timed");
    } else if (!feed_arg.empty()) {
        if (*to != VectorOut::gcode) return usage_error("segment: --feed needs --to gcode");
        char* end = nullptr;
        const double v = std::strtod(feed_arg.c_str(), &end);
        if (end == feed_arg.c_str() || *end != '\0' || !(v > 0) || !std::isfinite(v))
            return usage_error("segment: --feed wants a positive number of steps per second, "
                               "not '" + feed_arg + "'");
        feed.emplace();
        feed->steps_per_second = v;
        feed->step_size = gcode_options.step_size;
        if (feed_factor_arg == "exact")
            feed->factor = AxisFactor::exact;
        else if (feed_factor_arg != "seed")
            return usage_error("segment: unknown --feed-factor '" + feed_factor_arg + "'");
    }
    const bool quiet = vm.count("quiet") > 0;
    const bool verbose = vm.count("verbose") > 0;
    const bool overlay = vm.count("overlay") > 0;
    if (quiet && verbose) return usage_error("segment: -q and -v conflict");
    if (overlay && *to != VectorOut::svg) return usage_error("segment: --overlay needs --to svg");
    std::optional<ArcMethod> arc_method;
    if (!arc_arg.empty()) {
        arc_method = parse_arc_method(arc_arg);
        if (!arc_method) return usage_error("segment: unknown arc method '" + arc_arg + "'");
        if (*to != VectorOut::gcode)
            return usage_error("segment: --arc-method needs --to gcode (the other outputs "
                               "carry no exact arcs)");
        if (*kind == SegmenterKind::patent)
            return usage_error("segment: --arc-method does not go with --segmenter patent");
        if (feed) return usage_error("segment: --arc-method does not go with --feed");
        if (timed) return usage_error("segment: --arc-method does not go with --format timed");
        if (min_arc < 1) return usage_error("segment: --min-arc must be at least 1");
    } else if (vm.count("min-arc")) {
        return usage_error("segment: --min-arc needs --arc-method");
    }
    const std::string out_path = vm.count("stdout") ? std::string("-") : out_arg;
    const bool force = vm.count("force") > 0;

    // Read the chains.
    const std::string source = input_name(input);
    auto data = read_input(input);
    if (!data) return report(data.error());
    if (!format) {
        format = detect_format(std::string_view(*data).substr(0, 4096));
        if (!format)
            return report(make_error(Errc::syntax,
                                     source + ": not a chain file (freeman, points or steps; "
                                              "use --format)"));
    }
    auto chains = read_chains(*format, *data, source);
    if (!chains) return report(chains.error());
    // A timed log: its moves are read out; the rest works on its path.
    if (timed) {
        std::vector<TimedReading> readings;
        for (const Chain& c : *chains) readings.push_back(read_timed(c, tick_us * 1e-6));
        if (*to == VectorOut::json) return write_text(write_timed_json(readings, tick_us), source, out_path, force);
        if (readings.empty() || readings.front().path.path.axes != 2)
            return report(make_error(Errc::unsupported, source + ": vectors of a timed log need two axes"));
        const Drawing drawing = timed_drawing(readings, timed_feed, gcode_options.step_size);
        const std::string comment = "moves read out of a timed log (" + json_number(tick_us) +
                                    " us ticks): straight within " + json_number(kTimedMoveTolerance) +
                                    " steps of its path" +
                                    (timed_feed ? "; F: each move's cruise speed" : "");
        Result<std::string> text = std::string();
        switch (*to) {
            case VectorOut::gcode:
                gcode_options.comment = comment;
                text = write_gcode(drawing, gcode_options);
                break;
            case VectorOut::hpgl: text = write_hpgl(drawing, comment); break;
            case VectorOut::svg: text = write_svg_paths(drawing, comment); break;
            case VectorOut::json: break;
        }
        return write_text(text, source, out_path, force);
    }

    // Cut them; "auto" keeps the profile with the fewest segments.
    const bool vectors = *to != VectorOut::json;
    SegmentStats stats;
    std::vector<SegmentedChain> cut_chains;
    std::vector<ArcCutChain> arc_chains;
    if (arc_method) {
        ArcCutOptions arc_options;
        arc_options.search.min_length = min_arc;
        arc_options.lines = *kind;
        auto r = cut_arcs(*chains, profile, *arc_method, arc_options, source);
        if (!r) return report(r.error());
        arc_chains = std::move(*r);
        for (const ArcCutChain& ac : arc_chains) cut_chains.push_back({ac.chain, {}});
    } else if (profile) {
        auto r = cut(*chains, *profile, *kind, vectors, source, stats);
        if (!r) return report(r.error());
        cut_chains = std::move(*r);
    } else {
        std::vector<SegmentStats> per_profile(std::size(kAllProfiles));
        auto r = fewest_moves(profile, [&](Profile p) {
            return cut(*chains, p, *kind, vectors, source, per_profile[static_cast<std::size_t>(p)]);
        }, [](const SegmentedChain& sc) { return sc.segments.size(); });
        if (!r) return report(r.error());
        stats = per_profile[static_cast<std::size_t>(*profile)];
        cut_chains = std::move(*r);
    }
    const std::string pname(profile_name(*profile));
    if (verbose)
        note("profile " + pname + (profile_arg == "auto" ? " (auto: fewest segments)" : "") +
             ", segmenter " + std::string(segmenter_name(*kind)));

    CutInfo info;
    info.profile = *profile;
    info.segmenter = *kind;
    info.exact = *kind != SegmenterKind::patent;
    if (!info.exact) {
        info.stats = stats;
        if (!quiet)
            note("patent approximation mode: " + std::to_string(stats.patent_segments) +
                 " segment(s) read out, " + std::to_string(stats.patent_exact) +
                 " reproduce their steps exactly, largest deviation " +
                 std::to_string(stats.patent_max_deviation) + " step(s)");
    }

    Result<std::string> text = std::string();
    if (*to == VectorOut::json) {
        text = write_json(cut_chains, info);
    } else {
        auto drawing = arc_method ? arc_cut_to_drawing(arc_chains)
                       : feed     ? segments_to_drawing(cut_chains, *feed)
                                  : segments_to_drawing(cut_chains);
        if (!drawing)
            return report(make_error(drawing.error().code, source + ": " + drawing.error().message));

        // Pens named by "# pen N" comments of the chain file.
        if (*format != InputFormat::steps) {
            const std::vector<int> pens = chain_pens(*format, *data);
            std::size_t path = 0;
            for (std::size_t c = 0; c < cut_chains.size() && path < drawing->size(); ++c)
                if (!cut_chains[c].chain.steps.empty())
                    (*drawing)[path++].pen = c < pens.size() ? pens[c] : 1;
        }
        // The proof: the profile redraws the vectors into the input steps.
        std::vector<Chain> input;
        input.reserve(cut_chains.size());
        for (SegmentedChain& sc : cut_chains) input.push_back(sc.chain);
        const auto redraw = check_redraw(*drawing, input, *profile, arc_method);
        std::string comment = "profile " + pname + ": `stepzip interpolate --profile " + pname +
                              "` redraws these vectors into the input steps";
        if (arc_method) {
            const std::string aname(arc_method_name(*arc_method));
            comment = "profile " + pname + ", arc method " + aname +
                      ": `stepzip interpolate --profile " + pname + " --arc-method " + aname +
                      "` redraws these vectors into the input steps";
        }
        if (!info.exact) {
            comment = "profile " + pname + ", patent approximation mode: end points read out by "
                      "SU 1089551 Fig. 5";
            comment += redraw ? "; they redraw the input steps exactly"
                              : "; they do not redraw the input steps exactly";
            if (!redraw && !quiet)
                note("patent approximation mode: the vectors do not redraw the input exactly (" +
                     redraw.error().message + ")");
        } else if (!redraw) {
            return report(make_error(Errc::mismatch, source + ": internal error, nothing written: " +
                                                         redraw.error().message));
        }
        switch (*to) {
            case VectorOut::gcode:
                gcode_options.comment = comment;
                text = write_gcode(*drawing, gcode_options);
                break;
            case VectorOut::hpgl: text = write_hpgl(*drawing, comment); break;
            case VectorOut::svg:
                text = overlay ? write_svg(cut_chains, info) : write_svg_paths(*drawing, comment);
                break;
            case VectorOut::json: break;
        }
    }
    return write_text(text, source, out_path, force);
}

}  // namespace stepzip::cli
