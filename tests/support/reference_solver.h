// A deliberately plain implementation of docs/models/thesis.md, written independently of sim/src/solver.cpp:
// an edge list in doubles, one vertex struct per vertex, forces scattered per spring. It is the
// "straightforward" baseline the benchmark compares against and the oracle the solver test checks.
#pragma once

#include "sim/mesh.h"
#include "sim/solver.h"

namespace reference {

sim::Positions Relax(const sim::Positions& initial, const sim::MeshDef& def, const sim::SimParams& params);

}  // namespace reference
