// The Python module `stepzip`: the library on bytes and numpy arrays.
// Errors raise stepzip.Error (a ValueError) whose `code` is the Errc value
// and whose text is the library's one-line message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <vector>

#include "stepzip/container.hpp"
#include "stepzip/profile.hpp"
#include "stepzip/segmenter.hpp"
#include "stepzip/streaming.hpp"
#include "stepzip/vectors.hpp"
#include "stepzip/version.hpp"

namespace py = pybind11;
using namespace stepzip;

namespace {

struct LibraryError {
    Errc code;
    std::string message;
};

[[noreturn]] void raise(const Error& e) { throw LibraryError{e.code, e.message}; }
[[noreturn]] void raise(Errc code, std::string message) { throw LibraryError{code, std::move(message)}; }

template <class T>
T take(Result<T> r) {
    if (!r) raise(r.error());
    return std::move(*r);
}

void take(Result<void> r) {
    if (!r) raise(r.error());
}

Profile to_profile(const std::string& name) {
    auto p = parse_profile(name);
    if (!p) raise(Errc::invalid_argument, "unknown profile '" + name + "'");
    return *p;
}

SegmenterKind to_segmenter(const std::string& name) {
    auto k = parse_segmenter(name);
    if (!k) raise(Errc::invalid_argument, "unknown segmenter '" + name + "'");
    return *k;
}

std::string_view bytes_view(const py::bytes& b) {
    char* data = nullptr;
    Py_ssize_t size = 0;
    PyBytes_AsStringAndSize(b.ptr(), &data, &size);
    return {data, static_cast<std::size_t>(size)};
}

using StepArray = py::array_t<std::uint16_t, py::array::c_style | py::array::forcecast>;
using IntArray = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;

std::span<const Step> step_span(const StepArray& a) {
    if (a.ndim() != 1) raise(Errc::invalid_argument, "steps must be a one-dimensional array");
    return {a.data(), static_cast<std::size_t>(a.shape(0))};
}

StepArray to_array(const std::vector<Step>& steps) {
    StepArray a(static_cast<py::ssize_t>(steps.size()));
    std::copy(steps.begin(), steps.end(), a.mutable_data());
    return a;
}

// Segments as two arrays: totals (n, axes) and phases (n, phase_count).
py::tuple to_arrays(const std::vector<Segment>& segs, Profile p, int axes) {
    const int nph = phase_count(p, axes);
    IntArray deltas({static_cast<py::ssize_t>(segs.size()), static_cast<py::ssize_t>(axes)});
    IntArray phases({static_cast<py::ssize_t>(segs.size()), static_cast<py::ssize_t>(nph)});
    auto d = deltas.mutable_unchecked<2>();
    auto f = phases.mutable_unchecked<2>();
    for (std::size_t i = 0; i < segs.size(); ++i) {
        const auto r = static_cast<py::ssize_t>(i);
        for (int a = 0; a < axes; ++a) d(r, a) = segs[i].delta[static_cast<std::size_t>(a)];
        for (int j = 0; j < nph; ++j) f(r, j) = segs[i].phase[static_cast<std::size_t>(j)];
    }
    return py::make_tuple(deltas, phases);
}

class PyStreaming {
public:
    PyStreaming(const std::string& profile, int axes, std::size_t max_held)
        : seg_(to_profile(profile), axes, max_held) {
        if (!seg_.valid())
            raise(Errc::invalid_argument, "profile " + profile + " with " + std::to_string(axes) +
                                              " axes and max_held " + std::to_string(max_held) +
                                              " is not usable");
    }
    py::tuple push(const StepArray& steps) {
        std::vector<Segment> out;
        take(seg_.push(step_span(steps), out));
        return to_arrays(out, seg_.profile(), seg_.axes());
    }
    py::tuple push_step(int step) {
        if (step < 0 || step > 0xFFFF) raise(Errc::invalid_argument, "a step is 16 bits");
        std::vector<Segment> out;
        take(seg_.push(static_cast<Step>(step), out));
        return to_arrays(out, seg_.profile(), seg_.axes());
    }
    py::tuple finish() {
        std::vector<Segment> out;
        seg_.finish(out);
        return to_arrays(out, seg_.profile(), seg_.axes());
    }
    const StreamingSegmenter& get() const { return seg_; }

private:
    StreamingSegmenter seg_;
};

}  // namespace

