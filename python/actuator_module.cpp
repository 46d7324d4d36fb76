// `import actuator`: the workbench from Python. Shapes, the models' def structs (def_binding.h),
// evaluate and evaluate_many on the workbench's evaluators (threads, servers, or any Python map:
// map_evaluator.h) with the GIL released, experiments with their tables as NumPy or pandas, results
// with NumPy arrays, pictures, and archives as iterables of records.
// Bad input raises ValueError with the command line's message; numerical failure is a status.
#include <pybind11/eval.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include <filesystem>
#include <numbers>
#include <optional>
#include <sstream>
#include <iostream>
#include <utility>

#include "commands/registry.h"
#include "formats/archive.h"
#include "options/cli.h"
#include "def_binding.h"
#include "support/errors.h"
#include "evaluation/characterize.h"
#include "evaluation/evaluator.h"
#include "evaluation/mesh_check.h"
#include "experiments/experiment.h"
#include "experiments/experiment_runner.h"
#include "formats/files.h"
#include "materials/material_file.h"
#include "pictures/figures.h"
#include "map_evaluator.h"
#include "fields/result_fields.h"
#include "formats/results_folder.h"
#include "formats/table.h"
#include "options/part_options.h"
#include "report/part_export.h"
#include "formats/schema_convert.h"
#include "sim/batch.h"
#include "sim/names.h"
#include "sim/shape.h"
#include "sim/shell.h"

namespace py = pybind11;
using pybinding::BindDef;

namespace {

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

// The keyword arguments that set a model's def; each def takes its own and refuses the others'.
struct DefArguments {
    std::optional<sim::SimParams> params;
    std::optional<sim::MeshDef> mesh;
    std::optional<sim::GeometryDef> geometry;
    std::optional<sim::MaterialDef> material;
    std::optional<sim::LoadDef> load;
    std::optional<sim::EndsDef> ends;
    std::optional<sim::SolverDef> solver;
    std::optional<sim::FibreDef> fibres;
    std::optional<sim::EnvelopeDef> envelope;
    std::optional<sim::ContactDef> contact;
};

// [SECTION] Each def from the keyword arguments (a new def adds its overload).
void FillDef(const DefArguments& a, sim::ModelKind, sim::ThesisDef& def) {
    if (a.geometry || a.material || a.load || a.ends || a.solver || a.fibres || a.envelope || a.contact)
        throw py::value_error("geometry, material, load, ends, solver, fibres, envelope and contact are the membrane and shell models'; the thesis model takes params and mesh");
    def.params = a.params.value_or(sim::DefaultSimParams());
    def.mesh = a.mesh.value_or(sim::DefaultMeshDef());
}
void FillDef(const DefArguments& a, sim::ModelKind model, sim::ShellDef& def) {
    if (a.params || a.mesh)
        throw py::value_error(std::string("params and mesh are the thesis model's; the ") + sim::Name(model) + " model takes geometry, material, load, ends, solver, fibres, envelope and contact");
    if (a.geometry) def.geometry = *a.geometry;
    if (a.material) def.material = *a.material;
    if (a.load) def.load = *a.load;
    if (a.ends) def.ends = *a.ends;
    if (a.solver) def.solver = *a.solver;
    if (a.fibres) def.fibres = *a.fibres;
    if (a.envelope) def.envelope = *a.envelope;
    if (a.contact) def.contact = *a.contact;
    if (const std::string error = sim::ShellFieldsWithoutEffect(def); !error.empty()) throw py::value_error(error);
}

// The job for a shape under a model, its def from the model's default and the arguments given.
sim::EvalJob JobOf(const sim::Shape& shape, const std::string& model, const DefArguments& arguments) {
    sim::EvalJob job;
    const auto kind = sim::FromName<sim::ModelKind>(model);
    if (!kind) throw py::value_error("model: unknown value '" + model + "' (choose " + sim::Choices<sim::ModelKind>() + ")");
    job.SetModel(*kind);
    job.shape = shape;
    std::visit([&](auto& def) { FillDef(arguments, job.model, def); }, job.def);
    if (const std::string error = sim::JobError(job); !error.empty()) throw py::value_error(error);
    return job;
}

// A result with the job that made it: pictures and the shell model's outputs need both.
struct Evaluated {
    sim::EvalJob job;
    sim::SimResult result;
};

// An archive's record: where it came from, and its result.
struct Record {
    app::ArchiveRecord record;
};

// The archive read a few records at a time (memory stays bounded on a 100,000-record archive). A
// torn tail (a run cut off while writing) ends the records quietly; a damaged record raises
// ValueError after the records before it.
class ArchiveIterator {
public:
    ArchiveIterator(std::string path, bool meshes) : path_(std::move(path)), meshes_(meshes) {}

    Record Next() {
        if (next_ == buffer_.size() && !done_) Refill();
        if (next_ == buffer_.size()) {
            if (!problem_.empty()) throw app::UsageError(app::Quote(path_) + ": " + std::exchange(problem_, std::string()));
            throw py::stop_iteration();
        }
        return Record{std::move(buffer_[next_++])};
    }

private:
    static constexpr size_t kChunk = 256;

    app::ArchiveScan Scan(size_t limit) {
        return app::ScanArchive(
            path_, meshes_,
            [&](app::ArchiveRecord&& r) {
                buffer_.push_back(std::move(r));
                return buffer_.size() < limit;
            },
            place_);
    }

    void Refill() {
        buffer_.clear();
        next_ = 0;
        py::gil_scoped_release release;
        app::ArchiveScan scan = Scan(kChunk);
        if (scan.version == 1 && buffer_.size() == kChunk) {  // a version-1 archive reads only from its start: take it whole
            buffer_.clear();
            scan = Scan(SIZE_MAX);
        }
        place_ = {scan.goodBytes, scan.records};
        done_ = buffer_.size() < kChunk || scan.version == 1 || scan.corrupt;
        if (scan.corrupt) problem_ = scan.problem;
    }

