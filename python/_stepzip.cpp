// The extension module `stepzip._stepzip`: the library on buffers and numpy
// arrays. python/stepzip/__init__.py is the public interface: it checks the
// argument types (so that no error message repeats the caller's data) and
// converts (n, axes) move arrays. Every call that can take long releases the
// GIL. Errors raise stepzip.Error (a ValueError) whose `code` is the Errc
// value and whose text is the library's one-line message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <vector>

#include "stepzip.h"
#include "stepzip/container.hpp"
#include "stepzip/document.hpp"
#include "stepzip/profile.hpp"
#include "stepzip/segmenter.hpp"
#include "stepzip/streaming.hpp"
#include "stepzip/timed.hpp"
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

// A read-only view of any object with the buffer protocol (bytes,
// bytearray, memoryview, numpy arrays), held for the view's lifetime so the
// memory cannot move while the GIL is released. A non-contiguous buffer is
// a TypeError that names the type only, never the data.
class ByteView {
public:
    ByteView(const py::object& o, const char* what) {
        if (!PyObject_CheckBuffer(o.ptr()))
            throw py::type_error(std::string(what) +
                                 " must be a bytes-like object (bytes, bytearray, memoryview, "
                                 "numpy array), not " + Py_TYPE(o.ptr())->tp_name);
        if (PyObject_GetBuffer(o.ptr(), &view_, PyBUF_SIMPLE) != 0) {
            PyErr_Clear();
            throw py::type_error(std::string(what) + " must be a contiguous buffer (" +
                                 Py_TYPE(o.ptr())->tp_name + " given)");
        }
    }
    ~ByteView() { PyBuffer_Release(&view_); }
    ByteView(const ByteView&) = delete;
    ByteView& operator=(const ByteView&) = delete;
    std::string_view view() const noexcept {
        return {static_cast<const char*>(view_.buf), static_cast<std::size_t>(view_.len)};
    }

private:
    Py_buffer view_{};
};

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

// Moves (an (n, axes) int8 array of -1/0/+1) <-> packed STEP/DIR words.
StepArray moves_to_steps(const py::array_t<std::int8_t, py::array::c_style | py::array::forcecast>& moves) {
    if (moves.ndim() != 2 || moves.shape(1) < 1 || moves.shape(1) > kMaxAxes)
        raise(Errc::invalid_argument, "moves must have shape (n, axes) with 1 <= axes <= " +
                                          std::to_string(kMaxAxes));
    const auto n = moves.shape(0);
    const int axes = static_cast<int>(moves.shape(1));
    StepArray out(n);
    const std::int8_t* m = moves.data();
    Step* o = out.mutable_data();
    py::ssize_t bad_row = -1;
    {
        py::gil_scoped_release release;
        for (py::ssize_t i = 0; i < n && bad_row < 0; ++i) {
            Step s = 0;
            for (int a = 0; a < axes; ++a) {
                const int v = m[i * axes + a];
                if (v < -1 || v > 1) {
                    bad_row = i;
                    break;
                }
                if (v != 0) s = static_cast<Step>(s | (1u << (2 * a)) | (v < 0 ? 2u << (2 * a) : 0u));
            }
            if (s == 0) bad_row = i;
            o[i] = s;
        }
    }
    if (bad_row >= 0)
        raise(Errc::invalid_argument, "moves row " + std::to_string(bad_row) +
                                          ": a step moves at least one axis, each by -1, 0 or +1");
    return out;
}

py::array_t<std::int8_t> steps_to_moves(const StepArray& steps, int axes) {
    const auto s = step_span(steps);
    if (axes < 1 || axes > kMaxAxes)
        raise(Errc::invalid_argument, "axes must be 1.." + std::to_string(kMaxAxes));
    py::array_t<std::int8_t> out({static_cast<py::ssize_t>(s.size()), static_cast<py::ssize_t>(axes)});
    std::int8_t* o = out.mutable_data();
    std::size_t bad = s.size();
    {
        py::gil_scoped_release release;
        const unsigned beyond = axes >= 8 ? 0u : ~((1u << (2 * axes)) - 1u) & 0xFFFFu;
        for (std::size_t i = 0; i < s.size(); ++i) {
            const unsigned w = s[i];
            if (w == 0 || (w & beyond) != 0) {
                bad = i;
                break;
            }
            for (int a = 0; a < axes; ++a) {
                const bool moved = (w >> (2 * a)) & 1u, negative = (w >> (2 * a + 1)) & 1u;
                if (negative && !moved) bad = i;
                o[i * static_cast<std::size_t>(axes) + static_cast<std::size_t>(a)] =
                    static_cast<std::int8_t>(moved ? (negative ? -1 : 1) : 0);
            }
            if (bad != s.size()) break;
        }
    }
    if (bad != s.size())
        raise(Errc::invalid_argument, "step " + std::to_string(bad) + " is not a step on " +
                                          std::to_string(axes) + " axes");
    return out;
}

