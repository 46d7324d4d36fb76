// Conversions between sim's plain data and the Cap'n Proto schema (app/schema/actuator.capnp),
// shared by archives and the evaluation server: every field is converted in this one place. The
// schema's enums list their values in sim's order, so enums convert by value (checked below).
#pragma once

#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>

#include "actuator.capnp.h"
#include "sim/batch.h"
#include "sim/search.h"
#include "sim/solver.h"

namespace app {

namespace schema = actuator::schema;

// Meshes: float32 when that is exact, else float64 (Mesh); always float64 (ExactMesh, the wire).
void SetMesh(schema::Mesh::Builder out, const sim::Positions& p);
sim::Positions GetMesh(schema::Mesh::Reader in);  // throws std::runtime_error on ragged lists
void SetExactMesh(schema::ExactMesh::Builder out, const sim::Positions& p);
sim::Positions GetExactMesh(schema::ExactMesh::Reader in);

void SetShape(schema::Shape::Builder out, const sim::Shape& shape);
sim::Shape GetShape(schema::Shape::Reader in);
void SetParams(schema::SimParams::Builder out, const sim::SimParams& params);
sim::SimParams GetParams(schema::SimParams::Reader in);  // throws on an enum value this build does not know

void SetShellDef(schema::ShellDef::Builder out, const sim::ShellDef& def);
sim::ShellDef GetShellDef(schema::ShellDef::Reader in);  // throws std::runtime_error on a name this build does not know

// The numbers of a result (status, fitness, ..., the shell models' outputs), without its meshes.
void SetResultNumbers(schema::EvalResult::Builder out, const sim::SimResult& result, sim::ModelKind model);
void GetResultNumbers(schema::EvalResult::Reader in, sim::SimResult& result);

// A whole result as evaluation servers send it: its numbers and both meshes at full precision, so
// it equals a local run's bit for bit (the shell models' per-step positions stay behind).
void SetResponse(schema::EvalResponse::Builder out, const sim::SimResult& result, sim::ModelKind model);
sim::SimResult GetResponse(schema::EvalResponse::Reader in);

// One job and one result as self-contained bytes (a Cap'n Proto EvalRequest / EvalResponse message):
// what the Python module hands to a `map` (Dask, concurrent.futures) to evaluate anywhere.
std::string JobBytes(const sim::EvalJob& job);
sim::EvalJob JobFromBytes(const std::string& bytes);  // throws std::runtime_error on bytes that do not decode
std::string ResultBytes(const sim::SimResult& result, sim::ModelKind model);
sim::SimResult ResultFromBytes(const std::string& bytes);  // throws std::runtime_error likewise

// A job into any struct that has its fields (EvalRequest on the wire, Evaluation in archives): the
// shape, the model, and the model's settings (the thesis model's parameters and mesh size, or the
// shell def). Records from before the shell models read as thesis jobs.
// Each def into and out of its own struct (a new def adds its pair of overloads; without them the
// visits below do not compile).
template <class Builder>
void SetDef(Builder& out, const sim::ThesisDef& def) {
    SetParams(out.initParams(), def.params);
    auto size = out.initMeshSize();
    size.setResolution(static_cast<std::uint32_t>(def.mesh.resolution));
    size.setTurns(static_cast<std::uint32_t>(def.mesh.turns));
}
template <class Builder>
void SetDef(Builder& out, const sim::ShellDef& def) { SetShellDef(out.initShell(), def); }
template <class Reader>
void GetDef(Reader& in, sim::ThesisDef& def) {
    def.params = GetParams(in.getParams());
    def.mesh = sim::MeshDef{static_cast<int>(std::min<std::uint32_t>(in.getMeshSize().getResolution(), 1u << 30)),
                            static_cast<int>(std::min<std::uint32_t>(in.getMeshSize().getTurns(), 1u << 30))};
}
template <class Reader>
void GetDef(Reader& in, sim::ShellDef& def) { def = GetShellDef(in.getShell()); }

template <class Builder>
void SetJob(Builder out, const sim::EvalJob& job) {
    SetShape(out.initShape(), job.shape);
    out.setModel(static_cast<schema::ModelKind>(static_cast<int>(job.model)));
    std::visit([&](const auto& def) { SetDef(out, def); }, job.def);
}
template <class Reader>
sim::EvalJob GetJob(Reader in) {
    sim::EvalJob job;
    job.shape = GetShape(in.getShape());
    const int model = static_cast<int>(in.getModel());
    if (model >= static_cast<int>(sim::EnumNames<sim::ModelKind>::table.size()))
        throw std::runtime_error("unknown model " + std::to_string(model) + " (written by a newer version?)");
    job.SetModel(static_cast<sim::ModelKind>(model));
    std::visit([&](auto& def) { GetDef(in, def); }, job.def);
    return job;
}

}  // namespace app
