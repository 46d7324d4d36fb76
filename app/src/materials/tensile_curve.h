// A uniaxial tensile test as a CSV table (docs/guide/materials.md): one header row naming an
// engineering strain column and an engineering stress column, any rows of notes before it (a test
// machine's preamble), ',' or ';' between fields. The stress's unit comes from its column name
// ("Stress (MPa)", "stress_kpa") or from the caller; strain is a fraction unless its name says "%".
// An optional "specimen" column tells several specimens apart; columns of true strain or stress
// are ignored.
#pragma once

#include <string>
#include <vector>

#include "sim/material_fit.h"

namespace app {

enum class StressUnit { FromHeader, Kpa, Mpa };

struct TensileCurve {
    std::vector<sim::TensilePoint> points;  // stress in kPa
    std::string strainColumn, stressColumn, specimenColumn;
    std::string unit;                       // "kPa" or "MPa", as read
    int specimens = 1;
};

// Reads the curve. Refuses with one line naming the row (1-based, as an editor counts): a field that
// is not a number, a negative strain or stress, strain that falls within a specimen, a missing unit,
// fewer than two points. Throws UsageError.
TensileCurve ReadTensileCurve(const std::string& path, StressUnit unit);

}  // namespace app
