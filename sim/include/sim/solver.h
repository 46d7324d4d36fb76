// Evaluation of one shape: build the mesh, relax it under a load for a number of iterations
// (docs/models/thesis.md, "One iteration"), and measure the contraction (docs/models/thesis.md, "Fitness").
//
// Evaluate() and Simulate() are pure functions of their arguments: safe to call from many threads.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "sim/mesh.h"
#include "sim/names.h"
#include "sim/shape.h"
#include "sim/result.h"
#include "sim/status.h"

namespace sim {

enum class Load {
    Inflate,  // cross-product pressure on every free vertex (the thesis's inflation)
    Stretch,  // pull the bottom turn down and the top turn up; no inflation (thesis chapter 6)
    None,     // springs and clamps only: a rest mesh must stay exactly where it is
};

enum class Precision {
    Float,   // the fast path; its fitness stays within 0.005 of Double (tests/sim)
    Double,  // reference
};


// Parameters of the `thesis` model. Defaults are the thesis's Table 3.2 values.
struct SimParams {
    int iterations = 10000;          // relaxation steps; the fitness is read after the last
    Load load = Load::Inflate;
    double springConstant = 0.01;    // k: force per unit of stretch
    double pressureScale = 0.005;    // c_p: scales the cross-product inflation force
    double pullForce = 0.005;        // c_pull: force on each end-turn vertex under Load::Stretch
    double stepScale = 0.07;         // c_step: displacement per unit of force (overdamped update)
    double divergenceLimit = 1.0e4;  // |coordinate| beyond this (mesh units) ends the run as Diverged;
                                     // checked after every iteration
    Precision precision = Precision::Float;
};
SimParams DefaultSimParams();

// Empty when the parameters are usable; otherwise what is wrong, for a user to read.
std::string SimParamsError(const SimParams& params);

// The largest iteration count any command accepts: about 15 minutes of a 30x30 evaluation.
constexpr int kMaxIterations = 100'000'000;


// Called every `interval` iterations (and with iteration 0 before the first) with the current
// positions; used for time-lapse frames. Return false to stop the run early.
struct SimObserver {
    int interval = 0;  // 0: never called
    std::function<bool(int iteration, const Positions& positions)> onSnapshot;
};

// Relaxes an initial mesh. Precondition: initial has VertexCount(def) finite entries.
SimResult Simulate(const Positions& initial, const MeshDef& def, const SimParams& params,
                   const SimObserver* observer = nullptr);

// Builds the shape's mesh and relaxes it. Precondition: ShapeError(shape, def) is empty.
SimResult Evaluate(const Shape& shape, const MeshDef& def, const SimParams& params);

// The thesis's contraction measure: mean rise of the bottom turn plus mean fall of the top turn.
double Fitness(const Positions& initial, const Positions& final, const MeshDef& def);

// FNV-1a over the bit patterns of all coordinates: equal hashes mean bit-identical meshes.
std::uint64_t PositionsHash(const Positions& positions);

template <>
struct EnumNames<Load> {
    static constexpr std::array<std::pair<Load, const char*>, 3> table{{
        {Load::Inflate, "inflate"}, {Load::Stretch, "stretch"}, {Load::None, "none"}}};
};
template <>
struct EnumNames<Precision> {
    static constexpr std::array<std::pair<Precision, const char*>, 2> table{{{Precision::Float, "float"}, {Precision::Double, "double"}}};
};

}  // namespace sim
