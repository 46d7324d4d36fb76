// How an evaluation ended: every model reports one of these, and a failed evaluation is never a
// silent zero (numerical failure is a status in the result, never an exception or a crash).
#pragma once

#include "sim/names.h"

namespace sim {

// How an evaluation ended. Every model reports one; a failed evaluation is never a silent zero.
enum class Status {
    Ok,               // finished: the fitness and every output are meaningful
    NaN,              // thesis: a position became NaN or infinite
    Diverged,         // thesis: a position left the divergence bound: the mesh ran away
    LimitPoint,       // shell models: past the pressure maximum (the actuator balloons)
    NotConverged,     // shell models: Newton did not reach equilibrium within its budget
    NonFinite,        // shell models: energy or forces became NaN or infinite
    SelfIntersection, // shell models: the wall passes through itself at equilibrium
    InvalidGeometry,  // shell models: the rest shape cannot be built (radius <= 0, self-intersecting)
    OverStretched,    // shell models: the wall stretches past the material's allowed stretch
    MaterialUnstable, // shell models: the wall stretches past where the material's law is Drucker-stable
    OutsideEnvelope,  // shell models: the rest design lies outside the def's envelope (too wide or too heavy); nothing simulated
    BudgetExceeded,   // shell models: the evaluation's Newton iterations ran past SolverDef::newtonBudget (a design too costly to trust)
};

template <>
struct EnumNames<Status> {
    static constexpr std::array<std::pair<Status, const char*>, 12> table{{
        {Status::Ok, "ok"},
        {Status::NaN, "nan"},
        {Status::Diverged, "diverged"},
        {Status::LimitPoint, "limit-point"},
        {Status::NotConverged, "not-converged"},
        {Status::NonFinite, "non-finite"},
        {Status::SelfIntersection, "self-intersection"},
        {Status::InvalidGeometry, "invalid-geometry"},
        {Status::OverStretched, "over-stretched"},
        {Status::MaterialUnstable, "material-unstable"},
        {Status::OutsideEnvelope, "outside-envelope"},
        {Status::BudgetExceeded, "budget-exceeded"},
    }};
};

}  // namespace sim
