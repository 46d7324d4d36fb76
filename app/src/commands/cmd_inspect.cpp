// `actuator inspect ARCHIVE`: list, filter, sort and export the evaluations of an archive, as a
// table or as complete JSON records.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <iostream>

#include "formats/archive.h"
#include "options/cli.h"
#include "commands/registry.h"
#include "formats/files.h"
#include "formats/json_out.h"
#include "formats/obj_io.h"
#include "fields/result_fields.h"
#include "evaluation/recorder.h"

namespace app {
namespace {

enum class SortKey { Id, Fitness };

}  // namespace
}  // namespace app

template <>
struct sim::EnumNames<app::SortKey> {
    static constexpr std::array<std::pair<app::SortKey, const char*>, 2> table{{{app::SortKey::Id, "id"}, {app::SortKey::Fitness, "fitness"}}};
};

namespace app {

static int RunInspect(int argc, char** argv, int first) {
    namespace fs = std::filesystem;
    Cli cli("inspect", "Lists the evaluations an experiment archived (DIR/evaluations.capnp): id, role, run, generation, status, fitness, "
                       "contraction and design. A cut-off archive is read up to its last complete evaluation (a note on stderr says so).");
    std::string archive, statusName, exportDir, exportVtuDir;
    int run = 0, generation = 0, limit = 0, top = 0;
    int index = 0;
    Role role = Role::Grid;
    double minFitness = 0, maxFitness = 0;
    SortKey sort = SortKey::Id;
    bool json = false;
    cli.App().add_option("archive", archive, "the archive")->required()->type_name("DIR/evaluations.capnp");
    cli.Group("Filters");
    cli.Integer("--index", index, "only the evaluation with this id (as render, simulate and export --from take it)", 0, 1 << 30)->default_str("");
    cli.Integer("--run", run, "only GA run R", 0, 1 << 30);
    cli.Integer("--generation", generation, "only GA generation G", -1, 1 << 30);
    cli.Enum("--role", role, "only evaluations made for this purpose");
    cli.Text("--status", statusName, "only evaluations with this status (" + sim::Choices<sim::Status>() + ")")->type_name("STATUS");
    cli.Number("--min-fitness", minFitness, "only evaluations with fitness >= F (implies status ok)");
    cli.Number("--max-fitness", maxFitness, "only evaluations with fitness <= F (implies status ok)");
    cli.Group("Order and output");
    cli.Enum("--sort", sort, "order: by id, or by fitness, best first (failed evaluations last)");
    cli.Integer("--top", top, "the N best by fitness (implies --sort fitness)", 1, 1 << 30);
    cli.Integer("--limit", limit, "show at most N evaluations (after filtering and sorting)", 0, 1 << 30);
    cli.Flag("--json", json, "one JSON object with complete records (design with every parameter, model settings, result)");
    cli.Text("--export-obj", exportDir, "write each shown evaluation's initial and final mesh as DIR/evaluation_NNNNNN_{initial,final}.obj")
        ->type_name("DIR");
    cli.Text("--export-vtu", exportVtuDir, "write each shown evaluation's deformed wall with its fields as DIR/evaluation_NNNNNN.vtu (as simulate "
                                           "--save-vtu, from the stored meshes: no load steps); a file already there is refused")
        ->type_name("DIR");
    cli.Examples("  actuator inspect runs/5.2/evaluations.capnp --run 2 --generation 40\n"
                 "  actuator inspect runs/5.2/evaluations.capnp --top 5 --json\n"
                 "  actuator inspect runs/4.1/evaluations.capnp --sort fitness --limit 3 --export-obj best_meshes/\n"
                 "  actuator inspect runs/5.2F/evaluations.capnp --index 117 --export-vtu fields/\n"
                 "  actuator render --from runs/5.2/evaluations.capnp --index 117 --out pictures/\n");
    if (!cli.Parse(argc, argv, first)) return 0;
    std::optional<sim::Status> status;
    if (cli.Given("--status")) status = Cli::ParseEnum<sim::Status>(statusName, "--status");
    if (cli.Given("--top")) {
        if (cli.Given("--sort") && sort != SortKey::Fitness) throw UsageError("--top takes the best by fitness; it does not go with --sort id");
        sort = SortKey::Fitness;
        limit = cli.Given("--limit") ? std::min(limit, top) : top;
    }
    const bool fitnessFilter = cli.Given("--min-fitness") || cli.Given("--max-fitness");
    const ArchiveContents contents = ReadArchive(archive, cli.Given("--export-obj") || cli.Given("--export-vtu"));
    if (contents.records.empty() && (contents.scan.tornTail || contents.scan.corrupt))
        throw UsageError(Quote(archive) + " holds no readable evaluation (" + contents.scan.problem + ")");
    std::vector<const ArchiveRecord*> shown;
    if (cli.Given("--index") && (contents.records.empty() || index > static_cast<long long>(contents.records.back().id)))
        throw UsageError(fmt::format("--index: no evaluation {} in {} (ids 0 to {})", index, Quote(archive),
                                     contents.records.empty() ? -1 : static_cast<long long>(contents.records.back().id)));
    for (const auto& r : contents.records) {
        if (cli.Given("--index") && static_cast<long long>(r.id) != index) continue;
        if (cli.Given("--run") && r.run != run) continue;
        if (cli.Given("--generation") && r.generation != generation) continue;
        if (cli.Given("--role") && r.role != role) continue;
        if (status && r.result.status != *status) continue;
        const bool ok = r.result.status == sim::Status::Ok;
        if (fitnessFilter && (!ok || (cli.Given("--min-fitness") && r.result.fitness < minFitness) || (cli.Given("--max-fitness") && r.result.fitness > maxFitness)))
            continue;
        shown.push_back(&r);
    }
    if (sort == SortKey::Fitness)
        std::stable_sort(shown.begin(), shown.end(), [](const ArchiveRecord* a, const ArchiveRecord* b) {
            const bool okA = a->result.status == sim::Status::Ok, okB = b->result.status == sim::Status::Ok;
            if (okA != okB) return okA;
            return okA && a->result.fitness > b->result.fitness;
        });
    if (cli.Given("--limit") || cli.Given("--top")) shown.resize(std::min<size_t>(shown.size(), static_cast<size_t>(limit)));

    // Every mesh or none, never over a file that is there, and no folder left behind by a refusal.
    auto refuseExisting = [&](const std::string& option, const fs::path& path) {
        std::error_code ec;
        if (fs::exists(path, ec)) throw UsageError(option + ": " + Quote(path.string()) + " already exists; remove it or give another folder");
    };
    auto objPath = [&](const ArchiveRecord* r, const char* which) { return fs::path(exportDir) / fmt::format("evaluation_{:06}_{}.obj", r->id, which); };
    auto vtuPath = [&](const ArchiveRecord* r) { return fs::path(exportVtuDir) / fmt::format("evaluation_{:06}.vtu", r->id); };
    for (const ArchiveRecord* r : shown) {
        if (cli.Given("--export-obj"))
            for (const char* which : {"initial", "final"}) refuseExisting("--export-obj", objPath(r, which));
        if (cli.Given("--export-vtu")) refuseExisting("--export-vtu", vtuPath(r));
    }
    CreatedFolders folders;
    if (cli.Given("--export-obj")) folders.Create(exportDir, "--export-obj");
    if (cli.Given("--export-vtu")) folders.Create(exportVtuDir, "--export-vtu");
    OutputBatch batch;
    if (cli.Given("--export-obj"))
        for (const ArchiveRecord* r : shown) {
            const auto surface = sim::SurfaceOf(r->job);
            for (const auto& [which, positions] : {std::pair{"initial", &r->result.initial}, std::pair{"final", &r->result.final}}) {
                WriteFileAtomically(objPath(r, which).string(), FormatObj(*positions, surface, fmt::format("actuator workbench evaluation {}, {} mesh", r->id, which)));
            }
        }
    if (cli.Given("--export-vtu"))
        for (const ArchiveRecord* r : shown) WriteFileAtomically(vtuPath(r).string(), FormatVtu(ResultFieldMesh(r->job, r->result)));
    batch.Commit();

    if (json) {
        Json records = Json::array();
        for (const ArchiveRecord* r : shown) {
            Json j{{"id", r->id}, {"experiment", r->experiment}, {"role", sim::Name(r->role)}, {"run", r->run}, {"generation", r->generation},
                   {"label", r->label}};
            j.update(ResultNumbersJson(r->result, r->job));
            j["design"] = DesignText(r->job.shape);
            j["shape"] = ShapeJson(r->job.shape);
            j["model"] = ModelJson(r->job);
            records.push_back(std::move(j));
        }
        std::cout << Json{{"archive", archive}, {"total", contents.records.size()}, {"shown", shown.size()},
                          {"truncated", contents.scan.tornTail}, {"damaged", contents.scan.corrupt}, {"evaluations", records}}
                         .dump()
                  << "\n";
    } else {
        std::cout << fmt::format("{:>7} {:<13} {:>4} {:>5} {:<10} {:>10} {:>8} {:>8}  {}\n", "id", "role", "run", "gen", "status", "fitness", "contr%",
                                 "iters", "design");
        for (const ArchiveRecord* r : shown) {
            const bool ok = r->result.status == sim::Status::Ok;
            std::string design = sim::ShapeName(r->job.shape) + std::string(" ") + DesignText(r->job.shape);
            if (design.size() > 60) design = design.substr(0, 57) + "...";
            std::cout << fmt::format("{:>7} {:<13} {:>4} {:>5} {:<10} {:>10} {:>8} {:>8}  {}\n", r->id, sim::Name(r->role), r->run,
                                     r->generation < 0 ? "-" : std::to_string(r->generation), sim::Name(r->result.status),
                                     ok ? fmt::format("{:.5f}", r->result.fitness) : "-", ok ? fmt::format("{:.3f}", r->result.contractionPercent) : "-",
                                     r->result.iterationsRun, design);
        }
        std::cout << shown.size() << " of " << contents.records.size() << " evaluations shown\n";
    }
    if (contents.scan.tornTail || contents.scan.corrupt)
        std::cerr << "note: " << contents.scan.problem << "; the " << contents.records.size() << " evaluations before it are shown\n";
    return 0;
}

static const RegisterCommand kInspectCommand{{"inspect", "list, filter, sort and export the evaluations in an archive", 80, RunInspect}};

}  // namespace app
