// module.cpp: gonio._core, the compiled half of gonio's Python API (python/gonio/api.py is the half users call):
// stacks parsed, runs made and kept in memory (in_process.h), their bytes and nodes handed to Python. The GIL is
// released while the device works; the progress callback and Ctrl-C are looked at after every dispatch
// (KeyboardInterrupt stops the run). A refusal raises: gonio.StackError (a ValueError: file:line: reason) for a
// stack, ValueError for options, RuntimeError for a failure while running; nothing exits the interpreter.
#include "in_process.h"
#include "json.h"
#include "options.h"
#include "refusal.h"
#include "stack.h"

#include <cstring>

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;
using namespace gonio;

namespace {

// The Python callable's progress, and Ctrl-C, between dispatches. The function is copied and called without the GIL,
// so it holds the callable as a bare pointer (no reference count to touch): the caller's argument keeps it alive for
// the call, and it is used only with the GIL taken.
RunProgress python_progress(const py::object& callback) {
    PyObject* const f = callback.ptr();
    return [f](uint64_t done, uint64_t total) {
        py::gil_scoped_acquire gil;
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
        if (f != Py_None) {
            const py::handle callable(f);
            callable(done, total);
        }
    };
}

// run(stack, args, progress) on the stack's text, parsed, with the GIL released while it runs: every in-process run.
template <class Run>
auto run_without_gil(const std::string& text, const std::string& path, const std::vector<std::string>& args,
                     const py::object& progress, const Run& run) {
    const Stack s = parse_stack_string(text, path);
    const RunProgress p = python_progress(progress);
    py::gil_scoped_release nogil;
    return run(s, args, p);
}

InProcessRun run_stack(const std::string& text, const std::string& path, const std::vector<std::string>& args,
                       bool compare, const py::object& progress) {
    return run_without_gil(text, path, args, progress, [compare](const Stack& s, const auto& a, const RunProgress& p) {
        return run_in_process(s, a, compare, p);
    });
}

// The run's nodes as arrays: angle, side, bin (uint32), l and v (N x 3), weight (N).
py::dict nodes_arrays(const InProcessRun& run, int k) {
    const std::vector<BinNode> nodes = run_nodes(run, k);
    const py::ssize_t n = py::ssize_t(nodes.size());
    py::array_t<uint32_t> angle(n), side(n), bin(n);
    py::array_t<double> l({n, py::ssize_t(3)}), v({n, py::ssize_t(3)}), weight(n);
    auto a = angle.mutable_unchecked<1>(), s = side.mutable_unchecked<1>(), b = bin.mutable_unchecked<1>();
    auto lm = l.mutable_unchecked<2>(), vm = v.mutable_unchecked<2>();
    auto w = weight.mutable_unchecked<1>();
    for (py::ssize_t i = 0; i < n; ++i) {
        const BinNode& x = nodes[size_t(i)];
        a(i) = x.angle, s(i) = x.side, b(i) = x.bin, w(i) = x.weight;
        for (int c = 0; c < 3; ++c) lm(i, c) = x.l[c], vm(i, c) = x.v[c];
    }
    py::dict d;
    d["angle"] = angle, d["side"] = side, d["bin"] = bin, d["l"] = l, d["v"] = v, d["weight"] = weight;
    return d;
}

ModelSlices values_model(const InProcessRun& run, const std::string& id, int k,
                         const py::array_t<double, py::array::c_style | py::array::forcecast>& values) {
    if (values.ndim() != 2 || values.shape(1) != 3)
        throw std::invalid_argument(id + ": the values must have shape (nodes, 3), got " +
                                    std::to_string(values.ndim()) + " dimensions");
    std::vector<glm::dvec3> v(size_t(values.shape(0)));
    auto x = values.unchecked<2>();
    for (py::ssize_t i = 0; i < values.shape(0); ++i) v[size_t(i)] = {x(i, 0), x(i, 1), x(i, 2)};
    return node_model(run, id, k, v);
}

InProcessRun models_on(const InProcessRun& run, const std::vector<std::string>& args, std::vector<ModelSlices> extra,
                       const std::vector<std::string>& glsl) {
    py::gil_scoped_release nogil;
    return with_models(run, args, std::move(extra), glsl);
}

// A spectral run as gonio.SpectralRun holds it: summary.json's bytes and the EXR's parts, {name: {channel:
// (n_theta, n_phi) float32, "header": {attribute: value}}}, the values the file would hold.
py::tuple spectral_run(const std::string& text, const std::string& path, const std::vector<std::string>& args,
                       const py::object& progress) {
    const SpectralResult r = run_without_gil(text, path, args, progress, spectral_in_process);
    const SimResult& first = r.groups.front();
    py::dict parts;
    for (const ExrPart& p : spectral_exr_parts(r)) {
        py::dict part, header;
        for (const auto& [name, plane] : p.planes) {
            py::array_t<float> a({py::ssize_t(first.n_theta), py::ssize_t(first.n_phi)});
            std::copy(plane.begin(), plane.end(), a.mutable_data());
            part[py::str(name)] = a;
        }
        for (const auto& [key, value] : p.attributes)
            std::visit([&](const auto& v) { header[py::str(key)] = v; }, value);
        part["header"] = header;
        parts[py::str(p.name)] = part;
    }
    return py::make_tuple(json_text(spectral_summary_json(r)), parts);
}

// A render in memory: {name: (size, size, 4) float32 RGBA, row 0 at the top}, {model: why not rendered}, the
// environment.
py::tuple render_run(const std::string& text, const std::string& path, const std::vector<std::string>& args,
                     const py::object& progress) {
    const InProcessRender r = run_without_gil(text, path, args, progress, render_in_process);
    py::dict images, not_rendered;
    for (const auto& [name, im] : r.images) {
        const py::ssize_t n = py::ssize_t(im.size);
        py::array_t<float> a({n, n, py::ssize_t(4)});
        std::memcpy(a.mutable_data(), im.rgba.data(), im.rgba.size() * sizeof(glm::vec4));
        images[py::str(name)] = a;
    }
    for (const auto& [id, why] : r.not_rendered) not_rendered[py::str(id)] = why;
    return py::make_tuple(images, not_rendered, r.environment);
}

}   // namespace