    std::string path_;
    bool meshes_;
    app::ArchivePlace place_;
    std::vector<app::ArchiveRecord> buffer_;
    size_t next_ = 0;
    bool done_ = false;
    std::string problem_;
};

// A CSV table as a pandas DataFrame (when asked, or when pandas is there and nothing was said) or
// as a NumPy structured array.
py::object Table(const std::filesystem::path& csv, bool asFrame) {
    // round_trip: pandas's default parser may be off in the last bit; the CSVs hold exact round-trip numbers.
    if (asFrame) return py::module_::import("pandas").attr("read_csv")(csv.string(), py::arg("float_precision") = "round_trip");
    // NumPy: read by the tables' own reader (RFC 4180: quoted fields may hold commas, which
    // numpy.genfromtxt splits); a column of numbers (empty: NaN) is float64, any other str.
    const app::Table table = app::Table::Read(csv.string());
    py::list columns, names;
    for (const std::string& column : table.Columns()) {
        std::vector<double> numbers(table.Rows());
        bool numeric = true;
        for (size_t k = 0; k < table.Rows() && numeric; ++k) {
            try {
                numbers[k] = table.Number(k, column);
            } catch (const app::UsageError&) {
                numeric = false;
            }
        }
        if (numeric) {
            columns.append(py::array_t<double>(static_cast<py::ssize_t>(numbers.size()), numbers.data()));
        } else {
            py::list text;
            for (size_t k = 0; k < table.Rows(); ++k) text.append(table.Text(k, column));
            columns.append(py::module_::import("numpy").attr("array")(text, py::arg("dtype") = "U"));
        }
        names.append(column);
    }
    return py::module_::import("numpy").attr("rec").attr("fromarrays")(columns, py::arg("names") = names);
}

bool PandasInstalled() {
    return !py::module_::import("importlib.util").attr("find_spec")("pandas").is_none();
}

bool FramesWanted(const py::object& asFrame) {
    if (!asFrame.is_none()) {
        const bool wanted = asFrame.cast<bool>();
        if (wanted && !PandasInstalled())
            throw py::value_error("as_frame=True: pandas is not installed (apt-get install python3-pandas), or pass as_frame=False for NumPy arrays");
        return wanted;
    }
    return PandasInstalled();
}

// A path argument as Python's own functions take one (os.fspath): str, bytes (decoded as the file
// system does) or any os.PathLike; anything else is a TypeError naming the argument.
std::string FsPath(const py::object& value, const char* what) {
    const py::module_ os = py::module_::import("os");
    if (!py::isinstance<py::str>(value) && !py::isinstance<py::bytes>(value) && !py::hasattr(value, "__fspath__"))
        throw py::type_error(fmt::format("{}: expected a path (str, bytes or os.PathLike), got {}", what, std::string(py::str(value.get_type().attr("__name__")))));
    return os.attr("fsdecode")(os.attr("fspath")(value)).cast<std::string>();
}

// A field array as NumPy: (N,) for scalars, (N, 3) for vectors; Int32 codes as int32.
py::array FieldNumpy(const app::FieldArray& a) {
    const py::ssize_t tuples = static_cast<py::ssize_t>(a.values.size() / a.components);
    if (a.integer) {
        py::array_t<int32_t> out(tuples);
        for (py::ssize_t k = 0; k < tuples; ++k) out.mutable_at(k) = static_cast<int32_t>(a.values[k]);
        return out;
    }
    std::vector<py::ssize_t> shape{tuples};
    if (a.components > 1) shape.push_back(a.components);
    py::array_t<double> out(shape);
    std::copy(a.values.begin(), a.values.end(), out.mutable_data());
    return out;
}

py::array_t<int32_t> Faces(const std::vector<std::array<int, 3>>& triangles) {
    py::array_t<int32_t> out({static_cast<py::ssize_t>(triangles.size()), static_cast<py::ssize_t>(3)});
    auto a = out.mutable_unchecked<2>();
    for (size_t t = 0; t < triangles.size(); ++t)
        for (int c = 0; c < 3; ++c) a(t, c) = triangles[t][c];
    return out;
}

// An enum argument by its name, as the command line takes it.
template <class E>
E EnumArgument(const std::string& text, const char* what) {
    const auto parsed = sim::FromName<E>(text);
    if (!parsed) throw py::value_error(fmt::format("{}: unknown value '{}' (choose {})", what, text, sim::Choices<E>()));
    return *parsed;
}

// A number argument that must be finite, as the command line's are.
double Finite(double value, const char* what) {
    if (!std::isfinite(value)) throw py::value_error(fmt::format("{}: {} is not a finite number", what, value));
    return value;
}

struct RunArgs {
    int threads = 0;
    py::object map, workers, asFrame;
    bool resume = false;
    bool progress = false;  // the command line's progress lines, on the process's stderr
};

// Every table a results folder holds, by name: its own CSV files under their stem (results,
// evaluations, ...), then each run's as run_K_<stem> (logbook, halloffame, best_per_generation,
// pareto_front), in a fixed order.
std::vector<std::pair<std::string, std::filesystem::path>> FolderTables(const std::string& out, int runs) {
    namespace fs = std::filesystem;
    auto csvs = [](const fs::path& dir) {
        std::vector<fs::path> files;
        if (fs::is_directory(dir))
            for (const auto& entry : fs::directory_iterator(dir))
                if (entry.is_regular_file() && entry.path().extension() == ".csv") files.push_back(entry.path());
        std::sort(files.begin(), files.end());
        return files;
    };
    std::vector<std::pair<std::string, fs::path>> tables;
    for (const fs::path& csv : csvs(out)) tables.emplace_back(csv.stem().string(), csv);
    for (int r = 1; r <= runs; ++r)
        for (const fs::path& csv : csvs(fs::path(out) / ("run_" + std::to_string(r))))
            tables.emplace_back(fmt::format("run_{}_{}", r, csv.stem().string()), csv);
    return tables;
}

// Runs an experiment (a dict, or the path of a JSON file) into `out` (new or empty; or, with resume,
// a folder an interrupted run left) and returns its summary and every table the folder holds.
py::dict RunExperimentFromPython(const py::object& experiment, const py::object& outPath, const RunArgs& args, std::optional<app::ExperimentKind> kind) {
    namespace fs = std::filesystem;
    const std::string out = FsPath(outPath, "out");
    app::Experiment e;
    if (py::isinstance<py::dict>(experiment)) {
        // allow_nan=False: NaN is not JSON, and the experiment file format has none.
        std::string text;
        try {
            text = py::str(py::module_::import("json").attr("dumps")(experiment, py::arg("allow_nan") = false));
        } catch (py::error_already_set& error) {
            if (!error.matches(PyExc_ValueError) && !error.matches(PyExc_TypeError) && !error.matches(PyExc_RecursionError)) throw;
            throw py::value_error(std::string("experiment: not an experiment in JSON's terms (") + error.what() + ")");
        }
        e = app::ParseExperiment(text, "<dict>");
    } else {
        if (!py::isinstance<py::str>(experiment) && !py::isinstance<py::bytes>(experiment) && !py::hasattr(experiment, "__fspath__"))
            throw py::type_error(fmt::format("experiment: expected a dict or a path, got {}", std::string(py::str(experiment.get_type().attr("__name__")))));
        e = app::LoadExperiment(FsPath(experiment, "experiment"));
    }
    if (kind && e.kind != *kind) {
        throw py::value_error(fmt::format("this experiment is a '{}' one; use actuator.run (or the function of that name)", sim::Name(e.kind)));
    }
    const bool frames = FramesWanted(args.asFrame);
    const std::unique_ptr<app::Evaluator> evaluator = pybinding::MakePythonEvaluator(args.threads, args.map, args.workers);
    {
        py::gil_scoped_release release;
        app::ResultsFolder folder(out, args.resume ? app::FolderMode::Resume : app::FolderMode::Fresh, "python");
        app::RunOptions options;
        options.evaluator = evaluator.get();
        options.progress = args.progress;
        options.resume = args.resume;
        options.folder = &folder;
        app::RunExperiment(e, out, options);
        folder.FirstResultDone();
    }
    py::dict tables;
    for (const auto& [name, csv] : FolderTables(out, e.runs)) tables[py::str(name)] = Table(csv, frames);
    py::dict result;
    result["summary"] = py::module_::import("json").attr("loads")(app::ReadInputFile((fs::path(out) / "summary.json").string()));
    result["tables"] = tables;
    result["folder"] = out;
    return result;
}

// The picture `view` of a result: "before_after" (the command line's inflation figure) or
// "turntable" (the deformed mesh turned by angle_deg).
render::Image RenderResult(const Evaluated& e, const std::string& view, double angleDeg, int width, int height, const std::string& colouringName,
                           int supersample) {
    const auto colouring = sim::FromName<app::Colouring>(colouringName);
    if (!colouring) throw py::value_error("colouring: unknown value '" + colouringName + "' (choose " + sim::Choices<app::Colouring>() + ")");
    if (const std::string error = app::ColouringError(*colouring, e.job); !error.empty()) throw py::value_error("colouring: " + error);
    if (view != "before_after" && view != "turntable") throw py::value_error("view: unknown value '" + view + "' (choose before_after, turntable)");
    if (width < 16 || height < 16 || width > 8192 || height > 8192) throw py::value_error("width and height: 16 to 8192 pixels");
    if (supersample < 1 || supersample > 4) throw py::value_error("supersample: 1 to 4");
    if (e.result.final.Size() == 0) throw py::value_error("this result has no meshes (an archive read with meshes=False?)");
    py::gil_scoped_release release;
    const std::string title = app::JobTitle(e.job);  // as `actuator render` titles it
    const render::Scene scene = view == "before_after" ? app::BeforeAfterScene(title, e.result, e.job, *colouring)
                                                       : app::TurntableScene(title, e.result, e.job, angleDeg, *colouring);
    return app::MakeRenderer(width, height, supersample)->Render(scene);
}

// Jupyter's rich display: the result's before-and-after figure as PNG bytes, at the command line's
// size (its overlay's lines are laid out for it; a notebook scales the picture to the cell); None
// for a result without meshes (Jupyter then shows the repr).
py::object ReprPng(const Evaluated& e) {
    if (e.result.final.Size() == 0) return py::none();
    const render::RenderDef def = render::DefaultRenderDef();
    const render::Image image = RenderResult(e, "before_after", 0, def.width, def.height, "auto", def.supersample);
    const std::vector<std::uint8_t> png = render::EncodePng(image, 6);
    return py::bytes(reinterpret_cast<const char*>(png.data()), png.size());
}

py::array_t<std::uint8_t> ImageArray(render::Image&& image) {
    auto* owned = new std::vector<std::uint8_t>(std::move(image.rgba));
    py::capsule free(owned, [](void* p) { delete static_cast<std::vector<std::uint8_t>*>(p); });
    return py::array_t<std::uint8_t>({image.height, image.width, 4}, owned->data(), free);
}

// The model's own outputs as `actuator simulate`'s JSON names them (the same visit writes both);
// curves as NumPy arrays. Fitness, contraction and time are the Result's own attributes.
py::dict ModelOutputs(const Evaluated& e) {
    struct Dict final : sim::OutputVisitor {
        py::dict d;
        static bool Common(const std::string& name) { return name == "fitness" || name == "contraction_percent" || name == "elapsed_ms"; }
        void Number(const char* name, const char*, double value) override {
            if (!Common(name)) d[name] = value;
        }
        void Count(const char* name, long long value) override { d[name] = value; }
        void Curve(const char* name, const char*, const std::vector<double>& v) override {
            d[name] = py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
        }
    } dict;
    if (!sim::ModelOf(e.job).physical) return dict.d;
    sim::VisitOutputs(e.result, e.job, dict);
    return dict.d;
}

}  // namespace

