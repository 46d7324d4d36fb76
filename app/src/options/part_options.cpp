#include "options/part_options.h"

#include "support/errors.h"
#include "sim/shell.h"

namespace app {

void AddPartOptions(Cli& cli, PartOptions& o) {
    cli.Group("Part");
    cli.Enum("--wall", o.part.wall, "centred: half the wall each side of the rest surface; outward: the rest surface is the wall's inside");
    cli.Number("--unit-mm", o.unitMm, "thesis-model designs: millimetres per design unit (radius 1, length 30 turns)", 1e-3, 1e4)->default_str("5");
    cli.Number("--wall-mm", o.wallMm, "thesis-model designs: wall thickness, mm (membrane and shell: --thickness-mm)", 1e-3, 1e3)->default_str("1");
    cli.Integer("--sampling", o.sampling,
                "surface samples per simulation-mesh edge, around and along (smooth designs look faceted at 30 x 30); the helix's "
                "--resolution stays the simulation mesh's",
                1, 64)
        ->default_str("4");
    cli.Flag("--fittings", o.fittings.enabled, "also rigid end fittings: a plug for each end (insert and collar), the bottom one bored for the air line");
    cli.Number("--port-mm", o.fittings.portMm, "with --fittings: the bottom plug's through hole, diameter", 0.1, 1e3)->default_str("4");
    cli.Group("Mold");
    cli.Fields(o.mold);
}

std::vector<std::string> PartOptionNames() { return {"--wall", "--unit-mm", "--wall-mm", "--sampling", "--fittings", "--port-mm"}; }

namespace {
struct MoldOptionNameCollector {
    std::vector<std::string>& names;
    void Number(const char* key, const double&, const char*, double, double) { names.push_back(OptionName(key)); }
    template <class E>
    void Enum(const char* key, const E&, const char*) {
        names.push_back(OptionName(key));
    }
};
}  // namespace

std::vector<std::string> MoldOptionNames() {
    std::vector<std::string> names;
    const sim::MoldDef mold;
    VisitFields(mold, MoldOptionNameCollector{names});
    return names;
}

namespace {

// [SECTION] Each model's part: its size from the def (a new def adds its overload). A thesis design
// is in mesh units: --unit-mm is one of them, --wall-mm its wall.
void SizePart(const PartOptions& o, const sim::ThesisDef& def, sim::PartDef& part) {
    part.radiusMm = o.unitMm;
    part.lengthMm = o.unitMm * def.mesh.turns;
    part.thicknessMm = o.wallMm;
    part.clampFraction = static_cast<double>(sim::kClampedTurns) / def.mesh.turns;
    part.angularSamples = 8 * ((def.mesh.resolution * o.sampling + 7) / 8);
    part.axialSamples = def.mesh.turns * o.sampling + 1;
    part.helixAngles = true;
}
void SizePart(const PartOptions& o, const sim::ShellDef& def, sim::PartDef& part) {
    const sim::GeometryDef& g = def.geometry;
    // The part samples the shape evenly, as many rows as evenly spaced rings: the model's grading
    // toward the clamps is for the wall's bending there, not for the shape.
    sim::GeometryDef evenly = g;
    evenly.edgeSpacingMm = 0;
    const int rings = sim::RingCount(evenly);
    part.radiusMm = g.radiusMm;
    part.lengthMm = g.lengthMm;
    part.thicknessMm = g.thicknessMm;
    part.clampFraction = g.clampMm / g.lengthMm;
    part.angularSamples = 8 * ((g.ringVertices * o.sampling + 7) / 8);
    part.axialSamples = (rings - 1) * o.sampling + 1;
}

// The silicone it is cast in: the thesis model has none of its own, so the default.
sim::MaterialDef CastMaterial(const sim::ThesisDef&) { return sim::DefaultShellDef().material; }
sim::MaterialDef CastMaterial(const sim::ShellDef& def) { return def.material; }

}  // namespace

sim::PartDef PartDefOf(const Cli& cli, const PartOptions& o, const sim::EvalJob& job) {
    if (cli.Given("--port-mm") && !o.fittings.enabled) throw UsageError("--port-mm goes with --fittings (the plug it bores)");
    if (cli.Given("--drain-mm") && o.mold.core != sim::CoreKind::Lost) throw UsageError("--drain-mm applies to --core lost (a rigid core has no drain)");
    if (job.model != sim::ModelKind::Thesis) {
        cli.RefuseIfGiven("--unit-mm", "is for thesis-model designs; the membrane and shell models' size is --radius-mm and --length-mm");
        cli.RefuseIfGiven("--wall-mm", "is for thesis-model designs; the membrane and shell models' wall is --thickness-mm");
    }
    return SizedPart(o, job);
}

sim::PartDef SizedPart(const PartOptions& o, const sim::EvalJob& job) {
    sim::PartDef part = o.part;
    std::visit([&](const auto& def) { SizePart(o, def, part); }, job.def);
    return part;
}

sim::MaterialDef CastMaterialOf(const sim::EvalJob& job) {
    return std::visit([](const auto& def) { return CastMaterial(def); }, job.def);
}

sim::PartSolids BuildSolids(const sim::EvalJob& job, const sim::PartDef& part, const sim::MoldDef& mold, const sim::FittingDef& fittings) {
    sim::PartSolids solids;
    // Designs defined per vertex are measured on their rest mesh; the others have a profile.
    sim::RadiusField measured;
    if (std::holds_alternative<sim::FreeXYShape>(job.shape) || std::holds_alternative<sim::MeshShape>(job.shape)) {
        std::string error;
        measured = sim::MeasuredRadiusField(job, &error);
        if (!measured) throw UsageError("cannot make this design: " + error);
    }
    if (const std::string error = sim::BuildPartSolids(job.shape, part, mold, &solids, fittings, measured); !error.empty())
        throw UsageError("cannot make this design: " + error);
    return solids;
}

}  // namespace app