PYBIND11_MODULE(_core, m) {
    m.doc() = "gonio's pipeline in this process (python/gonio/api.py is its interface: import gonio)";
    static py::exception<StackError> stack_error(m, "StackError", PyExc_ValueError);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const StackError& e) {
            py::object err = py::reinterpret_borrow<py::object>(stack_error.ptr())(e.what());
            err.attr("file") = e.file;
            err.attr("line") = e.line;
            PyErr_SetObject(stack_error.ptr(), err.ptr());
        } catch (const UsageError& e) { PyErr_SetString(PyExc_ValueError, e.what()); }
    });
    m.attr("version") = GONIO_VERSION;

    py::class_<ModelSlices>(m, "ModelBins", "a model's bins on a run (opaque: a Run reads them)")
        .def_readonly("id", &ModelSlices::id);
    py::class_<InProcessRun>(m, "CoreRun", "a run in memory: its reference and the models on its bins")
        .def("summary_json", &run_summary_text, "summary.json's bytes")
        .def("slices_csv", &run_slices_text, "slices.csv's bytes")
        .def("save", &save_run, py::arg("dir"), "writes the EXR, slices.csv, summary.json and state.gonio to dir")
        .def("nodes", &nodes_arrays, py::arg("k"), "k x k nodes per bin: angle, side, bin, l, v, weight")
        .def("values_model", &values_model, py::arg("id"), py::arg("k"), py::arg("values"),
             "a model's bins from its values at nodes(k)")
        .def("with_models", &models_on, py::arg("args"), py::arg("extra"), py::arg("glsl") = std::vector<std::string>{},
             "the run with the models compare's options select (and extra) on its bins, compared");
    py::class_<InProcessFit>(m, "CoreFit", "a fit in memory: fit.json's bytes and the run with the model at both ends")
        .def_readonly("run", &InProcessFit::run)
        .def_readonly("fit_json", &InProcessFit::fit_json);
    m.def(
        "fit",
        [](const InProcessRun& run, const std::vector<std::string>& args) {
            py::gil_scoped_release nogil;
            return fit_in_process(run, args);
        },
        py::arg("run"), py::arg("args"), "gonio fit --reference on a run in memory");
    m.def(
        "check_stack",
        [](const std::string& text, const std::string& path) { return describe_stack(parse_stack_string(text, path)); },
        py::arg("text"), py::arg("path"), "the stack parsed and validated: gonio check's description");
    m.def("run", &run_stack, py::arg("text"), py::arg("path"), py::arg("args"), py::arg("compare"),
          py::arg("progress") = py::none(), "simulate (compare: and the models) in memory");
    m.def("spectral_run", &spectral_run, py::arg("text"), py::arg("path"), py::arg("args"),
          py::arg("progress") = py::none(), "simulate --spectral in memory: (summary.json's bytes, the EXR's parts)");
    m.def("render", &render_run, py::arg("text"), py::arg("path"), py::arg("args"), py::arg("progress") = py::none(),
          "gonio render in memory: (images, not rendered, environment)");
    m.def("command_help", &command_help_text, py::arg("command"), "`gonio COMMAND --help`");
}
