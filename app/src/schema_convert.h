// Conversions between sim's plain data and the Cap'n Proto schema (app/schema/actuator.capnp),
// shared by archives and the evaluation server: every field is converted in this one place. The
// schema's enums list their values in sim's order, so enums convert by value (checked below).
#pragma once

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

// The numbers of a result (status, fitness, ...), without its meshes.
void SetResultNumbers(schema::EvalResult::Builder out, const sim::SimResult& result);
void GetResultNumbers(schema::EvalResult::Reader in, sim::SimResult& result);

// A job's shape, parameters and mesh size into any struct that has those three fields
// (EvalRequest on the wire, Evaluation in archives).
template <class Builder>
void SetJob(Builder out, const sim::EvalJob& job) {
    SetShape(out.initShape(), job.shape);
    SetParams(out.initParams(), job.params);
    auto size = out.initMeshSize();
    size.setResolution(static_cast<std::uint32_t>(job.mesh.resolution));
    size.setTurns(static_cast<std::uint32_t>(job.mesh.turns));
}
template <class Reader>
sim::EvalJob GetJob(Reader in) {
    sim::EvalJob job;
    job.shape = GetShape(in.getShape());
    job.params = GetParams(in.getParams());
    job.mesh = sim::MeshDef{static_cast<int>(std::min<std::uint32_t>(in.getMeshSize().getResolution(), 1u << 30)),
                            static_cast<int>(std::min<std::uint32_t>(in.getMeshSize().getTurns(), 1u << 30))};
    return job;
}

}  // namespace app
