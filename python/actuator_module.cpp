// `import actuator`: the workbench from Python. Shapes, the models' def structs (their fields bound
// from app/fields.h, so names, defaults and ranges are the C++ ones, written once), evaluate and
// evaluate_many on the workbench's evaluator with the GIL released, and results with NumPy arrays.
// Bad input raises ValueError with the command line's message; numerical failure is a status.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <filesystem>
#include <numbers>
#include <optional>

#include "errors.h"
#include "evaluator.h"
#include "experiment.h"
#include "experiment_runner.h"
#include "results_folder.h"
#include "fields.h"
#include "sim/batch.h"
#include "sim/names.h"
#include "sim/shape.h"
#include "sim/shell.h"

namespace py = pybind11;

namespace {

// Visitors of app/fields.h for one field, found by key: read it as a Python object (int, float or
// the enum's name), set it with the command line's range checks, or list the keys.
struct FieldReader {
    const std::string& key;
    py::object& out;
    void Integer(const char* k, const int& v, const char*, long long, long long) {
        if (key == k) out = py::int_(v);
    }
    void Number(const char* k, const double& v, const char*, double, double) {
        if (key == k) out = py::float_(v);
    }
    template <class E>
    void Enum(const char* k, const E& v, const char*) {
        if (key == k) out = py::str(sim::Name(v));
    }
};

struct FieldWriter {
    const std::string& key;
    const py::object& value;
    void Integer(const char* k, int& v, const char*, long long min, long long max) {
        if (key != k) return;
        const long long x = value.cast<long long>();
        if (x < min || x > max) throw py::value_error(fmt::format("{}: {} is out of range ({} to {})", k, x, min, max));
        v = static_cast<int>(x);
    }
    void Number(const char* k, double& v, const char*, double min, double max) {
        if (key != k) return;
        const double x = value.cast<double>();
        if (!(x >= min && x <= max)) throw py::value_error(fmt::format("{}: {} is out of range ({} to {})", k, x, min, max));
        v = x;
    }
    template <class E>
    void Enum(const char* k, E& v, const char*) {
        if (key != k) return;
        const std::string text = value.cast<std::string>();
        const auto parsed = sim::FromName<E>(text);
        if (!parsed) throw py::value_error(fmt::format("{}: unknown value '{}' (choose {})", k, text, sim::Choices<E>()));
        v = *parsed;
    }
};

template <class Def>
py::object GetField(const Def& def, const std::string& key) {
    py::object out;
    app::VisitFields(def, FieldReader{key, out});
    return out;
}

template <class Def>
void SetField(Def& def, const std::string& key, const py::object& value) {
    app::VisitFields(def, FieldWriter{key, value});
}

template <class Def>
struct FieldLister {
    std::vector<std::string>& keys;
    py::class_<Def>& cls;
    void Add(const char* k, const char* help) {
        keys.push_back(k);
        const std::string key = k;
        cls.def_property(
            k, [key](const Def& d) { return GetField(d, key); }, [key](Def& d, const py::object& v) { SetField(d, key, v); }, help);
    }
    void Integer(const char* k, int&, const char* help, long long, long long) { Add(k, help); }
    void Number(const char* k, double&, const char* help, double, double) { Add(k, help); }
    template <class E>
    void Enum(const char* k, E&, const char* help) {
        Add(k, help);
    }
};

// A def struct as a Python class: a keyword constructor and one attribute per field, with its help.
template <class Def>
void BindDef(py::module_& m, const char* name, const char* doc, Def defaults = Def{}) {
    py::class_<Def> cls(m, name, doc);
    std::vector<std::string> keys;
    Def probe = defaults;
    app::VisitFields(probe, FieldLister<Def>{keys, cls});
    cls.def(py::init([defaults, keys](const py::kwargs& kwargs) {
        Def def = defaults;
        for (const auto& [key, value] : kwargs) {
            const std::string k = key.template cast<std::string>();
            if (std::find(keys.begin(), keys.end(), k) == keys.end()) {
                std::string valid;
                for (const auto& v : keys) valid += (valid.empty() ? "" : ", ") + v;
                throw py::value_error(fmt::format("unknown field '{}' (valid: {})", k, valid));
            }
            SetField(def, k, py::reinterpret_borrow<py::object>(value));
        }
        return def;
    }));
    const std::string className = name;
    cls.def("__repr__", [keys, className](const Def& d) {
        std::string text = className + "(";
        for (size_t k = 0; k < keys.size(); ++k) text += (k ? ", " : "") + keys[k] + "=" + std::string(py::repr(GetField(d, keys[k])));
        return text + ")";
    });
}

// A design, held whole: pybind11's std::variant caster would otherwise unpack sim::Shape.
struct Design {
    sim::Shape shape;
};

// (N, 3) array of positions (the solver's structure-of-arrays is copied into rows).
py::array_t<double> Rows(const sim::Positions& p) {
    py::array_t<double> out({static_cast<py::ssize_t>(p.Size()), static_cast<py::ssize_t>(3)});
    auto a = out.mutable_unchecked<2>();
    for (int i = 0; i < p.Size(); ++i) {
        a(i, 0) = p.x[i];
        a(i, 1) = p.y[i];
        a(i, 2) = p.z[i];
    }
    return out;
}

// The job for a shape under a model: thesis (params, mesh) or membrane/shell (the shell def's parts).
sim::EvalJob JobOf(const sim::Shape& shape, const std::string& model, const std::optional<sim::SimParams>& params, const std::optional<sim::MeshDef>& mesh,
                   const std::optional<sim::GeometryDef>& geometry, const std::optional<sim::MaterialDef>& material,
                   const std::optional<sim::LoadDef>& load) {
    sim::EvalJob job;
    const auto kind = sim::FromName<sim::ModelKind>(model);
    if (!kind) throw py::value_error("model: unknown value '" + model + "' (choose " + sim::Choices<sim::ModelKind>() + ")");
    job.model = *kind;
    job.shape = shape;
    if (job.model == sim::ModelKind::Thesis) {
        if (geometry || material || load) throw py::value_error("geometry, material and load are the membrane and shell models'; the thesis model takes params and mesh");
        job.params = params.value_or(sim::DefaultSimParams());
        job.mesh = mesh.value_or(sim::DefaultMeshDef());
    } else {
        if (params || mesh) throw py::value_error(std::string("params and mesh are the thesis model's; the ") + model + " model takes geometry, material and load");
        job.shell = sim::DefaultShellDef();
        if (geometry) job.shell.geometry = *geometry;
        if (material) job.shell.material = *material;
        if (load) job.shell.load = *load;
    }
    if (const std::string error = sim::JobError(job); !error.empty()) throw py::value_error(error);
    return job;
}

// Runs an experiment (a dict, or the path of a JSON file) into `out` (new or empty) on `threads`
// threads and returns its summary and its tables as NumPy structured arrays: results.csv for a sweep
// or a list, each run's logbook.csv (and pareto_front.csv) for the GA and the optimizers.
py::dict RunExperimentFromPython(const py::object& experiment, const std::string& out, int threads, std::optional<app::ExperimentKind> kind) {
    namespace fs = std::filesystem;
    app::Experiment e;
    if (py::isinstance<py::dict>(experiment)) {
        const std::string text = py::str(py::module_::import("json").attr("dumps")(experiment));
        e = app::ParseExperiment(text, "<dict>");
    } else {
        e = app::LoadExperiment(experiment.cast<std::string>());
    }
    if (kind && e.kind != *kind) {
        static const char* names[] = {"sweep", "evolve", "evaluate", "optimizer"};
        throw py::value_error(std::string("this experiment is a '") + names[static_cast<int>(e.kind)] + "' one; use actuator.run (or the function of that name)");
    }
    if (threads < 0) throw py::value_error("threads: must be 0 (one per core) or more");
    {
        py::gil_scoped_release release;
        app::ResultsFolder folder(out, app::FolderMode::Fresh, "python");
        const auto evaluator = app::MakeLocalEvaluator(threads);
        app::RunOptions options;
        options.evaluator = evaluator.get();
        options.progress = false;
        options.folder = &folder;
        app::RunExperiment(e, out, options);
        folder.FirstResultDone();
    }
    const py::object numpy = py::module_::import("numpy");
    auto table = [&](const fs::path& csv) {
        return numpy.attr("genfromtxt")(csv.string(), py::arg("delimiter") = ",", py::arg("names") = true, py::arg("dtype") = py::none(),
                                        py::arg("encoding") = "utf-8", py::arg("ndmin") = 1);
    };
    py::dict tables;
    if (fs::exists(fs::path(out) / "results.csv")) tables["results"] = table(fs::path(out) / "results.csv");
    for (int r = 1; r <= e.runs; ++r)
        for (const char* name : {"logbook", "pareto_front"}) {
            const fs::path csv = fs::path(out) / ("run_" + std::to_string(r)) / (std::string(name) + ".csv");
            if (fs::exists(csv)) tables[py::str(fmt::format("run_{}_{}", r, name))] = table(csv);
        }
    py::dict result;
    result["summary"] = py::module_::import("json").attr("loads")(app::ReadInputFile((fs::path(out) / "summary.json").string()));
    result["tables"] = tables;
    result["folder"] = out;
    return result;
}

}  // namespace