PYBIND11_MODULE(actuator, m) {
    // The command line's bad-input errors are Python's ValueError, with the same one line.
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const app::UsageError& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const app::OutputError& e) {
            PyErr_SetString(PyExc_OSError, e.what());  // a full disk: nothing of the output was kept
        }
    });
    m.attr("__version__") = app::Version();
    m.doc() = "Actuator Workbench: generative design of thin-walled soft pneumatic actuators (the `actuator` command line's models, from Python).";

    py::class_<Design>(m, "Shape", "An actuator design: make one with cylinder(), sine(), abs_sine(), bspline() or free_xy().")
        .def_property_readonly("family", [](const Design& d) { return std::string(sim::ShapeName(d.shape)); })
        .def_property_readonly("title", [](const Design& d) { return app::ShapeTitle(d.shape); })
        .def("__repr__", [](const Design& d) { return "<actuator.Shape " + app::ShapeTitle(d.shape) + ">"; })
        .def(py::pickle(
                 [](const Design& d) {
                     sim::EvalJob job;
                     job.shape = d.shape;
                     return py::bytes(app::JobBytes(job));
                 },
                        [](const py::bytes& b) { return Design{app::JobFromBytes(b.cast<std::string>()).shape}; }));
    m.def("cylinder", []() { return Design{sim::CylinderShape{}}; }, "The plain tube of radius 1.");
    const sim::SineShape sine;
    m.def("sine",
          [](double amplitude, std::pair<double, double> phase) {
              return Design{sim::SineShape{Finite(amplitude, "amplitude"), Finite(phase.first, "phase"), Finite(phase.second, "phase")}};
          },
          py::arg("amplitude") = sine.amplitude, py::arg("phase") = std::pair{sine.phaseStart, sine.phaseEnd},
          "Radius A sin(phase) along the tube (thesis chapter 4).");
    const sim::AbsSineShape absSine;
    m.def("abs_sine",
          [](double amplitude, std::pair<double, double> phase) {
              return Design{sim::AbsSineShape{Finite(amplitude, "amplitude"), Finite(phase.first, "phase"), Finite(phase.second, "phase")}};
          },
          py::arg("amplitude") = absSine.amplitude, py::arg("phase") = std::pair{absSine.phaseStart, absSine.phaseEnd},
          "Radius A |sin(phase)| along the tube (thesis 4.3).");
    m.def(
        "bspline",
        [](std::vector<std::vector<double>> controlPoints, const std::string& region) {
            const auto r = sim::FromName<sim::SplineRegion>(region);
            if (!r) throw py::value_error("region: unknown value '" + region + "' (choose " + sim::Choices<sim::SplineRegion>() + ")");
            for (const auto& spline : controlPoints)
                for (double c : spline) Finite(c, "control_points");
            return Design{sim::BSplineShape{*r, std::move(controlPoints)}};
        },
        py::arg("control_points"), py::arg("region") = std::string(sim::Name(sim::BSplineShape{}.region)),
        "Radius from 1, 2 or 4 cubic B-splines (one per angular sector), over the middle or the entire tube (thesis chapter 5).");
    m.def(
        "free_xy",
        [](std::vector<double> dx, std::vector<double> dy) {
            for (double v : dx) Finite(v, "dx");
            for (double v : dy) Finite(v, "dy");
            return Design{sim::FreeXYShape{std::move(dx), std::move(dy)}};
        },
        py::arg("dx"),
        py::arg("dy"), "The plain tube with an (dx, dy) offset per vertex of the model's mesh (thesis 5.5).");

    BindDef<sim::SimParams>(m, "ThesisParams", "The thesis model's constants (docs/models/thesis.md).", sim::DefaultSimParams());
    BindDef<sim::MeshDef>(m, "Mesh", "The thesis model's helix.", sim::DefaultMeshDef());
    const sim::ShellDef shell = sim::DefaultShellDef();
    BindDef<sim::GeometryDef>(m, "Geometry", "The membrane and shell models' tube, in mm.", shell.geometry);
    BindDef<sim::MaterialDef>(m, "Material", "The membrane and shell models' material (a preset's constants, or your own).", shell.material)
        .def_static(
            "from_preset",
            [](const std::string& name) {
                const auto preset = sim::FromName<sim::MaterialPreset>(name);
                if (!preset) throw py::value_error("preset: unknown value '" + name + "' (choose " + sim::Choices<sim::MaterialPreset>() + ")");
                return sim::MaterialPresetDef(*preset);
            },
            py::arg("name"), "A preset's constants and limits (Material() is ecoflex-00-30's); change fields after, as the command line's keys override a preset.")
        .def_static(
            "from_file",
            [](const std::string& path) {
                try {
                    return app::ReadMaterialFile(path).material;
                } catch (const app::UsageError& e) {
                    throw py::value_error(e.what());
                }
            },
            py::arg("path"), "A material file's law, constants and limits (written by `actuator material fit`; docs/guide/materials.md).")
        .def_property_readonly("preset", [](const sim::MaterialDef& d) { return std::string(sim::Name(d.preset)); },
                               "the preset the constants started from (figures and JSON name it)");
    BindDef<sim::LoadDef>(m, "Load", "The membrane and shell models' load.", shell.load);
    BindDef<sim::EndsDef>(m, "Ends", "The membrane and shell models' top clamp: its turn held, free or loaded (docs/models/shell.md section 12).", shell.ends);
    BindDef<sim::SolverDef>(m, "Solver", "The membrane and shell models' Newton solver.", shell.solver);
    BindDef<sim::FibreDef>(m, "Fibres", "Fibres on the membrane or shell wall (docs/models/shell.md section 7).", shell.fibres);
    BindDef<sim::EnvelopeDef>(m, "Envelope", "The bounds a bench puts on a design (docs/models/shell.md section 12, envelope): beyond one, the status is outside-envelope.",
                              shell.envelope);
    BindDef<sim::ContactDef>(m, "Contact", "Self-contact (docs/models/shell.md section 8): the walls touch by default (contact='on'; vacuum actuators need it); with contact='off' a state that passes through itself is the status self-intersection.",
                             shell.contact);

    py::class_<Evaluated>(m, "Result", "One evaluation: numbers, status, the meshes before and after, and the job that made it.")
        .def_property_readonly("status", [](const Evaluated& e) { return std::string(sim::Name(e.result.status)); },
                               "ok, or why the evaluation failed (a status, never an exception)")
        .def_property_readonly("fitness", [](const Evaluated& e) { return e.result.fitness; },
                               "thesis model: mesh units; membrane and shell: contraction in percent at the target pressure")
        .def_property_readonly("contraction_percent", [](const Evaluated& e) { return e.result.contractionPercent; }, "positive = shorter")
        .def_property_readonly("iterations", [](const Evaluated& e) { return e.result.iterationsRun; },
                               "thesis: relaxation steps run; membrane and shell: Newton iterations, all load steps")
        .def_property_readonly("elapsed_ms", [](const Evaluated& e) { return e.result.elapsedMs; }, "wall time of the solve, ms")
        .def_property_readonly("model", [](const Evaluated& e) { return std::string(sim::Name(e.job.model)); })
        .def_property_readonly("shape", [](const Evaluated& e) { return Design{e.job.shape}; })
        .def_property_readonly("initial", [](const Evaluated& e) { return Rows(e.result.initial); }, "(N, 3) rest positions")
        .def_property_readonly("final", [](const Evaluated& e) { return Rows(e.result.final); }, "(N, 3) positions after the load")
        .def_property_readonly(
            "faces", [](const Evaluated& e) { return Faces(sim::SurfaceOf(e.job).triangles); },
            "(M, 3) int32 vertex indices of the triangles both meshes are drawn on, counter-clockwise seen from outside (membrane and "
            "shell: the wall's, then the end caps')")
        .def(
            "fields",
            [](const Evaluated& e) {
                const app::FieldMesh mesh = app::ResultFieldMesh(e.job, e.result);
                py::dict point, cell, field;
                for (const auto& a : mesh.pointData) point[py::str(a.name)] = FieldNumpy(a);
                for (const auto& a : mesh.cellData) cell[py::str(a.name)] = FieldNumpy(a);
                for (const auto& a : mesh.fieldData) field[py::str(a.name)] = a.integer ? py::object(py::int_(static_cast<long long>(a.values[0]))) : py::object(py::float_(a.values[0]));
                py::dict out;
                out["point"] = point;
                out["cell"] = cell;
                out["field"] = field;
                return out;
            },
            "The fields a VTU file holds, as NumPy: {'point': per vertex (displacement, rest position; thesis: spring strain), 'cell': per "
            "face (membrane and shell: principal stretches, true stresses in kPa, thickness in mm, each fibre family's direction, strain "
            "and tension in N/mm, 'region' 0 wall / 1 clamped / 2 cap; NaN where a field has no value), 'field': the outputs}. Units in the names.")
        .def(
            "to_vtu",
            [](const Evaluated& e, const py::object& path, bool overwrite) {
                const std::string target = FsPath(path, "path");
                if (std::filesystem::path(target).extension() != ".vtu") throw py::value_error("path: " + target + " must end in .vtu");
                if (std::filesystem::exists(target) && !overwrite)
                    throw py::value_error("path: " + target + " exists; pass overwrite=True to replace it, or another path");
                try {
                    app::WriteFileAtomically(target, app::FormatVtu(app::ResultFieldMesh(e.job, e.result)));
                } catch (const std::exception& error) {
                    throw py::value_error(std::string("path: ") + error.what());
                }
            },
            py::arg("path"), py::arg("overwrite") = false,
            "Writes the deformed wall with its fields as VTK XML (the file `actuator simulate --save-vtu` writes), whole or not at all.")
        .def(
            "to_meshio",
            [](const Evaluated& e) {
                const py::module_ meshio = py::module_::import("meshio");
                const app::FieldMesh mesh = app::ResultFieldMesh(e.job, e.result);
                py::dict point, cell, field;
                for (const auto& a : mesh.pointData) point[py::str(a.name)] = FieldNumpy(a);
                for (const auto& a : mesh.cellData) {  // meshio: one array per cell block (one block of triangles)
                    py::list blocks;
                    blocks.append(FieldNumpy(a));
                    cell[py::str(a.name)] = blocks;
                }
                for (const auto& a : mesh.fieldData) field[py::str(a.name)] = FieldNumpy(a);
                py::list cells;
                cells.append(py::make_tuple("triangle", Faces(mesh.triangles)));
                return meshio.attr("Mesh")(Rows(mesh.points), cells, py::arg("point_data") = point, py::arg("cell_data") = cell,
                                           py::arg("field_data") = field);
            },
            "The deformed wall and its fields as a meshio.Mesh (needs meshio: apt-get install python3-meshio), the same arrays as to_vtu's file.")
        .def(
            "mesh_check",
            [](const Evaluated& e) {
                if (e.job.model == sim::ModelKind::Thesis)
                    throw py::value_error("mesh_check: the thesis model's 30 x 30 helix is part of its definition; the check is for membrane and shell");
                const sim::EvalJob refined = app::RefinedJob(e.job);
                sim::SimResult fine;
                {
                    py::gil_scoped_release release;
                    fine = sim::Evaluate(refined);
                }
                return py::module_::import("json").attr("loads")(app::MeshCheckJson(e.result, refined, fine).dump());
            },
            "Evaluates the same design meshed twice as finely in both directions (the clamps keep their length) and returns what "
            "`actuator simulate --mesh-check` reports as mesh_check: the refined mesh, its status and contraction, how far the "
            "contraction moved (points and percent), 'converged' by docs/models/shell.md section 2's rule, and for a held state the "
            "blocking force refined with its own verdict. Membrane and shell only; it costs about 5-8 evaluations' time.")
        .def_property_readonly("shell", &ModelOutputs,
                               "membrane and shell models: the pressure-contraction-volume curve (NumPy arrays) and the numbers at the "
                               "target pressure, named as in `actuator simulate`'s JSON, units in the names; {} for the thesis model")
        .def("__repr__", [](const Evaluated& e) {
            return fmt::format("<actuator.Result {} {} fitness={:.6g} contraction={:.4g}%>", sim::Name(e.job.model), sim::Name(e.result.status),
                               e.result.fitness, e.result.contractionPercent);
        })
        .def("_repr_png_", &ReprPng, "the before-and-after figure as PNG bytes (Jupyter shows a result as this picture)")
        // Pickled as the wire carries it: every number and both meshes exactly (not the shell
        // models' per-step positions).
        .def(py::pickle([](const Evaluated& e) { return py::make_tuple(py::bytes(app::JobBytes(e.job)), py::bytes(app::ResultBytes(e.result, e.job.model))); },
                        [](const py::tuple& t) {
                            if (t.size() != 2) throw py::value_error("not a pickled actuator.Result");
                            return Evaluated{app::JobFromBytes(t[0].cast<std::string>()), app::ResultFromBytes(t[1].cast<std::string>())};
                        }));

    m.def(
        "evaluate",
        [](const Design& design, const std::string& model, std::optional<sim::SimParams> params, std::optional<sim::MeshDef> mesh,
           std::optional<sim::GeometryDef> geometry, std::optional<sim::MaterialDef> material, std::optional<sim::LoadDef> load,
           std::optional<sim::SolverDef> solver, std::optional<sim::FibreDef> fibres, std::optional<sim::EndsDef> ends,
           std::optional<sim::EnvelopeDef> envelope, std::optional<sim::ContactDef> contact) {
            Evaluated e{JobOf(design.shape, model, {params, mesh, geometry, material, load, ends, solver, fibres, envelope, contact}), {}};
            py::gil_scoped_release release;
            e.result = sim::Evaluate(e.job);
            return e;
        },
        py::arg("shape"), py::arg("model") = std::string(sim::Name(sim::kDefaultModel)), py::arg("params") = py::none(), py::arg("mesh") = py::none(),
        py::arg("geometry") = py::none(), py::arg("material") = py::none(), py::arg("load") = py::none(), py::arg("solver") = py::none(),
        py::arg("fibres") = py::none(), py::arg("ends") = py::none(), py::arg("envelope") = py::none(), py::arg("contact") = py::none(),
        "Evaluates one design under a model: 'shell' (the default) or 'membrane' (geometry, material, load, ends, solver, fibres, envelope, contact), or 'thesis' (params, mesh).");
    m.def(
        "evaluate_many",
        [](const std::vector<Design>& designs, int threads, const py::object& map, const py::object& workers, size_t batch, const std::string& model,
           std::optional<sim::SimParams> params, std::optional<sim::MeshDef> mesh, std::optional<sim::GeometryDef> geometry,
           std::optional<sim::MaterialDef> material, std::optional<sim::LoadDef> load, std::optional<sim::SolverDef> solver,
           std::optional<sim::FibreDef> fibres, std::optional<sim::EndsDef> ends, std::optional<sim::EnvelopeDef> envelope,
           std::optional<sim::ContactDef> contact) {
            std::vector<sim::EvalJob> jobs;
            for (const auto& design : designs)
                jobs.push_back(JobOf(design.shape, model, {params, mesh, geometry, material, load, ends, solver, fibres, envelope, contact}));
            const std::unique_ptr<app::Evaluator> evaluator = pybinding::MakePythonEvaluator(threads, map, workers, batch);
            std::vector<Evaluated> out(jobs.size());
            {
                py::gil_scoped_release release;
                evaluator->Evaluate(jobs, [&](size_t k, sim::SimResult&& r) { out[k] = Evaluated{std::move(jobs[k]), std::move(r)}; });
            }
            return out;
        },
        py::arg("shapes"), py::arg("threads") = 0, py::arg("map") = py::none(), py::arg("workers") = py::none(), py::arg("batch") = pybinding::kDefaultMapBatch,
        py::arg("model") = std::string(sim::Name(sim::kDefaultModel)), py::arg("params") = py::none(), py::arg("mesh") = py::none(),
        py::arg("geometry") = py::none(), py::arg("material") = py::none(), py::arg("load") = py::none(), py::arg("solver") = py::none(),
        py::arg("fibres") = py::none(), py::arg("ends") = py::none(), py::arg("envelope") = py::none(), py::arg("contact") = py::none(),
        "Evaluates many designs, results in the order given, identical wherever they run: on this machine's threads (0: one per core; "
        "the GIL is released), on evaluation servers (workers=['host:port', 'local', ...]), or through any map-like callable "
        "(map=builtins.map, an executor's map, a pool's map, or a Dask client), `batch` jobs at a time.");

    m.def(
        "characterize",
        [](const Design& design, const std::vector<double>& pressuresKpa, int points, int threads, const std::string& model,
           std::optional<sim::GeometryDef> geometry, std::optional<sim::MaterialDef> material, std::optional<sim::LoadDef> load,
           std::optional<sim::SolverDef> solver, std::optional<sim::FibreDef> fibres, std::optional<sim::EndsDef> ends) {
            const sim::EvalJob base = JobOf(design.shape, model, {std::nullopt, std::nullopt, geometry, material, load, ends, solver, fibres});
            if (const app::CharacterizeRefusal refusal = app::CharacterizeJobError(base); !refusal.reason.empty())
                throw py::value_error(refusal.Text(refusal.key));
            if (const std::string error = app::PressuresError(pressuresKpa); !error.empty()) throw py::value_error("pressures_kpa: " + error);
            if (points < 2 || points > 100) throw py::value_error(fmt::format("points: {} is out of range (2 to 100)", points));
            app::CharacteristicCurves curves;
            {
                py::gil_scoped_release release;
                curves = app::Characterize(base, pressuresKpa, points, threads);
            }
            // The table by column: names and statuses as str, numbers as float arrays (NaN where a point has none).
            const app::Table table = app::CharacteristicTable(curves);
            py::dict columns;
            for (const std::string& column : table.Columns()) {
                if (column == "curve" || column == "status") {
                    py::list text;
                    for (size_t k = 0; k < table.Rows(); ++k) text.append(table.Text(k, column));
                    columns[py::str(column)] = text;
                } else {
                    std::vector<double> values;
                    for (size_t k = 0; k < table.Rows(); ++k) values.push_back(table.Text(k, column).empty() ? NAN : table.Number(k, column));
                    columns[py::str(column)] = py::array_t<double>(static_cast<py::ssize_t>(values.size()), values.data());
                }
            }
            py::dict result;
            result["summary"] = py::module_::import("json").attr("loads")(app::CharacteristicSummary(base, curves).dump());
            result["curves"] = columns;
            return result;
        },
        py::arg("shape"), py::arg("pressures_kpa") = std::vector<double>{5, 10, 20}, py::arg("points") = 6, py::arg("threads") = 0,
        py::arg("model") = std::string(sim::Name(sim::kDefaultModel)), py::arg("geometry") = py::none(), py::arg("material") = py::none(),
        py::arg("load") = py::none(), py::arg("solver") = py::none(), py::arg("fibres") = py::none(), py::arg("ends") = py::none(),
        "A muscle's characteristic curves, as `actuator characterize` gives them: {'summary': per pressure the free stroke (%), the force "
        "at no contraction (N), the work of one stroke (mJ) and per gram of silicone (mJ/g), the isometric force (N); 'curves': the "
        "table by column (curve isobaric|isometric|free_stroke, pressure_kpa, contraction_percent, force_n, twist_deg, status)}. "
        "The load is the muscle alone (inflate, no force_n; its steps are the isometric and free-stroke curves' points).");

    BindDef<sim::MoldDef>(m, "Mold", "The mold `export` builds around a part (docs/guide/export.md): its block, sprue, vents, pins and core.",
                          app::PartOptions{}.mold);
    m.def(
        "export",
        [](const py::object& design, const py::object& outPath, const std::string& model, std::optional<sim::SimParams> params,
           std::optional<sim::MeshDef> mesh, std::optional<sim::GeometryDef> geometry, std::optional<sim::MaterialDef> material,
           std::optional<sim::FibreDef> fibres, std::optional<sim::MoldDef> mold, const std::string& wall, std::optional<double> unitMm,
           std::optional<double> wallMm, int sampling, bool fittings, std::optional<double> portMm, const std::string& format, bool ascii,
           const std::string& printerMm, const std::string& cast, std::optional<double> flangeMm, std::optional<double> threadSpacingMm,
           std::optional<double> viscosityCps, std::optional<double> potLifeMin) {
            const std::string out = FsPath(outPath, "out");
            sim::EvalJob job;
            if (py::isinstance<Evaluated>(design)) {  // a result's own design and model, as --from an archive
                if (params || mesh || geometry || material || fibres || model != std::string(sim::Name(sim::kDefaultModel)))
                    throw py::value_error("a Result carries its model and settings: pass its shape (result.shape) to give others");
                job = design.cast<const Evaluated&>().job;
            } else if (py::isinstance<Design>(design)) {
                job = JobOf(design.cast<const Design&>().shape, model, {params, mesh, geometry, material, std::nullopt, std::nullopt, std::nullopt, fibres});
            } else {
                throw py::type_error(fmt::format("shape: expected an actuator.Shape or an actuator.Result, got {}",
                                                 std::string(py::str(design.get_type().attr("__name__")))));
            }
            app::PartOptions options;
            const bool thesis = job.model == sim::ModelKind::Thesis;
            if (!thesis && (unitMm || wallMm))
                throw py::value_error(std::string(unitMm ? "unit_mm" : "wall_mm") + ": is for thesis-model designs; the membrane and shell models' size and wall are the geometry's");
            auto within = [](std::optional<double> v, const char* what, double lo, double hi) {
                if (v && !(*v >= lo && *v <= hi)) throw py::value_error(fmt::format("{}: {} is out of range ({} to {})", what, *v, lo, hi));
                return v;
            };
            options.unitMm = within(unitMm, "unit_mm", 1e-3, 1e4).value_or(options.unitMm);
            options.wallMm = within(wallMm, "wall_mm", 1e-3, 1e3).value_or(options.wallMm);
            if (sampling < 1 || sampling > 64) throw py::value_error(fmt::format("sampling: {} is out of range (1 to 64)", sampling));
            options.sampling = sampling;
            options.part.wall = EnumArgument<sim::WallSide>(wall, "wall");
            options.fittings.enabled = fittings;
            if (portMm && !fittings) throw py::value_error("port_mm: goes with fittings=True (the plug it bores)");
            options.fittings.portMm = within(portMm, "port_mm", 0.1, 1e3).value_or(options.fittings.portMm);
            if (mold) options.mold = *mold;
            app::ExportDef d;
            d.part = app::SizedPart(options, job);
            d.mold = options.mold;
            d.fittings = options.fittings;
            d.format = EnumArgument<app::SolidFormat>(format, "format");
            d.ascii = ascii;
            d.printerMm = printerMm;
            d.cast = EnumArgument<sim::CastKind>(cast, "cast");
            d.flangeMm = within(flangeMm, "flange_mm", 0.5, 50);
            d.threadSpacingMm = within(threadSpacingMm, "thread_spacing_mm", 0.5, 100);
            d.viscosityCps = within(viscosityCps, "viscosity_cps", 1, 1e7);
            d.potLifeMin = within(potLifeMin, "pot_life_min", 0.1, 1e4);
            nlohmann::json summary;
            {
                py::gil_scoped_release release;
                summary = app::ExportPart(job, d, out);
            }
            const py::object loads = py::module_::import("json").attr("loads");
            py::dict result = loads(summary.dump());
            result["manifest"] = loads(app::ReadInputFile((std::filesystem::path(out) / "manifest.json").string()));
            return result;
        },
        py::arg("shape"), py::arg("out"), py::arg("model") = std::string(sim::Name(sim::kDefaultModel)), py::arg("params") = py::none(),
        py::arg("mesh") = py::none(), py::arg("geometry") = py::none(), py::arg("material") = py::none(), py::arg("fibres") = py::none(),
        py::arg("mold") = py::none(), py::arg("wall") = std::string(sim::Name(sim::PartDef{}.wall)), py::arg("unit_mm") = py::none(),
        py::arg("wall_mm") = py::none(), py::arg("sampling") = app::PartOptions{}.sampling, py::arg("fittings") = false, py::arg("port_mm") = py::none(),
        py::arg("format") = "stl", py::arg("ascii") = false, py::arg("printer_mm") = app::ExportDef{}.printerMm, py::arg("cast") = "whole",
        py::arg("flange_mm") = py::none(), py::arg("thread_spacing_mm") = py::none(), py::arg("viscosity_cps") = py::none(),
        py::arg("pot_life_min") = py::none(),
        "Writes a design as the solids to print and cast, as `actuator export` does, into `out` (a new or empty folder): the wall, the "
        "mold's core and shells (or each half's with cast='halves', or a fibre design's two stages), mold_assembly.png, casting.md and "
        "manifest.json. `shape` is a Shape (under `model` and its settings) or a Result (its own design and model). Returns the "
        "command's summary with 'manifest' (the manifest as a dict). A design that cannot be made raises ValueError naming why, and "
        "nothing is written.");

    const char* runDoc = "Runs an experiment (a dict in the experiment-file format, or a JSON file's path) into `out` (a new or empty folder; "
                         "with resume=True, the folder an interrupted run left, which then ends exactly as an uninterrupted run) and returns "
                         "{'summary': ..., 'tables': {name: table}, 'folder': out}. Tables are pandas DataFrames when pandas is installed "
                         "(as_frame=None) or asked for (True), else NumPy structured arrays. Evaluations run on `threads`, on "
                         "evaluation servers (workers) or through a map-like callable (map: see evaluate_many); results do not depend on which. "
                         "progress=True prints the command line's progress lines on stderr.";
    auto bindRun = [&](const char* name, std::optional<app::ExperimentKind> kind, const std::string& doc) {
        m.def(
            name,
            [kind](const py::object& e, const py::object& out, int threads, const py::object& map, const py::object& workers, bool resume,
                   const py::object& asFrame, bool progress) {
                return RunExperimentFromPython(e, out, RunArgs{threads, map, workers, asFrame, resume, progress}, kind);
            },
            py::arg("experiment"), py::arg("out"), py::arg("threads") = 0, py::arg("map") = py::none(), py::arg("workers") = py::none(),
            py::arg("resume") = false, py::arg("as_frame") = py::none(), py::arg("progress") = false, doc.c_str());
    };
    bindRun("run", std::nullopt, runDoc);
    bindRun("sweep", app::ExperimentKind::Sweep, std::string("A sweep experiment; its tables are 'results' and 'evaluations'. ") + runDoc);
    bindRun("evolve", app::ExperimentKind::Evolve,
            std::string("A GA experiment; its tables are 'evaluations' and per run 'run_K_logbook', 'run_K_halloffame' and "
                        "'run_K_best_per_generation'. ") + runDoc);
    bindRun("optimize", app::ExperimentKind::Optimize,
            std::string("An optimizer experiment (pagmo); its tables are 'evaluations' and per run 'run_K_logbook' and "
                        "'run_K_halloffame' (one objective) or 'run_K_pareto_front' (several). ") + runDoc);

    m.def(
        "render",
        [](const Evaluated& e, const py::object& path, const std::string& view, double angleDeg, int width, int height, const std::string& colouring,
           int supersample, bool overwrite) -> py::object {
            std::string target;
            Finite(angleDeg, "angle_deg");
            if (!path.is_none()) {
                target = FsPath(path, "path");
                if (std::filesystem::exists(target) && !overwrite)
                    throw py::value_error("path: " + target + " exists; pass overwrite=True to replace it, or another path");
            }
            render::Image image = RenderResult(e, view, angleDeg, width, height, colouring, supersample);
            if (target.empty()) return ImageArray(std::move(image));
            app::WritePng(target, image, 6);
            return py::none();
        },
        py::arg("result"), py::arg("path") = py::none(), py::arg("view") = "before_after", py::arg("angle_deg") = 0.0,
        py::arg("width") = render::DefaultRenderDef().width, py::arg("height") = render::DefaultRenderDef().height, py::arg("colouring") = "auto",
        py::arg("supersample") = render::DefaultRenderDef().supersample, py::arg("overwrite") = false,
        "Draws a result offscreen (OSMesa): 'before_after' (the rest mesh and the loaded one) or 'turntable' (the loaded mesh turned "
        "angle_deg about its axis). Returns an (H, W, 4) uint8 RGBA array, or writes a PNG to `path` (whole or not at all) and returns None.");

    py::class_<Record>(m, "Record", "One evaluation from an archive (DIR/evaluations.capnp).")
        .def_property_readonly("id", [](const Record& r) { return r.record.id; }, "its place in the archive, from 0 (the evaluation id)")
        .def_property_readonly("experiment", [](const Record& r) { return r.record.experiment; })
        .def_property_readonly("run", [](const Record& r) { return r.record.run; }, "GA or optimizer run, 1-based; 0 for sweeps and lists")
        .def_property_readonly("generation", [](const Record& r) { return r.record.generation; }, "-1 for sweeps and lists")
        .def_property_readonly("role", [](const Record& r) { return std::string(sim::Name(r.record.role)); })
        .def_property_readonly("label", [](const Record& r) { return r.record.label; })
        .def_property_readonly("result", [](const Record& r) { return Evaluated{r.record.job, r.record.result}; })
        .def("_repr_png_", [](const Record& r) { return ReprPng(Evaluated{r.record.job, r.record.result}); },
             "its result's before-and-after figure as PNG bytes (None when read with meshes=False)")
        .def("__repr__", [](const Record& r) {
            return fmt::format("<actuator.Record {} {} {} fitness={:.6g}>", r.record.id, sim::Name(r.record.role), r.record.label, r.record.result.fitness);
        });
    py::class_<ArchiveIterator>(m, "_ArchiveIterator")
        .def("__iter__", [](ArchiveIterator& it) -> ArchiveIterator& { return it; })
        .def("__next__", &ArchiveIterator::Next);
    m.def(
        "open_archive",
        [](const py::object& where, bool meshes) {
            const std::string path = FsPath(where, "path");
            app::ScanArchive(path, false, [](app::ArchiveRecord&&) { return false; });  // refuses a missing file or a non-archive now
            return ArchiveIterator(path, meshes);
        },
        py::arg("path"), py::arg("meshes") = true,
        "The records of an archive (a run folder's evaluations.capnp), in order, read a few at a time; meshes=False skips the positions "
        "(fast listing). A torn tail (a run cut off while writing) ends the records; a damaged record raises ValueError.");
    m.def(
        "cli",
        [](const py::args& args) {
            std::vector<std::string> argv{"actuator"};
            for (const auto& a : args) argv.push_back(FsPath(py::reinterpret_borrow<py::object>(a), "argument"));
            std::string names;
            for (const app::Command& c : app::Commands()) names += (names.empty() ? "" : ", ") + std::string(c.name);
            if (argv.size() < 2) throw py::value_error("cli: give a command (" + names + ") and its arguments, as after `actuator`");
            const app::Command* command = app::FindCommand(argv[1]);
            if (!command) throw py::value_error("cli: unknown command '" + argv[1] + "' (choose " + names + ")");
            std::vector<char*> pointers;
            for (auto& a : argv) pointers.push_back(a.data());
            pointers.push_back(nullptr);
            // The command's standard output is its result (JSON for most): captured, as a pipe would.
            struct Capture {
                std::ostringstream text;
                std::streambuf* saved = std::cout.rdbuf(text.rdbuf());
                ~Capture() { std::cout.rdbuf(saved); }
            };
            int code = 0;
            std::string out;
            {
                py::gil_scoped_release release;
                Capture capture;
                code = command->run(static_cast<int>(argv.size()), pointers.data(), 2);
                out = capture.text.str();
            }
            py::dict result;
            result["exit_code"] = code;
            result["stdout"] = out;
            return result;
        },
        "Runs any `actuator` command in this process with the command line's arguments, e.g. cli('reproduce', '--quick', '--out', "
        "'thesis/') or cli('material', 'fit', 'curve.csv', '--out', 'mix.json'): {'exit_code': ..., 'stdout': its standard output (JSON "
        "for most)}. Bad input raises ValueError with the command's message (where the command line exits with code 2); progress goes "
        "to stderr. For the commands the module has functions for (evaluate, characterize, export, run, render, ...) those are the "
        "better way: they take and give Python objects.");
    m.def("_evaluate_job_bytes", &pybinding::EvaluateJobBytes, py::arg("job"));
    {  // actuator.optuna: Optuna objectives (python/optuna_adapter.py; imports optuna only when a trial runs)
        static const char* const source =
#include "optuna_adapter.inc"
            ;
        py::module_ adapter = m.def_submodule("optuna");
        py::exec(source, adapter.attr("__dict__"));
        const py::module_ ast = py::module_::import("ast");
        adapter.attr("__doc__") = ast.attr("get_docstring")(ast.attr("parse")(source));
    }
    // What a map evaluates: a plain Python function, so that pickle (process pools) sends it by name
    // (pybind11's own functions do not pickle).
    // The public functions become plain Python functions around the bindings too, so that
    // pool.map(actuator.evaluate, ...) works; their help and signatures stay.
    py::exec(R"(
def _evaluate_job(job):
    """One job's bytes in, its result's bytes out: what evaluate_many and the experiments hand a map."""
    return _evaluate_job_bytes(job)

def _picklable(bound):
    import functools
    @functools.wraps(bound)
    def function(*args, **kwargs):
        return bound(*args, **kwargs)
    function.__module__, function.__qualname__ = "actuator", bound.__name__
    return function

for _name in ("cylinder", "sine", "abs_sine", "bspline", "free_xy", "evaluate", "evaluate_many", "characterize", "export", "run", "sweep",
              "evolve", "optimize", "render", "open_archive", "cli"):
    globals()[_name] = _picklable(globals()[_name])
del _name
)",
             m.attr("__dict__"));
}
