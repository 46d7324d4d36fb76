#include "formats/schema_convert.h"

#include <capnp/any.h>
#include <capnp/message.h>
#include <capnp/serialize.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace app {
namespace {

template <class... Fs>
struct Overloaded : Fs... {
    using Fs::operator()...;
};

// Enums convert by value: the schema lists them in sim's order. A value from a newer writer that
// this build does not know is an error, never a silent default.
template <class Sim, class Schema>
Sim EnumFromSchema(Schema value, const char* what) {
    const auto index = static_cast<size_t>(value);
    if (index >= sim::EnumNames<Sim>::table.size()) throw std::runtime_error(std::string("unknown ") + what + " value " + std::to_string(index));
    return static_cast<Sim>(index);
}
template <class Schema, class Sim>
Schema EnumToSchema(Sim value) {
    return static_cast<Schema>(static_cast<std::uint16_t>(value));
}
static_assert(static_cast<int>(schema::Status::OUTSIDE_ENVELOPE) == static_cast<int>(sim::Status::OutsideEnvelope));
static_assert(static_cast<int>(schema::Status::BUDGET_EXCEEDED) == static_cast<int>(sim::Status::BudgetExceeded));
static_assert(static_cast<int>(schema::Load::NONE) == static_cast<int>(sim::Load::None));
static_assert(static_cast<int>(schema::Precision::DOUBLE) == static_cast<int>(sim::Precision::Double));
static_assert(static_cast<int>(schema::SplineRegion::MIDDLE) == static_cast<int>(sim::SplineRegion::Middle));
static_assert(static_cast<int>(schema::ModelKind::SHELL) == static_cast<int>(sim::ModelKind::Shell));

template <class Value, class List>
void Fill(List list, const std::vector<double>& values) {
    for (unsigned i = 0; i < values.size(); ++i) list.set(i, static_cast<Value>(values[i]));
}

template <class List>
std::vector<double> Copy(List list) {
    std::vector<double> values(list.size());
    for (unsigned i = 0; i < list.size(); ++i) values[i] = list[i];
    return values;
}

bool FloatIsExact(const sim::Positions& p) {
    for (const auto* axis : {&p.x, &p.y, &p.z})
        for (double v : *axis)
            if (static_cast<double>(static_cast<float>(v)) != v && !std::isnan(v)) return false;
    return true;
}

sim::Positions Checked(std::vector<double> x, std::vector<double> y, std::vector<double> z) {
    if (y.size() != x.size() || z.size() != x.size()) throw std::runtime_error("mesh coordinate lists differ in length");
    sim::Positions p;
    p.x = std::move(x);
    p.y = std::move(y);
    p.z = std::move(z);
    return p;
}

}  // namespace

void SetMesh(schema::Mesh::Builder out, const sim::Positions& p) {
    const unsigned n = static_cast<unsigned>(p.Size());
    if (FloatIsExact(p)) {
        Fill<float>(out.initX(n), p.x);
        Fill<float>(out.initY(n), p.y);
        Fill<float>(out.initZ(n), p.z);
    } else {
        Fill<double>(out.initExactX(n), p.x);
        Fill<double>(out.initExactY(n), p.y);
        Fill<double>(out.initExactZ(n), p.z);
    }
}

sim::Positions GetMesh(schema::Mesh::Reader in) {
    // Fetch each list once: every get charges the whole list against the traversal limit.
    if (in.hasExactX()) return Checked(Copy(in.getExactX()), Copy(in.getExactY()), Copy(in.getExactZ()));
    return Checked(Copy(in.getX()), Copy(in.getY()), Copy(in.getZ()));
}

void SetExactMesh(schema::ExactMesh::Builder out, const sim::Positions& p) {
    const unsigned n = static_cast<unsigned>(p.Size());
    Fill<double>(out.initX(n), p.x);
    Fill<double>(out.initY(n), p.y);
    Fill<double>(out.initZ(n), p.z);
}

sim::Positions GetExactMesh(schema::ExactMesh::Reader in) { return Checked(Copy(in.getX()), Copy(in.getY()), Copy(in.getZ())); }

