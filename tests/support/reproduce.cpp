#include "reproduce.h"

#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "sim/names.h"

namespace testing_support {

std::string ReproduceCommand(const sim::EvalJob& job) {
    if (job.model == sim::ModelKind::Thesis || !std::holds_alternative<sim::CylinderShape>(job.shape))
        throw std::logic_error("ReproduceCommand writes membrane and shell tubes (a cylinder) only");
    const sim::ShellDef& d = job.Shell();
    std::ostringstream line;
    line << std::setprecision(17);
    const auto option = [&](const char* name, const auto& value) { line << ' ' << name << ' ' << value; };
    line << "reproduce: actuator simulate";
    option("--model", sim::Name(job.model));
    option("--shape", "cylinder");
    option("--radius-mm", d.geometry.radiusMm);
    option("--length-mm", d.geometry.lengthMm);
    option("--thickness-mm", d.geometry.thicknessMm);
    option("--ring-vertices", d.geometry.ringVertices);
    option("--rings", d.geometry.rings);
    option("--ends", sim::Name(d.geometry.ends));
    if (d.geometry.ends == sim::EndCondition::Clamped) {  // sliding ends have no clamp to hold, turn or tilt
        option("--clamp-mm", d.geometry.clampMm);
        option("--edge-spacing-mm", d.geometry.edgeSpacingMm);
        option("--twist", sim::Name(d.ends.twist));
        if (d.ends.twist == sim::TwistEnd::Loaded) option("--torque-n-mm", d.ends.torqueNMm);
        if (d.ends.tip != sim::TipEnd::Held) option("--tip", sim::Name(d.ends.tip));
    }
    const sim::MaterialDef& m = d.material;
    if (m.preset != sim::MaterialPreset::Custom) throw std::logic_error("ReproduceCommand writes custom materials only");
    option("--material", "custom");
    option("--law", sim::Name(m.law));
    if (m.law == sim::MaterialLaw::NeoHookean) option("--mu-kpa", m.muKpa);
    else {
        option("--c10-kpa", m.c10Kpa);
        if (m.law == sim::MaterialLaw::MooneyRivlin) option("--c01-kpa", m.c01Kpa);
        else option("--c20-kpa", m.c20Kpa), option("--c30-kpa", m.c30Kpa);
    }
    option("--elongation-at-break", m.elongationAtBreak);
    if (m.stretchLimit != 0) option("--stretch-limit", m.stretchLimit);
    const sim::LoadDef& l = d.load;
    option("--load", sim::Name(l.kind));
    if (l.kind == sim::ShellLoad::Inflate || l.kind == sim::ShellLoad::Gas || l.kind == sim::ShellLoad::Blocked) option("--pressure-kpa", l.pressureKpa);
    if (l.kind == sim::ShellLoad::Volume) option("--volume-ratio", l.volumeRatio);
    if (l.forceN != 0) option("--force-n", l.forceN);
    if (l.kind == sim::ShellLoad::Blocked) option("--stroke-percent", l.strokePercent);
    option("--steps", l.steps);
    option("--fibres", sim::Name(d.fibres.layout));
    if (d.fibres.layout != sim::FibreLayout::None) {
        if (d.fibres.layout == sim::FibreLayout::Braid || d.fibres.layout == sim::FibreLayout::Single) option("--fibre-angle-deg", d.fibres.angleDeg);
        option("--fibre-stiffness-n-per-mm", d.fibres.stiffnessNPerMm);
    }
    option("--contact", sim::Name(d.contact.mode));
    if (!d.solver.selfContact) line << "  # and the self-intersection check off, as in the test";
    return line.str();
}

}  // namespace testing_support
