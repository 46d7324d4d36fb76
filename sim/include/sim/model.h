// A model is a row in one table. An evaluation job is a design and a model with its def; everything
// a caller asks of a model (evaluate the job, check it, the surface its meshes are drawn on, an
// estimate of its work, how its fitness is named) is asked of the model's row, never by testing the
// kind. Adding a model: its folder in sim/src/, its def in the ModelDef variant, one row in
// model.cpp, its fields (fields.h) and its outputs (result.h); docs/architecture.md walks through it.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "sim/shape.h"
#include "sim/shell.h"
#include "sim/solver.h"
#include "sim/surface.h"

namespace sim {

// The thesis model's def: its helix and its constants.
struct ThesisDef {
    MeshDef mesh = DefaultMeshDef();
    SimParams params = DefaultSimParams();
};

// The model a new study gets when it names none: the command line's --model, experiment files
// without a "model" block, Python's model=. The thesis's own files and examples name `thesis`.
constexpr ModelKind kDefaultModel = ModelKind::Shell;

// Each model's def; membrane and shell share ShellDef (bending on or off).
using ModelDef = std::variant<ThesisDef, ShellDef>;

// A physical model under a negative pressure: its walls collapse onto each other (the thesis model
// has no vacuum).
inline bool UnderVacuum(const ModelDef& def) {
    const auto* shell = std::get_if<ShellDef>(&def);
    return shell && UnderVacuum(shell->load);
}

// One evaluation: a design under a model. `def` holds the model's def (ThesisDef for the thesis
// model, ShellDef for membrane and shell).
struct EvalJob {
    Shape shape;
    ModelKind model = ModelKind::Thesis;
    ModelDef def = ThesisDef{};

    // Sets the model, with its default def unless the job already holds a def of that kind.
    void SetModel(ModelKind kind);  // model.cpp: the row gives the default def

    // The model's def. The const forms require the def to be the model's; the others make it so
    // (a job being built: set `model`, then fill its def).
    const ThesisDef& Thesis() const { return Get<ThesisDef>(); }
    const ShellDef& Shell() const { return Get<ShellDef>(); }
    ThesisDef& Thesis() { return Make<ThesisDef>(ThesisDef{}); }
    ShellDef& Shell() { return Make<ShellDef>(DefaultShellDef()); }

private:
    template <class D>
    const D& Get() const {
        if (const D* d = std::get_if<D>(&def)) return *d;
        throw std::logic_error("an evaluation job asked for a def its model does not have");
    }
    template <class D>
    D& Make(D fresh) {
        if (!std::holds_alternative<D>(def)) def = std::move(fresh);
        return std::get<D>(def);
    }
};

// What a result says, visited by name with its unit: JSON, the evaluation table, Python and the
// report are all written from this one list (VisitOutputs), so a name means one thing everywhere.
class OutputVisitor {
public:
    virtual ~OutputVisitor() = default;
    virtual void Number(const char* name, const char* unit, double value) = 0;  // NaN: the evaluation has none
    virtual void Count(const char* name, long long value) = 0;
    virtual void Curve(const char* name, const char* unit, const std::vector<double>& values) = 0;  // one per load step
};

// A model's row: what it does and how its numbers are named.
struct Model {
    ModelKind kind;
    const char* name;
    SimResult (*evaluate)(const EvalJob& job);      // pure, thread-safe
    std::string (*error)(const EvalJob& job);       // empty when the job can run; else why not
    Surface (*surface)(const EvalJob& job);         // what its meshes are drawn on
    int (*vertices)(const EvalJob& job);            // of its meshes
    MeshDef (*designMesh)(const EvalJob& job);      // what a design is given on: per turn (thesis helix) or ring x turns or rings
    std::uint64_t (*work)(const EvalJob& job);      // an estimate of its cost (server limits): vertex-iterations
    ModelDef (*defaultDef)();                       // the def a job of this model starts from
    std::string (*meshText)(const EvalJob& job);    // its meshes' size and vertex order, for file headers
    const char* (*loadName)(const EvalJob& job);    // the load it applies ("inflate", "stretch", "blocked", ...)
    int (*curvePoints)(const EvalJob& job);         // points of its load curve per result (0: none)
    // Its own outputs (beside fitness, contraction and time, which every model has), in order.
    void (*outputs)(const SimResult& result, const EvalJob& job, OutputVisitor& visitor);
    const char* fitnessLabel;                       // what its fitness is, with its unit
    const char* lengthUnit;                         // of its positions: "mesh units" or "mm"
    bool physical;                                  // silicone in mm, kPa and N at equilibrium (not the thesis's snapshot)
};

const Model& ModelOf(ModelKind kind);
inline const Model& ModelOf(const EvalJob& job) { return ModelOf(job.model); }

// Every output of a result: status aside, "fitness" and "contraction_percent" (NaN unless ok), the
// model's own, then "elapsed_ms".
void VisitOutputs(const SimResult& result, const EvalJob& job, OutputVisitor& visitor);
// Every model's output names that are one number each (no curves), in table order, each once: the
// columns a table of evaluations of any model has. Timings are left out (`withTime` false) where a
// table must read the same on every run.
std::vector<std::string> OutputNames(bool withTime);
// The one-number output names of these jobs' models (a table of those jobs' results), in order, each once.
std::vector<std::string> OutputNames(const std::vector<EvalJob>& jobs, bool withTime);

// The job's evaluation under its model.
inline SimResult Evaluate(const EvalJob& job) { return ModelOf(job).evaluate(job); }
// Empty when the job can be evaluated; otherwise what is wrong (shape, parameters, mesh).
std::string JobError(const EvalJob& job);
// The mesh a job's design is given on (free-xy offsets, OBJ vertices, genomes): the thesis helix, or
// the membrane and shell models' rings (their caps' centres aside).
inline MeshDef DesignMeshOf(const EvalJob& job) { return ModelOf(job).designMesh(job); }
// The triangles and edges a job's meshes are drawn with.
inline Surface SurfaceOf(const EvalJob& job) { return ModelOf(job).surface(job); }

}  // namespace sim
