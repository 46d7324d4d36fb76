// Conversions between sim's plain data and the Cap'n Proto schema (sim/actuator.capnp), shared by
// archives and the evaluation server, so that every field is converted in one place.
#pragma once

#include "actuator.capnp.h"
#include "sim/search.h"
#include "sim/solver.h"

namespace app {

namespace schema = actuator::schema;

void SetMesh(schema::Mesh::Builder out, const sim::Positions& p);  // float32
sim::Positions GetMesh(schema::Mesh::Reader in);                     // throws on ragged lists
void SetExactMesh(schema::ExactMesh::Builder out, const sim::Positions& p);
sim::Positions GetExactMesh(schema::ExactMesh::Reader in);
void SetSplines(capnp::List<schema::Spline>::Builder out, const std::vector<std::vector<double>>& splines);
std::vector<std::vector<double>> GetSplines(capnp::List<schema::Spline>::Reader in);
void SetShape(schema::Shape::Builder out, const sim::Shape& shape);
sim::Shape GetShape(schema::Shape::Reader in);
void SetParams(schema::SimParams::Builder out, const sim::SimParams& params);
sim::SimParams GetParams(schema::SimParams::Reader in);
schema::Status ToSchema(sim::Status status);
sim::Status FromSchema(schema::Status status);

}  // namespace app