void SetShape(schema::Shape::Builder out, const sim::Shape& shape) {
    auto sine = [](auto b, double amplitude, double a, double z) {
        b.setAmplitude(amplitude);
        b.setPhaseStart(a);
        b.setPhaseEnd(z);
    };
    std::visit(Overloaded{
                   [&](const sim::CylinderShape&) { out.setCylinder(); },
                   [&](const sim::SineShape& s) { sine(out.initSine(), s.amplitude, s.phaseStart, s.phaseEnd); },
                   [&](const sim::AbsSineShape& s) { sine(out.initAbsSine(), s.amplitude, s.phaseStart, s.phaseEnd); },
                   [&](const sim::BSplineShape& s) {
                       auto b = out.initBspline();
                       b.setRegion(EnumToSchema<schema::SplineRegion>(s.region));
                       auto splines = b.initSplines(static_cast<unsigned>(s.splines.size()));
                       for (unsigned k = 0; k < s.splines.size(); ++k)
                           Fill<double>(splines[k].initControlPoints(static_cast<unsigned>(s.splines[k].size())), s.splines[k]);
                   },
                   [&](const sim::FreeXYShape& s) {
                       auto b = out.initFreeXY();
                       Fill<double>(b.initDx(static_cast<unsigned>(s.dx.size())), s.dx);
                       Fill<double>(b.initDy(static_cast<unsigned>(s.dy.size())), s.dy);
                   },
                   [&](const sim::MeshShape& s) { SetMesh(out.initMesh(), s.positions); },
               },
               shape);
}

sim::Shape GetShape(schema::Shape::Reader in) {
    switch (in.which()) {
        case schema::Shape::CYLINDER: return sim::CylinderShape{};
        case schema::Shape::SINE: {
            auto s = in.getSine();
            return sim::SineShape{s.getAmplitude(), s.getPhaseStart(), s.getPhaseEnd()};
        }
        case schema::Shape::ABS_SINE: {
            auto s = in.getAbsSine();
            return sim::AbsSineShape{s.getAmplitude(), s.getPhaseStart(), s.getPhaseEnd()};
        }
        case schema::Shape::BSPLINE: {
            auto s = in.getBspline();
            sim::BSplineShape b{EnumFromSchema<sim::SplineRegion>(s.getRegion(), "spline region"), {}};
            for (auto spline : s.getSplines()) b.splines.push_back(Copy(spline.getControlPoints()));
            return b;
        }
        case schema::Shape::FREE_X_Y: return sim::FreeXYShape{Copy(in.getFreeXY().getDx()), Copy(in.getFreeXY().getDy())};
        case schema::Shape::MESH: return sim::MeshShape{GetMesh(in.getMesh())};
    }
    throw std::runtime_error("unknown shape kind");
}

void SetParams(schema::SimParams::Builder p, const sim::SimParams& params) {
    p.setIterations(static_cast<std::uint32_t>(params.iterations));
    p.setLoad(EnumToSchema<schema::Load>(params.load));
    p.setSpringConstant(params.springConstant);
    p.setPressureScale(params.pressureScale);
    p.setPullForce(params.pullForce);
    p.setStepScale(params.stepScale);
    p.setDivergenceLimit(params.divergenceLimit);
    p.setPrecision(EnumToSchema<schema::Precision>(params.precision));
}