PYBIND11_MODULE(actuator, m) {
    // The command line's bad-input errors are Python's ValueError, with the same one line.
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const app::UsageError& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        }
    });
    m.doc() = "Actuator Workbench: generative design of thin-walled soft pneumatic actuators (the `actuator` command line's models, from Python).";

    py::class_<Design>(m, "Shape", "An actuator design: make one with cylinder(), sine(), abs_sine(), bspline() or free_xy().")
        .def_property_readonly("family", [](const Design& d) { return std::string(sim::ShapeName(d.shape)); })
        .def("__repr__", [](const Design& d) { return std::string("<actuator.Shape ") + sim::ShapeName(d.shape) + ">"; });
    m.def("cylinder", []() { return Design{sim::CylinderShape{}}; }, "The plain tube of radius 1.");
    const sim::SineShape sine;
    m.def("sine", [](double amplitude, std::pair<double, double> phase) { return Design{sim::SineShape{amplitude, phase.first, phase.second}}; },
          py::arg("amplitude") = sine.amplitude, py::arg("phase") = std::pair{sine.phaseStart, sine.phaseEnd},
          "Radius A sin(phase) along the tube (thesis chapter 4).");
    const sim::AbsSineShape absSine;
    m.def("abs_sine", [](double amplitude, std::pair<double, double> phase) { return Design{sim::AbsSineShape{amplitude, phase.first, phase.second}}; },
          py::arg("amplitude") = absSine.amplitude, py::arg("phase") = std::pair{absSine.phaseStart, absSine.phaseEnd},
          "Radius A |sin(phase)| along the tube (thesis 4.3).");
    m.def(
        "bspline",
        [](std::vector<std::vector<double>> controlPoints, const std::string& region) {
            const auto r = sim::FromName<sim::SplineRegion>(region);
            if (!r) throw py::value_error("region: unknown value '" + region + "' (choose " + sim::Choices<sim::SplineRegion>() + ")");
            return Design{sim::BSplineShape{*r, std::move(controlPoints)}};
        },
        py::arg("control_points"), py::arg("region") = std::string(sim::Name(sim::BSplineShape{}.region)),
        "Radius from 1, 2 or 4 cubic B-splines (one per angular sector), over the middle or the entire tube (thesis chapter 5).");
    m.def(
        "free_xy", [](std::vector<double> dx, std::vector<double> dy) { return Design{sim::FreeXYShape{std::move(dx), std::move(dy)}}; }, py::arg("dx"),
        py::arg("dy"), "The plain tube with an (dx, dy) offset per vertex of the model's mesh (thesis 5.5).");

    BindDef<sim::SimParams>(m, "ThesisParams", "The thesis model's constants (shared/MODEL.md).", sim::DefaultSimParams());
    BindDef<sim::MeshDef>(m, "Mesh", "The thesis model's helix.", sim::DefaultMeshDef());
    BindDef<sim::GeometryDef>(m, "Geometry", "The membrane and shell models' tube, in mm.", sim::DefaultShellDef().geometry);
    BindDef<sim::MaterialDef>(m, "Material", "The membrane and shell models' material (a preset's constants, or your own).",
                              sim::DefaultShellDef().material);
    BindDef<sim::LoadDef>(m, "Load", "The membrane and shell models' load.", sim::DefaultShellDef().load);

    py::class_<sim::SimResult>(m, "Result", "One evaluation: numbers, status, and the meshes before and after.")
        .def_property_readonly("status", [](const sim::SimResult& r) { return std::string(sim::Name(r.status)); })
        .def_readonly("fitness", &sim::SimResult::fitness, "thesis model: mesh units; membrane and shell: contraction in percent at the target pressure")
        .def_readonly("contraction_percent", &sim::SimResult::contractionPercent, "positive = shorter")
        .def_readonly("iterations", &sim::SimResult::iterationsRun, "relaxation steps run (thesis model)")
        .def_property_readonly("initial", [](const sim::SimResult& r) { return Rows(r.initial); }, "(N, 3) rest positions")
        .def_property_readonly("final", [](const sim::SimResult& r) { return Rows(r.final); }, "(N, 3) positions after the load")
        .def("__repr__", [](const sim::SimResult& r) {
            return fmt::format("<actuator.Result {} fitness={:.6g} contraction={:.4g}%>", sim::Name(r.status), r.fitness, r.contractionPercent);
        });

    m.def(
        "evaluate",
        [](const Design& design, const std::string& model, std::optional<sim::SimParams> params, std::optional<sim::MeshDef> mesh,
           std::optional<sim::GeometryDef> geometry, std::optional<sim::MaterialDef> material, std::optional<sim::LoadDef> load) {
            const sim::EvalJob job = JobOf(design.shape, model, params, mesh, geometry, material, load);
            py::gil_scoped_release release;
            return sim::Evaluate(job);
        },
        py::arg("shape"), py::arg("model") = std::string(sim::Name(sim::ModelKind::Thesis)), py::arg("params") = py::none(), py::arg("mesh") = py::none(),
        py::arg("geometry") = py::none(), py::arg("material") = py::none(), py::arg("load") = py::none(),
        "Evaluates one design under a model: 'thesis' (params, mesh) or 'membrane'/'shell' (geometry, material, load).");
    m.def(
        "evaluate_many",
        [](const std::vector<Design>& designs, int threads, const std::string& model, std::optional<sim::SimParams> params,
           std::optional<sim::MeshDef> mesh, std::optional<sim::GeometryDef> geometry, std::optional<sim::MaterialDef> material,
           std::optional<sim::LoadDef> load) {
            if (threads < 0) throw py::value_error("threads: must be 0 (one per core) or more");
            std::vector<sim::EvalJob> jobs;
            for (const auto& design : designs) jobs.push_back(JobOf(design.shape, model, params, mesh, geometry, material, load));
            py::gil_scoped_release release;
            return app::MakeLocalEvaluator(threads)->EvaluateAll(jobs);
        },
        py::arg("shapes"), py::arg("threads") = 0, py::arg("model") = std::string(sim::Name(sim::ModelKind::Thesis)), py::arg("params") = py::none(),
        py::arg("mesh") = py::none(), py::arg("geometry") = py::none(), py::arg("material") = py::none(), py::arg("load") = py::none(),
        "Evaluates many designs on the workbench's evaluator (threads; 0: one per core), results in the order given. The GIL is released.");
    const char* runDoc = "Runs an experiment (a dict in the experiment-file format, or a JSON file's path) into `out` (a new or empty folder) and "
                         "returns {'summary': ..., 'tables': {name: NumPy structured array}, 'folder': out}.";
    m.def("run", [](const py::object& e, const std::string& out, int threads) { return RunExperimentFromPython(e, out, threads, std::nullopt); },
          py::arg("experiment"), py::arg("out"), py::arg("threads") = 0, runDoc);
    m.def("sweep", [](const py::object& e, const std::string& out, int threads) { return RunExperimentFromPython(e, out, threads, app::ExperimentKind::Sweep); },
          py::arg("experiment"), py::arg("out"), py::arg("threads") = 0, "run() for a sweep experiment; its table is 'results'.");
    m.def("evolve", [](const py::object& e, const std::string& out, int threads) { return RunExperimentFromPython(e, out, threads, app::ExperimentKind::Evolve); },
          py::arg("experiment"), py::arg("out"), py::arg("threads") = 0, "run() for a GA experiment; its tables are 'run_K_logbook'.");
    m.def("optimize",
          [](const py::object& e, const std::string& out, int threads) { return RunExperimentFromPython(e, out, threads, app::ExperimentKind::Optimize); },
          py::arg("experiment"), py::arg("out"), py::arg("threads") = 0, "run() for an optimizer experiment; 'run_K_logbook' and 'run_K_pareto_front'.");
}