// A stream handle of the C API (stepzip.h) driven from Python: bytes in,
// the bytes that are ready out, the GIL released while the coder works.
template <class Handle, auto Call, auto ErrorText, auto Reset, auto Free>
class PyStream {
public:
    explicit PyStream(Handle* h) : h_(h) {
        if (!h_) throw std::bad_alloc();
    }
    ~PyStream() { Free(h_); }
    PyStream(const PyStream&) = delete;
    PyStream& operator=(const PyStream&) = delete;

    // Feeds `data`; returns the output it made ready. `end`: no more input.
    py::bytes feed(std::string_view data, bool end) {
        std::string out;
        enum stepzip_result r = STEPZIP_OK;
        {
            py::gil_scoped_release release;
            char buf[1 << 16];
            stepzip_in_buffer in{data.data(), data.size(), 0};
            size_t remaining = 1;
            for (;;) {
                stepzip_out_buffer o{buf, sizeof buf, 0};
                r = Call(h_, &o, &in, end ? STEPZIP_END : STEPZIP_CONTINUE, &remaining);
                out.append(buf, o.pos);
                if (r != STEPZIP_OK) break;
                if (end ? remaining == 0 : (in.pos == in.size && o.pos < sizeof buf)) break;
            }
        }
        if (r != STEPZIP_OK) {
            const std::string message = ErrorText(h_);
            Reset(h_);
            raise(static_cast<Errc>(r == STEPZIP_NO_MEMORY ? static_cast<int>(Errc::io) : static_cast<int>(r)),
                  message);
        }
        return py::bytes(out);
    }
    void reset() { Reset(h_); }

private:
    Handle* h_;
};

using PyCStream = PyStream<stepzip_cstream, stepzip_compress_stream, stepzip_cstream_error,
                           stepzip_cstream_reset, stepzip_free_cstream>;
using PyDStream = PyStream<stepzip_dstream, stepzip_decompress_stream, stepzip_dstream_error,
                           stepzip_dstream_reset, stepzip_free_dstream>;

CompressOptions compress_options(std::optional<std::string> profile,
                                 std::optional<std::string> segmenter, int level,
                                 std::optional<std::string> format, std::string source,
                                 unsigned threads) {
    CompressOptions opt;
    if (level < 1 || level > 19) raise(Errc::invalid_argument, "level must be 1..19");
    opt.level = level;
    opt.threads = threads;
    opt.source = std::move(source);
    if (profile && *profile != "auto") opt.profile = to_profile(*profile);
    if (segmenter) opt.segmenter = to_segmenter(*segmenter);
    if (format) {
        auto f = parse_format(*format);
        if (!f) raise(Errc::invalid_argument, "unknown chain format '" + *format + "'");
        opt.format = *f;
    }
    return opt;
}