PYBIND11_MODULE(stepzip, m) {
    m.doc() = "Lossless compression of unit-step chains by reverse interpolation.";
    m.attr("__version__") = version_string();
    m.attr("FORMAT_VERSION") = kFormatVersion;
    static py::exception<LibraryError> error_type(m, "Error", PyExc_ValueError);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const LibraryError& e) {
            py::object type = py::reinterpret_borrow<py::object>(error_type.ptr());
            py::object err = type(std::string(errc_name(e.code)) + ": " + e.message);
            err.attr("code") = static_cast<int>(e.code);
            PyErr_SetObject(error_type.ptr(), err.ptr());
        }
    });

    m.def(
        "compress",
        [](const py::bytes& data, std::optional<std::string> profile,
           std::optional<std::string> segmenter, int level, std::optional<std::string> format,
           std::string source) {
            CompressOptions opt;
            opt.level = level;
            opt.source = std::move(source);
            if (profile && *profile != "auto") opt.profile = to_profile(*profile);
            if (segmenter) opt.segmenter = to_segmenter(*segmenter);
            if (format) {
                auto f = parse_format(*format);
                if (!f) raise(Errc::invalid_argument, "unknown chain format '" + *format + "'");
                opt.format = *f;
            }
            std::string frame;
            {
                const std::string_view in = bytes_view(data);
                py::gil_scoped_release release;
                auto r = stepzip::compress(in, opt);
                if (!r) {
                    py::gil_scoped_acquire acquire;
                    raise(r.error());
                }
                frame = std::move(*r);
            }
            return py::bytes(frame);
        },
        py::arg("data"), py::kw_only(), py::arg("profile") = py::none(),
        py::arg("segmenter") = py::none(), py::arg("level") = 3, py::arg("format") = py::none(),
        py::arg("source") = "<input>",
        "Compresses a chain file (freeman, points or steps bytes) into a .stz frame.\n"
        "The round trip is proved before returning; the bytes may change between versions.");

    m.def(
        "decompress",
        [](const py::bytes& frame) {
            std::string out;
            {
                const std::string_view in = bytes_view(frame);
                py::gil_scoped_release release;
                auto r = stepzip::decompress(in);
                if (!r) {
                    py::gil_scoped_acquire acquire;
                    raise(r.error());
                }
                out = std::move(*r);
            }
            return py::bytes(out);
        },
        py::arg("frame"), "Decodes a .stz frame to the original bytes (checksum verified).");

    m.def(
        "segment",
        [](const StepArray& steps, const std::string& profile, int axes,
           const std::string& segmenter) {
            const Profile p = to_profile(profile);
            std::vector<Segment> segs;
            take(segment_steps(step_span(steps), axes, p, to_segmenter(segmenter), segs));
            return to_arrays(segs, p, axes);
        },
        py::arg("steps"), py::arg("profile") = "eval8", py::arg("axes") = 2,
        py::arg("segmenter") = "greedy",
        "Reverse interpolation: packed steps (uint16) -> (deltas, phases), int64 arrays of\n"
        "shape (n, axes) and (n, phase_count).");

    m.def(
        "expand",
        [](const IntArray& deltas, const IntArray& phases, const std::string& profile, int axes) {
            const Profile p = to_profile(profile);
            if (deltas.ndim() != 2 || deltas.shape(1) != axes)
                raise(Errc::invalid_argument, "deltas must have shape (n, axes)");
            const int nph = phase_count(p, axes);
            if (phases.ndim() != 2 || phases.shape(0) != deltas.shape(0) || phases.shape(1) != nph)
                raise(Errc::invalid_argument, "phases must have shape (n, " + std::to_string(nph) + ")");
            auto d = deltas.unchecked<2>();
            auto f = phases.unchecked<2>();
            std::vector<Step> out;
            for (py::ssize_t i = 0; i < deltas.shape(0); ++i) {
                Segment s;
                for (int a = 0; a < axes; ++a) s.delta[static_cast<std::size_t>(a)] = d(i, a);
                for (int j = 0; j < nph; ++j) s.phase[static_cast<std::size_t>(j)] = f(i, j);
                if (auto r = check_segment(p, s, axes); !r)
                    raise(r.error().code, "segment " + std::to_string(i + 1) + ": " + r.error().message);
                expand_segment(p, s, axes, out);
            }
            return to_array(out);
        },
        py::arg("deltas"), py::arg("phases"), py::arg("profile") = "eval8", py::arg("axes") = 2,
        "Forward interpolation of segments: (deltas, phases) -> packed steps (uint16).");

    m.def(
        "interpolate",
        [](const std::string& text, const std::string& profile, std::optional<std::string> fmt,
           std::optional<std::string> step_size) {
            VectorReadOptions ro;
            if (step_size) ro.step_size = take(parse_step_size(*step_size));
            std::optional<VectorFormat> f;
            if (fmt) {
                f = parse_vector_format(*fmt);
                if (!f) raise(Errc::invalid_argument, "unknown vector format '" + *fmt + "'");
            } else {
                f = detect_vector_format(std::string_view(text).substr(0, 4096));
                if (!f) raise(Errc::syntax, "neither G-code nor HP-GL");
            }
            const Drawing drawing = take(read_vectors(*f, text, ro));
            DrawingInterpolation how;
            how.profile = to_profile(profile);
            py::list chains;
            for (const Chain& c : take(interpolate_drawing(drawing, how)))
                chains.append(py::make_tuple(py::make_tuple(c.start[0], c.start[1]), to_array(c.steps)));
            return chains;
        },
        py::arg("text"), py::arg("profile") = "eval8", py::arg("format") = py::none(),
        py::arg("step_size") = py::none(),
        "Vectors (G-code or HP-GL text) -> [((x0, y0), steps)], one chain per pen-down path.");

    m.def(
        "freeman_to_steps",
        [](const std::string& codes) {
            return to_array(take(from_freeman(0, 0, codes)).steps);
        },
        py::arg("codes"), "Freeman-8 digits -> packed two-axis steps.");
    m.def(
        "steps_to_freeman",
        [](const StepArray& steps) {
            Chain c;
            const auto s = step_span(steps);
            c.steps.assign(s.begin(), s.end());
            return take(to_freeman(c));
        },
        py::arg("steps"), "Packed two-axis steps -> Freeman-8 digits.");

    py::class_<PyStreaming>(m, "StreamingSegmenter",
                            "Online greedy reverse interpolation: push steps, receive each "
                            "segment when it is final; at most max_held steps wait.")
        .def(py::init<const std::string&, int, std::size_t>(), py::arg("profile") = "eval8",
             py::arg("axes") = 2, py::arg("max_held") = kStreamingDefaultHold)
        .def("push", &PyStreaming::push, py::arg("steps"),
             "Pushes an array of steps; returns the (deltas, phases) that became final.")
        .def("push_step", &PyStreaming::push_step, py::arg("step"), "Pushes one step.")
        .def("finish", &PyStreaming::finish,
             "Ends the chain: returns the remaining segments and resets.")
        .def_property_readonly("held", [](const PyStreaming& s) { return s.get().held(); })
        .def_property_readonly("max_held", [](const PyStreaming& s) { return s.get().max_held(); })
        .def_property_readonly("pushed", [](const PyStreaming& s) { return s.get().pushed(); })
        .def_property_readonly("forced_cuts",
                               [](const PyStreaming& s) { return s.get().forced_cuts(); });
}
