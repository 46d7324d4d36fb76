// How a design becomes a part, from the command line: shared by `export` (which writes the solids)
// and `render --solid` (which draws them). Thesis-model designs are scaled by --unit-mm with a
// --wall-mm wall; the membrane and shell models use their geometry options.
#pragma once

#include <string>
#include <vector>

#include "options/cli.h"
#include "sim/batch.h"
#include "sim/solid.h"

namespace app {

struct PartOptions {
    double unitMm = 5;                     // thesis designs: millimetres per design unit
    double wallMm = sim::PartDef{}.thicknessMm;  // thesis designs: the wall
    int sampling = 4;                      // surface samples per simulation-mesh edge
    sim::PartDef part;                     // its wall side is bound to --wall
    sim::MoldDef mold;                     // bound to the mold options
    sim::FittingDef fittings;              // bound to --fittings and --port-mm
};

// Adds --wall, --unit-mm, --wall-mm, --sampling under "Part" and the mold's options under "Mold".
void AddPartOptions(Cli& cli, PartOptions& options);

// The options of the part (--wall, --unit-mm, --wall-mm, --sampling, --fittings, --port-mm) and of
// the mold (--margin-mm, ...), to refuse them where no solid is made or no mold drawn.
std::vector<std::string> PartOptionNames();
std::vector<std::string> MoldOptionNames();

// The part for a job's design: its size from the model, sampled --sampling times finer than the
// model's mesh. Refuses the thesis-only options under the other models. Throws UsageError.
sim::PartDef PartDefOf(const Cli& cli, const PartOptions& options, const sim::EvalJob& job);
// The same without a command line (Python): unit_mm and wall_mm are the thesis model's alone.
sim::PartDef SizedPart(const PartOptions& options, const sim::EvalJob& job);

// The silicone the job's part is cast in (its mass in the manifest): the model's material, or the
// default one for a model that has none (thesis).
sim::MaterialDef CastMaterialOf(const sim::EvalJob& job);

// The solids, or UsageError naming why the design cannot be made.
sim::PartSolids BuildSolids(const sim::EvalJob& job, const sim::PartDef& part, const sim::MoldDef& mold, const sim::FittingDef& fittings = {});

}  // namespace app