sim::SimParams GetParams(schema::SimParams::Reader p) {
    sim::SimParams params;
    params.iterations = static_cast<int>(std::min<std::uint32_t>(p.getIterations(), 2'000'000'000u));
    params.load = EnumFromSchema<sim::Load>(p.getLoad(), "load");
    params.springConstant = p.getSpringConstant();
    params.pressureScale = p.getPressureScale();
    params.pullForce = p.getPullForce();
    params.stepScale = p.getStepScale();
    params.divergenceLimit = p.getDivergenceLimit();
    params.precision = EnumFromSchema<sim::Precision>(p.getPrecision(), "precision");
    return params;
}

namespace {

template <class E>
E NamedEnum(const std::string& name, const char* what) {
    if (auto value = sim::FromName<E>(name)) return *value;
    throw std::runtime_error(std::string("unknown ") + what + " \"" + name + "\" (written by a newer version?)");
}

std::uint32_t Count(int n) { return static_cast<std::uint32_t>(std::max(0, n)); }
int Count(std::uint32_t n) { return static_cast<int>(std::min<std::uint32_t>(n, 1u << 30)); }

}  // namespace

void SetShellDef(schema::ShellDef::Builder s, const sim::ShellDef& def) {
    const sim::GeometryDef& g = def.geometry;
    s.setRadiusMm(g.radiusMm);
    s.setLengthMm(g.lengthMm);
    s.setThicknessMm(g.thicknessMm);
    s.setRingVertices(Count(g.ringVertices));
    s.setRings(Count(g.rings));
    s.setClampMm(g.clampMm);
    s.setEdgeSpacingMm(g.edgeSpacingMm);
    s.setEnds(sim::Name(g.ends));
    const sim::MaterialDef& m = def.material;
    s.setPreset(sim::Name(m.preset));
    s.setLaw(sim::Name(m.law));
    s.setMuKpa(m.muKpa);
    s.setC10Kpa(m.c10Kpa);
    s.setC01Kpa(m.c01Kpa);
    s.setC20Kpa(m.c20Kpa);
    s.setC30Kpa(m.c30Kpa);
    s.setTensileStrengthKpa(m.tensileStrengthKpa);
    s.setElongationAtBreak(m.elongationAtBreak);
    s.setStretchLimit(m.stretchLimit);
    s.setDensityKgPerM3(m.densityKgPerM3);
    const sim::LoadDef& l = def.load;
    s.setLoad(sim::Name(l.kind));
    s.setPressureKpa(l.pressureKpa);
    s.setForceN(l.forceN);
    s.setVolumeRatio(l.volumeRatio);
    s.setSteps(Count(l.steps));
    s.setTwist(sim::Name(def.ends.twist));
    s.setTorqueNMm(def.ends.torqueNMm);
    s.setTip(sim::Name(def.ends.tip));
    s.setMaxRadiusRatio(def.envelope.maxRadiusRatio);
    s.setMaxRadiusMm(def.envelope.maxRadiusMm);
    s.setMaxSiliconeG(def.envelope.maxSiliconeG);
    s.setContact(sim::Name(def.contact.mode));
    s.setContactGapFraction(def.contact.gapFraction);
    s.setContactStiffness(def.contact.stiffness);
    s.setStrokePercent(l.strokePercent);
    s.setStrokeMm(l.strokeMm);
    s.setIsobaricPoints(Count(l.isobaricPoints));
    const sim::SolverDef& v = def.solver;
    s.setTolerance(v.tolerance);
    s.setMaxIterations(Count(v.maxIterations));
    s.setMaxBisections(Count(v.maxBisections));
    s.setNewtonBudget(Count(v.newtonBudget));
    s.setHeldPushDiameters(v.heldPushDiameters);
    s.setSelfContact(v.selfContact);
    const sim::FibreDef& f = def.fibres;
    s.setFibres(sim::Name(f.layout));
    s.setFibreAngleDeg(f.angleDeg);
    s.setFibreStiffnessNPerMm(f.stiffnessNPerMm);
    auto bands = s.initFibreBands(static_cast<unsigned>(f.bands.size()));
    for (unsigned k = 0; k < f.bands.size(); ++k) {
        bands[k].setFrom(f.bands[k].from);
        bands[k].setTo(f.bands[k].to);
        bands[k].setAngleDeg(f.bands[k].angleDeg);
    }
    Fill<double>(s.initFibreSectorsDeg(static_cast<unsigned>(f.sectorAnglesDeg.size())), f.sectorAnglesDeg);
    s.setFibrePlusOff(!f.plus);
    s.setFibreMinusOff(!f.minus);
}

sim::ShellDef GetShellDef(schema::ShellDef::Reader s) {
    sim::ShellDef def;
    sim::GeometryDef& g = def.geometry;
    g.radiusMm = s.getRadiusMm();
    g.lengthMm = s.getLengthMm();
    g.thicknessMm = s.getThicknessMm();
    g.ringVertices = Count(s.getRingVertices());
    g.rings = Count(s.getRings());
    g.edgeSpacingMm = s.getEdgeSpacingMm();  // 0, evenly spaced rings, in every record before it
    // Records before clampMm held their clamps by ring count: the same length in millimetres.
    if (s.getClampMm() > 0) g.clampMm = s.getClampMm();
    else if (s.getClampRings() > 0) g.clampMm = (s.getClampRings() - 1.0) * g.lengthMm / std::max(1, RingCount(g) - 1);
    g.ends = NamedEnum<sim::EndCondition>(s.getEnds(), "end condition");
    sim::MaterialDef& m = def.material;
    m.preset = NamedEnum<sim::MaterialPreset>(s.getPreset(), "material");
    m.law = NamedEnum<sim::MaterialLaw>(s.getLaw(), "material law");
    m.muKpa = s.getMuKpa();
    m.c10Kpa = s.getC10Kpa();
    m.c01Kpa = s.getC01Kpa();
    m.c20Kpa = s.getC20Kpa();
    m.c30Kpa = s.getC30Kpa();
    m.tensileStrengthKpa = s.getTensileStrengthKpa();
    m.elongationAtBreak = s.getElongationAtBreak();
    m.stretchLimit = s.getStretchLimit();
    m.densityKgPerM3 = s.getDensityKgPerM3();
    sim::LoadDef& l = def.load;
    l.kind = NamedEnum<sim::ShellLoad>(s.getLoad(), "load");
    l.pressureKpa = s.getPressureKpa();
    l.forceN = s.getForceN();
    l.volumeRatio = s.getVolumeRatio();
    l.steps = Count(s.getSteps());
    const std::string twist = s.getTwist();
    def.ends.twist = twist.empty() ? sim::TwistEnd::Held : NamedEnum<sim::TwistEnd>(twist, "twist");  // as such records were evaluated
    def.ends.torqueNMm = s.getTorqueNMm();
    const std::string tip = s.getTip();
    def.ends.tip = tip.empty() ? sim::TipEnd::Held : NamedEnum<sim::TipEnd>(tip, "tip");
    def.envelope = {s.getMaxRadiusRatio(), s.getMaxRadiusMm(), s.getMaxSiliconeG()};
    const std::string contact = s.getContact();
    def.contact = contact.empty() ? sim::ContactDef{.mode = sim::ContactMode::Off}  // as such records were evaluated
                                  : sim::ContactDef{NamedEnum<sim::ContactMode>(contact, "contact"), s.getContactGapFraction(), s.getContactStiffness()};
    l.strokePercent = s.getStrokePercent();
    l.strokeMm = s.getStrokeMm();
    l.isobaricPoints = Count(s.getIsobaricPoints());
    sim::SolverDef& v = def.solver;
    v.tolerance = s.getTolerance();
    v.maxIterations = Count(s.getMaxIterations());
    v.maxBisections = Count(s.getMaxBisections());
    v.newtonBudget = Count(s.getNewtonBudget());
    v.heldPushDiameters = s.getHeldPushDiameters();
    v.selfContact = s.getSelfContact();
    sim::FibreDef& f = def.fibres;
    const std::string layout = s.getFibres();
    f.layout = layout.empty() ? sim::FibreLayout::None : NamedEnum<sim::FibreLayout>(layout, "fibre layout");
    if (s.hasFibres()) {
        f.angleDeg = s.getFibreAngleDeg();
        f.stiffnessNPerMm = s.getFibreStiffnessNPerMm();
    }
    for (auto band : s.getFibreBands()) f.bands.push_back({band.getFrom(), band.getTo(), band.getAngleDeg()});
    f.sectorAnglesDeg = Copy(s.getFibreSectorsDeg());
    f.plus = !s.getFibrePlusOff();
    f.minus = !s.getFibreMinusOff();
    return def;
}

void SetResultNumbers(schema::EvalResult::Builder r, const sim::SimResult& result, sim::ModelKind model) {
    r.setStatus(EnumToSchema<schema::Status>(result.status));
    r.setFitness(result.fitness);
    r.setContractionPercent(result.contractionPercent);
    r.setIterationsRun(static_cast<std::uint32_t>(result.iterationsRun));
    r.setElapsedMs(result.elapsedMs);
    const sim::ShellOutputs& o = result.shell;
    if (model == sim::ModelKind::Thesis) return;
    auto s = r.initShell();
    Fill<double>(s.initCurvePressureKpa(static_cast<unsigned>(o.curvePressureKpa.size())), o.curvePressureKpa);
    Fill<double>(s.initCurveContractionPercent(static_cast<unsigned>(o.curveContractionPercent.size())), o.curveContractionPercent);
    Fill<double>(s.initCurveVolumeMm3(static_cast<unsigned>(o.curveVolumeMm3.size())), o.curveVolumeMm3);
    s.setTargetPressureKpa(o.targetPressureKpa);
    s.setLimitPressureKpa(o.limitPressureKpa);
    s.setBlockingForceN(o.blockingForceN);
    s.setAxialStiffnessNPerMm(o.axialStiffnessNPerMm);
    s.setRestVolumeMm3(o.restVolumeMm3);
    s.setVolumeMm3(o.volumeMm3);
    s.setMaxStretch(o.maxStretch);
    s.setMaxStressKpa(o.maxStressKpa);
    s.setStretchLimit(o.stretchLimit);
    s.setTensileStrengthKpa(o.tensileStrengthKpa);
    s.setDisplacementMm(o.displacementMm);
    s.setNewtonIterations(Count(o.newtonIterations));
    s.setFactorizations(Count(o.factorizations));
    s.setMaxFibreStrain(o.maxFibreStrain);
    s.setMeanFibreStrain(o.meanFibreStrain);
    s.setFibreAngleDeg(o.fibreAngleDeg);
    s.setTwistDeg(o.twistDeg);
    s.setTwistPerLengthDegPerMm(o.twistPerLengthDegPerMm);
    s.setTorqueNMm(o.torqueNMm);
    s.setStrokeForceN(o.strokeForceN);
    Fill<double>(s.initCurveForceN(static_cast<unsigned>(o.curveForceN.size())), o.curveForceN);
    Fill<double>(s.initCurveTwistDeg(static_cast<unsigned>(o.curveTwistDeg.size())), o.curveTwistDeg);
    Fill<double>(s.initIsobaricContractionPercent(static_cast<unsigned>(o.isobaricContractionPercent.size())), o.isobaricContractionPercent);
    Fill<double>(s.initIsobaricForceN(static_cast<unsigned>(o.isobaricForceN.size())), o.isobaricForceN);
    s.setWorkPerStrokeMj(o.workPerStrokeMj);
    s.setWorkPerGramMjPerG(o.workPerGramMjPerG);
    s.setTipLateralMm(o.tipLateralMm);
    s.setTipTiltDeg(o.tipTiltDeg);
    s.setTipForceN(o.tipForceN);
    s.setTipMomentNMm(o.tipMomentNMm);
    s.setHeldBowMm(o.heldBowMm);
    s.setSiliconeG(o.siliconeG);
    s.setRestMaxRadiusMm(o.restMaxRadiusMm);
    s.setContactPairs(static_cast<unsigned>(o.contactPairs));
    s.setMinGapMm(o.minGapMm);
    s.setContactForceN(o.contactForceN);
    s.setCollapsePressureKpa(o.collapsePressureKpa);
}

void GetResultNumbers(schema::EvalResult::Reader r, sim::SimResult& result) {
    result.status = EnumFromSchema<sim::Status>(r.getStatus(), "status");
    result.fitness = r.getFitness();
    result.contractionPercent = r.getContractionPercent();
    result.iterationsRun = static_cast<int>(std::min<std::uint32_t>(r.getIterationsRun(), 2'000'000'000u));
    result.elapsedMs = r.getElapsedMs();
    if (!r.hasShell()) return;
    auto s = r.getShell();
    sim::ShellOutputs& o = result.shell;
    o.curvePressureKpa = Copy(s.getCurvePressureKpa());
    o.curveContractionPercent = Copy(s.getCurveContractionPercent());
    o.curveVolumeMm3 = Copy(s.getCurveVolumeMm3());
    o.targetPressureKpa = s.getTargetPressureKpa();
    o.limitPressureKpa = s.getLimitPressureKpa();
    o.blockingForceN = s.getBlockingForceN();
    o.axialStiffnessNPerMm = s.getAxialStiffnessNPerMm();
    o.restVolumeMm3 = s.getRestVolumeMm3();
    o.volumeMm3 = s.getVolumeMm3();
    o.maxStretch = s.getMaxStretch();
    o.maxStressKpa = s.getMaxStressKpa();
    o.stretchLimit = s.getStretchLimit();
    o.tensileStrengthKpa = s.getTensileStrengthKpa();
    o.displacementMm = s.getDisplacementMm();
    o.newtonIterations = Count(s.getNewtonIterations());
    o.factorizations = Count(s.getFactorizations());
    o.maxFibreStrain = s.getMaxFibreStrain();
    o.meanFibreStrain = s.getMeanFibreStrain();
    o.fibreAngleDeg = s.getFibreAngleDeg();
    o.twistDeg = s.getTwistDeg();
    o.twistPerLengthDegPerMm = s.getTwistPerLengthDegPerMm();
    o.torqueNMm = s.getTorqueNMm();
    o.strokeForceN = s.getStrokeForceN();
    o.curveForceN = Copy(s.getCurveForceN());
    o.curveTwistDeg = Copy(s.getCurveTwistDeg());
    o.isobaricContractionPercent = Copy(s.getIsobaricContractionPercent());
    o.isobaricForceN = Copy(s.getIsobaricForceN());
    o.workPerStrokeMj = s.getWorkPerStrokeMj();
    o.workPerGramMjPerG = s.getWorkPerGramMjPerG();
    o.tipLateralMm = s.getTipLateralMm();
    o.tipTiltDeg = s.getTipTiltDeg();
    o.tipForceN = s.getTipForceN();
    o.tipMomentNMm = s.getTipMomentNMm();
    o.heldBowMm = s.getHeldBowMm();
    o.siliconeG = s.getSiliconeG();
    o.restMaxRadiusMm = s.getRestMaxRadiusMm();
    o.contactPairs = static_cast<int>(s.getContactPairs());
    o.minGapMm = s.getMinGapMm();
    o.contactForceN = s.getContactForceN();
    o.collapsePressureKpa = s.getCollapsePressureKpa();
}

void SetResponse(schema::EvalResponse::Builder out, const sim::SimResult& result, sim::ModelKind model) {
    SetResultNumbers(out.initResult(), result, model);
    SetExactMesh(out.initInitial(), result.initial);
    SetExactMesh(out.initFinal(), result.final);
}

sim::SimResult GetResponse(schema::EvalResponse::Reader in) {
    sim::SimResult result;
    GetResultNumbers(in.getResult(), result);
    result.initial = GetExactMesh(in.getInitial());
    result.final = GetExactMesh(in.getFinal());
    return result;
}

namespace {

std::string MessageBytes(capnp::MessageBuilder& message) {
    const kj::Array<capnp::word> words = capnp::messageToFlatArray(message);
    const auto bytes = words.asBytes();
    return std::string(reinterpret_cast<const char*>(bytes.begin()), bytes.size());
}

// Reads a root of type T from bytes (copied to word alignment) and converts it inside `use`, while
// the message lives. Bytes that are not one whole message are an error, never a crash.
template <class T, class Use>
auto FromBytes(const std::string& bytes, const char* what, const Use& use) {
    if (bytes.empty() || bytes.size() % sizeof(capnp::word) != 0)
        throw std::runtime_error(std::string("not a ") + what + " message: " + std::to_string(bytes.size()) + " bytes");
    kj::Array<capnp::word> words = kj::heapArray<capnp::word>(bytes.size() / sizeof(capnp::word));
    std::memcpy(words.begin(), bytes.data(), bytes.size());
    capnp::ReaderOptions options;
    options.traversalLimitInWords = std::max<std::uint64_t>(options.traversalLimitInWords, 2 * words.size());
    try {
        capnp::FlatArrayMessageReader reader(words, options);
        if (reader.getRoot<capnp::AnyPointer>().isNull()) throw std::runtime_error(std::string("not a ") + what + " message: it holds nothing");
        return use(reader.getRoot<T>());
    } catch (const kj::Exception& e) {
        throw std::runtime_error(std::string("not a ") + what + " message: " + e.getDescription().cStr());
    }
}

}  // namespace

std::string JobBytes(const sim::EvalJob& job) {
    capnp::MallocMessageBuilder message;
    SetJob(message.initRoot<schema::EvalRequest>(), job);
    return MessageBytes(message);
}

sim::EvalJob JobFromBytes(const std::string& bytes) {
    return FromBytes<schema::EvalRequest>(bytes, "job", [](schema::EvalRequest::Reader in) { return GetJob(in); });
}

std::string ResultBytes(const sim::SimResult& result, sim::ModelKind model) {
    capnp::MallocMessageBuilder message;
    SetResponse(message.initRoot<schema::EvalResponse>(), result, model);
    return MessageBytes(message);
}

sim::SimResult ResultFromBytes(const std::string& bytes) {
    return FromBytes<schema::EvalResponse>(bytes, "result", [](schema::EvalResponse::Reader in) { return GetResponse(in); });
}

}  // namespace app