// The C API's compressor settings for the same options.
stepzip_cstream* make_cstream(const CompressOptions& opt) {
    const auto profile = opt.profile ? static_cast<enum stepzip_profile>(static_cast<int>(*opt.profile))
                                     : STEPZIP_PROFILE_AUTO;
    const auto kind = opt.segmenter
                          ? static_cast<enum stepzip_segmenter_kind>(static_cast<int>(*opt.segmenter))
                          : STEPZIP_SEGMENTER_DEFAULT;
    stepzip_compressor* c = stepzip_alloc_compressor(opt.level, profile, kind);
    if (!c) throw std::bad_alloc();
    stepzip_compressor_set_source(c, opt.source.c_str());
    const auto format = opt.format ? static_cast<enum stepzip_format>(static_cast<int>(*opt.format))
                                   : STEPZIP_FORMAT_AUTO;
    stepzip_cstream* cs = stepzip_alloc_cstream(c, format);
    stepzip_free_compressor(c);
    return cs;
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

PYBIND11_MODULE(_stepzip, m) {
    m.doc() = "Lossless compression of unit-step chains by reverse interpolation (extension; "
              "use the stepzip package).";
    m.attr("__version__") = version_string();
    m.attr("FORMAT_VERSION") = kFormatVersion;
    m.attr("MAX_AXES") = kMaxAxes;
    m.attr("TIMED_MOVE_TOLERANCE") = kTimedMoveTolerance;
    py::list profiles;
    for (Profile p : kAllProfiles) profiles.append(std::string(profile_name(p)));
    m.attr("PROFILES") = py::tuple(profiles);
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
        [](const py::object& data, std::optional<std::string> profile,
           std::optional<std::string> segmenter, int level, std::optional<std::string> format,
           std::string source, unsigned threads) {
            const CompressOptions opt =
                compress_options(profile, segmenter, level, format, std::move(source), threads);
            const ByteView in(data, "data");
            std::optional<Result<std::string>> r;
            {
                py::gil_scoped_release release;
                r = stepzip::compress(in.view(), opt);
            }
            return py::bytes(take(std::move(*r)));
        },
        py::arg("data"), py::arg("profile"), py::arg("segmenter"), py::arg("level"),
        py::arg("format"), py::arg("source"), py::arg("threads"));

    m.def(
        "decompress",
        [](const py::object& frame) {
            const ByteView in(frame, "frame");
            std::optional<Result<std::string>> r;
            {
                py::gil_scoped_release release;
                r = stepzip::decompress(in.view());
            }
            return py::bytes(take(std::move(*r)));
        },
        py::arg("frame"));

    m.def(
        "segment",
        [](const StepArray& steps, const std::string& profile, int axes,
           const std::string& segmenter) {
            const SegmenterKind kind = to_segmenter(segmenter);
            const auto span = step_span(steps);
            std::optional<Profile> chosen;
            std::vector<Segment> segs;
            std::optional<Error> first_error;
            {
                py::gil_scoped_release release;
                if (profile != "auto") {
                    if (auto p = parse_profile(profile)) {
                        chosen = *p;
                        if (auto r = segment_steps(span, axes, *p, kind, segs); !r) first_error = r.error();
                    } else {
                        first_error = Error{Errc::invalid_argument, "unknown profile '" + profile + "'"};
                    }
                } else {
                    // As `stepzip segment --profile auto`: the fewest segments,
                    // the first profile on a tie.
                    std::vector<Segment> trial;
                    for (Profile p : kAllProfiles) {
                        trial.clear();
                        auto r = segment_steps(span, axes, p, kind, trial);
                        if (!r) {
                            if (!first_error) first_error = r.error();
                            continue;
                        }
                        if (!chosen || trial.size() < segs.size()) {
                            chosen = p;
                            segs.swap(trial);
                        }
                    }
                    if (chosen) first_error.reset();
                }
            }
            if (first_error) raise(*first_error);
            py::tuple arrays = to_arrays(segs, *chosen, axes);
            return py::make_tuple(arrays[0], arrays[1], std::string(profile_name(*chosen)));
        },
        py::arg("steps"), py::arg("profile"), py::arg("axes"), py::arg("segmenter"));

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
            std::optional<Error> error;
            {
                py::gil_scoped_release release;
                for (py::ssize_t i = 0; i < deltas.shape(0) && !error; ++i) {
                    Segment s;
                    for (int a = 0; a < axes; ++a) s.delta[static_cast<std::size_t>(a)] = d(i, a);
                    for (int j = 0; j < nph; ++j) s.phase[static_cast<std::size_t>(j)] = f(i, j);
                    if (auto r = check_segment(p, s, axes); !r)
                        error = Error{r.error().code,
                                      "segment " + std::to_string(i + 1) + ": " + r.error().message};
                    else
                        expand_segment(p, s, axes, out);
                }
            }
            if (error) raise(*error);
            return to_array(out);
        },
        py::arg("deltas"), py::arg("phases"), py::arg("profile"), py::arg("axes"));

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
            DrawingInterpolation how;
            how.profile = to_profile(profile);
            std::optional<Result<std::vector<Chain>>> chains;
            {
                py::gil_scoped_release release;
                auto drawing = read_vectors(*f, text, ro);
                chains = drawing ? interpolate_drawing(*drawing, how)
                                 : Result<std::vector<Chain>>(drawing.error());
            }
            py::list out;
            for (const Chain& c : take(std::move(*chains)))
                out.append(py::make_tuple(py::make_tuple(c.start[0], c.start[1]), to_array(c.steps)));
            return out;
        },
        py::arg("text"), py::arg("profile"), py::arg("format"), py::arg("step_size"));

    m.def(
        "timed_moves",
        [](const py::object& log, double tick_us, double tolerance) {
            // (the wrapper checked both numbers)
            const ByteView in(log, "log");
            std::optional<Result<std::vector<Chain>>> chains;
            std::vector<TimedReading> readings;
            {
                py::gil_scoped_release release;
                chains = read_chains(InputFormat::timed, in.view(), "log");
                if (*chains)
                    for (const Chain& c : **chains) readings.push_back(read_timed(c, tick_us * 1e-6, tolerance));
            }
            if (!*chains) raise(chains->error());
            // As `stepzip segment --format timed --to json`: per chain its
            // path's start, its step count, its axes' motion and its moves.
            py::list out;
            for (const TimedReading& r : readings) {
                const Chain& path = r.path.path;
                const auto axes = static_cast<std::size_t>(path.axes);
                py::list ms;
                for (const TimedMove& m : r.moves) {
                    py::tuple delta(axes);
                    for (std::size_t i = 0; i < axes; ++i) delta[i] = m.delta[i];
                    ms.append(py::make_tuple(delta, py::make_tuple(m.first_tick, m.last_tick), m.length,
                                             m.speeds.entry, m.speeds.cruise, m.speeds.exit,
                                             m.speeds.acceleration, m.speeds.ramp_steps));
                }
                py::tuple start(axes);
                for (std::size_t i = 0; i < axes; ++i) start[i] = path.start[i];
                py::list per_axis;
                for (const AxisMotion& a : r.axes)
                    per_axis.append(py::make_tuple(a.steps, a.max_rate, a.acceleration, a.windows));
                out.append(py::make_tuple(start, path.steps.size(), per_axis, ms));
            }
            return out;
        },
        py::arg("log"), py::arg("tick_us"), py::arg("tolerance"));

    m.def(
        "freeman_to_steps",
        [](const std::string& codes) { return to_array(take(from_freeman(0, 0, codes)).steps); },
        py::arg("codes"));
    m.def(
        "steps_to_freeman",
        [](const StepArray& steps) {
            Chain c;
            const auto s = step_span(steps);
            c.steps.assign(s.begin(), s.end());
            return take(to_freeman(c));
        },
        py::arg("steps"));
    m.def("moves_to_steps", &moves_to_steps, py::arg("moves"));
    m.def("steps_to_moves", &steps_to_moves, py::arg("steps"), py::arg("axes"));

    py::class_<PyCStream>(m, "CStream")
        .def(py::init([](std::optional<std::string> profile, std::optional<std::string> segmenter,
                         int level, std::optional<std::string> format, std::string source) {
                 return new PyCStream(make_cstream(
                     compress_options(profile, segmenter, level, format, std::move(source), 1)));
             }),
             py::arg("profile"), py::arg("segmenter"), py::arg("level"), py::arg("format"),
             py::arg("source"))
        .def("feed",
             [](PyCStream& s, const py::object& data, bool end) {
                 const ByteView in(data, "data");
                 return s.feed(in.view(), end);
             },
             py::arg("data"), py::arg("end"))
        .def("reset", &PyCStream::reset);
    py::class_<PyDStream>(m, "DStream")
        .def(py::init([] { return new PyDStream(stepzip_alloc_dstream()); }))
        .def("feed",
             [](PyDStream& s, const py::object& data, bool end) {
                 const ByteView in(data, "data");
                 return s.feed(in.view(), end);
             },
             py::arg("data"), py::arg("end"))
        .def("reset", &PyDStream::reset);

    py::class_<PyStreaming>(m, "StreamingSegmenter")
        .def(py::init<const std::string&, int, std::size_t>(), py::arg("profile"),
             py::arg("axes"), py::arg("max_held"))
        .def("push", &PyStreaming::push, py::arg("steps"))
        .def("push_step", &PyStreaming::push_step, py::arg("step"))
        .def("finish", &PyStreaming::finish)
        .def_property_readonly("held", [](const PyStreaming& s) { return s.get().held(); })
        .def_property_readonly("max_held", [](const PyStreaming& s) { return s.get().max_held(); })
        .def_property_readonly("pushed", [](const PyStreaming& s) { return s.get().pushed(); })
        .def_property_readonly("forced_cuts",
                               [](const PyStreaming& s) { return s.get().forced_cuts(); });
    m.attr("DEFAULT_MAX_HELD") = kStreamingDefaultHold;
}
