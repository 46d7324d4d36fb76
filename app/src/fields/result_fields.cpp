#include "fields/result_fields.h"

#include <cmath>
#include <filesystem>
#include <fmt/format.h>

#include "formats/files.h"
#include "sim/model.h"
#include "sim/shell.h"
#include "sim/surface.h"

namespace app {
namespace {

// Every one-number output of the result, under its name, as field data.
class FieldDataOutputs : public sim::OutputVisitor {
public:
    explicit FieldDataOutputs(std::vector<FieldArray>& data) : data_(data) {}
    void Number(const char* name, const char*, double value) override { data_.push_back({name, 1, {value}}); }
    void Count(const char* name, long long value) override { data_.push_back({name, 1, {static_cast<double>(value)}, true}); }
    void Curve(const char*, const char*, const std::vector<double>&) override {}

private:
    std::vector<FieldArray>& data_;
};

FieldArray Vectors(std::string name, const sim::Positions& p) {
    FieldArray a{std::move(name), 3, {}};
    a.values.reserve(3 * static_cast<size_t>(p.Size()));
    for (int i = 0; i < p.Size(); ++i) a.values.insert(a.values.end(), {p.x[i], p.y[i], p.z[i]});
    return a;
}

FieldArray Difference(std::string name, const sim::Positions& to, const sim::Positions& from) {
    FieldArray a{std::move(name), 3, {}};
    for (int i = 0; i < to.Size(); ++i) a.values.insert(a.values.end(), {to.x[i] - from.x[i], to.y[i] - from.y[i], to.z[i] - from.z[i]});
    return a;
}

double At(const std::vector<double>& curve, int step) { return step >= 0 && step < static_cast<int>(curve.size()) ? curve[step] : NAN; }

}  // namespace

FieldMesh ResultFieldMesh(const sim::EvalJob& job, const sim::SimResult& result, int step) {
    const sim::Model& model = sim::ModelOf(job);
    const sim::Positions& rest = result.initial;
    const sim::Positions& deformed = step >= 0 ? result.shell.steps.at(step) : result.final;
    const sim::Surface surface = sim::SurfaceOf(job);
    FieldMesh mesh;
    mesh.points = deformed;
    const bool complete = deformed.Size() == surface.vertexCount && rest.Size() == surface.vertexCount;
    if (complete) mesh.triangles = surface.triangles;
    const std::string length = model.physical ? "mm" : "mesh_units";
    if (complete) {
        mesh.pointData.push_back(Difference("displacement_" + length, deformed, rest));
        mesh.pointData.push_back(Vectors("rest_position_" + length, rest));
    }
    if (complete && !model.physical) {
        mesh.pointData.push_back({"spring_strain", 1, sim::EdgeStrainPerVertex(surface, rest, deformed)});
    } else if (complete) {
        const sim::WallCells cells = sim::WallCellValues(job.Shell(), job.shape, job.model == sim::ModelKind::Shell, deformed);
        if (cells.region.size() == mesh.triangles.size()) {
            mesh.cellData.push_back({"region", 1, std::vector<double>(cells.region.begin(), cells.region.end()), true});
            mesh.cellData.push_back({"max_principal_stretch", 1, cells.stretchMax});
            mesh.cellData.push_back({"min_principal_stretch", 1, cells.stretchMin});
            mesh.cellData.push_back({"max_principal_stress_kpa", 1, cells.stressMaxKpa});
            mesh.cellData.push_back({"min_principal_stress_kpa", 1, cells.stressMinKpa});
            mesh.cellData.push_back({"thickness_mm", 1, cells.thicknessMm});
            for (int f = 0; f < cells.families; ++f) {
                const std::string family = fmt::format("fibre_{}_", f + 1);
                FieldArray direction{family + "direction", 3, {}};
                for (const auto& d : cells.fibreDirection[f]) direction.values.insert(direction.values.end(), d.begin(), d.end());
                mesh.cellData.push_back(std::move(direction));
                mesh.cellData.push_back({family + "strain", 1, cells.fibreStrain[f]});
                mesh.cellData.push_back({family + "tension_n_per_mm", 1, cells.fibreTensionNPerMm[f]});
            }
        }
    }
    FieldDataOutputs outputs(mesh.fieldData);
    sim::VisitOutputs(result, job, outputs);
    mesh.fieldData.push_back({"status_ok", 1, {result.status == sim::Status::Ok ? 1.0 : 0.0}, true});
    if (step >= 0) {
        mesh.fieldData.push_back({"step", 1, {static_cast<double>(step)}, true});
        mesh.fieldData.push_back({"step_pressure_kpa", 1, {At(result.shell.curvePressureKpa, step)}});
        mesh.fieldData.push_back({"step_contraction_percent", 1, {At(result.shell.curveContractionPercent, step)}});
        mesh.fieldData.push_back({"step_volume_mm3", 1, {At(result.shell.curveVolumeMm3, step)}});
        mesh.fieldData.push_back({"step_force_n", 1, {At(result.shell.curveForceN, step)}});
    }
    mesh.comment = fmt::format("actuator workbench: {} model, status {}; {}; {}", model.name, sim::Name(result.status), model.meshText(job),
                               model.physical ? "lengths in mm, stresses in kPa, fibre tensions in N per mm of rest width; cell data "
                                                "'region': 0 free wall, 1 wall within a clamp, 2 end cap (the fixture's: its wall fields are NaN)"
                                              : "lengths in mesh units (one unit is the tube's rest radius), as the 2019 mass-spring model has them");
    if (step >= 0) mesh.comment += fmt::format("; load step {} of {}", step + 1, result.shell.steps.size());
    return mesh;
}

void WriteFieldSeries(const std::string& folder, const sim::EvalJob& job, const sim::SimResult& result, CreatedFolders& folders) {
    folders.Create(folder, "--save-pvd");
    std::vector<SeriesEntry> entries;
    for (size_t k = 0; k < result.shell.steps.size(); ++k) {
        const std::string file = fmt::format("step_{:03}.vtu", k + 1);
        WriteFileAtomically((std::filesystem::path(folder) / file).string(), FormatVtu(ResultFieldMesh(job, result, static_cast<int>(k))));
        entries.push_back({static_cast<double>(k + 1), file});
    }
    WriteFileAtomically((std::filesystem::path(folder) / "series.pvd").string(), FormatPvd(entries));
}

}  // namespace app
