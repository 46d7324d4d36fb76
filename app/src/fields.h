// Every user-settable field of the models' def structs, listed once: its key in experiment files
// and JSON outputs (the command-line option is the key with '-' for '_'), what it means with its
// unit, and its valid range. The default is whatever the def struct holds. Visitors read the fields
// from JSON (experiment.cpp), bind them to options (cli.cpp) and write them out (json_out.cpp).
//
// A visitor provides:
//   Integer(key, int& value, help, min, max)
//   Number(key, double& value, help, min, max)
//   Enum(key, E& value, help)            (the names come from sim::EnumNames<E>)
// Visiting a const def hands out const references (for writing).
#pragma once

#include <limits>

#include "sim/mesh.h"
#include "sim/solver.h"

namespace app {

constexpr double kUnbounded = std::numeric_limits<double>::max();

// The helix of the `thesis` model.
template <class Def, class Visitor>
void VisitFields(Def& mesh, Visitor&& v) requires std::is_same_v<std::remove_const_t<Def>, sim::MeshDef> {
    v.Integer("resolution", mesh.resolution, "vertices per turn of the helix", sim::kMinResolution, 4096);
    v.Integer("turns", mesh.turns, "turns of the helix (two clamped at each end)", sim::kMinTurns, 4096);
}

// The `thesis` model's constants (MODEL.md, "One iteration").
template <class Def, class Visitor>
void VisitFields(Def& p, Visitor&& v) requires std::is_same_v<std::remove_const_t<Def>, sim::SimParams> {
    v.Integer("iterations", p.iterations, "relaxation steps; the fitness is read after the last", 0, sim::kMaxIterations);
    v.Enum("load", p.load, "inflation pressure, the stretch test's pull on the end turns, or no load");
    v.Number("spring_constant", p.springConstant, "spring stiffness k (force per unit of stretch)", 0, kUnbounded);
    v.Number("pressure_scale", p.pressureScale, "inflation scale c_p on the cross-product force", 0, kUnbounded);
    v.Number("pull_force", p.pullForce, "stretch load c_pull on each end-turn vertex", 0, kUnbounded);
    v.Number("step_scale", p.stepScale, "displacement per unit force per iteration (c_step)", 0, kUnbounded);
    v.Number("divergence_limit", p.divergenceLimit, "a coordinate beyond this (mesh units) ends the run as 'diverged'", 1e-300, kUnbounded);
    v.Enum("precision", p.precision, "solver arithmetic; float is about twice as fast and within 0.005 of double in fitness");
}

// "spring_constant" -> "--spring-constant".
inline std::string OptionName(const char* key) {
    std::string name = std::string("--") + key;
    for (char& c : name)
        if (c == '_') c = '-';
    return name;
}

}  // namespace app
