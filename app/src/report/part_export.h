// A design as the files that go to the printer and the bench (what `actuator export` and Python's
// actuator.export write): the wall as a closed solid, the mold's core and shells (or each half's, or
// a fibre design's two stages), the pictures, manifest.json and casting.md. Everything is built and
// checked before the first file is written: a design that cannot be made writes nothing.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "formats/solid_io.h"
#include "sim/batch.h"
#include "sim/casting.h"
#include "sim/solid.h"

namespace app {

struct ExportDef {
    sim::PartDef part;           // sized for the job (options/part_options.h: PartDefOf or SizedPart)
    sim::MoldDef mold;
    sim::FittingDef fittings;
    SolidFormat format = SolidFormat::Stl;
    bool ascii = false;                    // STL only
    std::string printerMm = "220x220x250";  // the build volume each printed part is checked against, WxDxH mm
    sim::CastKind cast = sim::CastKind::Whole;
    // Given or not: a value given where it has no effect is refused.
    std::optional<double> flangeMm;        // --cast halves: the bonding flange, mm (default below)
    std::optional<double> threadSpacingMm;  // fibre designs: the threads of a family at most this far apart, mm
    std::optional<double> viscosityCps;    // the mixed silicone's, for the fill time (default: the preset's bulletin)
    std::optional<double> potLifeMin;
    nlohmann::json from;                   // {"archive": ..., "index": ...} for a stored design, else null

    static constexpr double defaultFlangeMm = 3;
    static constexpr double defaultThreadSpacingMm = 3;
};

// Writes the part's files into `out` (new or empty; created) and returns the command's summary
// ({"out", "silicone_volume_mm3", "files", "seconds", warnings}). Throws UsageError naming why a
// design cannot be made (nothing written) and OutputError when the disk refuses (nothing kept).
nlohmann::json ExportPart(const sim::EvalJob& job, const ExportDef& d, const std::string& out);

}  // namespace app
