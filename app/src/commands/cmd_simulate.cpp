// `actuator simulate`: one evaluation, one JSON object on stdout, optionally the meshes as OBJ. The
// design comes from the shape options, an OBJ mesh, or an archive (--from ARCHIVE --index K).
#include <filesystem>
#include <fmt/format.h>
#include <iostream>

#include "formats/archive.h"
#include "options/cli.h"
#include "commands/registry.h"
#include "evaluation/evaluator.h"
#include "evaluation/mesh_check.h"
#include "formats/files.h"
#include "formats/json_out.h"
#include "options/model_options.h"
#include "formats/obj_io.h"
#include "fields/result_fields.h"
#include "options/shape_options.h"

namespace app {
namespace {

void CheckMeshPath(const Cli& cli, const std::string& option, const std::string& path, const char* extension) {
    if (!cli.Given(option)) return;
    CheckOutputPath(path, option);
    if (std::filesystem::path(path).extension() != extension) throw UsageError(option + ": " + Quote(path) + " must end in " + extension);
}

}  // namespace

static int RunSimulate(int argc, char** argv, int first) {
    Cli cli("simulate", "Evaluates one actuator design and prints one JSON object: status, fitness, contraction_percent (positive = shorter), "
                        "the model's outputs, the design and the model's settings. --model thesis is the 2019 mass-spring model (fitness in mesh "
                        "units); membrane and shell are silicone at equilibrium in mm, kPa and N (fitness = contraction in percent at the "
                        "target pressure). Exit code 0 when it ran (whatever the status), 2 on bad input.");
    ShapeOptions shape;
    ModelOptions model;
    std::string from, saveMesh, saveInitial, saveVtu, savePvd;
    int index = 0;
    bool meshCheck = false;
    bool overwrite = false;
    AddShapeOptions(cli, shape);
    AddModelOptions(cli, model);
    cli.Group("Design from an archive");
    cli.Text("--from", from, "re-simulate a stored design: an archive (DIR/evaluations.capnp) with --index; model options given here override the stored ones")
        ->type_name("ARCHIVE");
    cli.Integer("--index", index, "with --from: the evaluation id (see actuator inspect)", 0, 1ll << 40)->default_str("");
    cli.Group("Output");
    cli.Flag("--mesh-check", meshCheck,
             "membrane and shell: also evaluate the design meshed twice as finely in both directions (the clamps keep their length) and report "
             "mesh_check: its contraction and how far it moved, against the rule of docs/models/shell.md section 2");
    cli.Text("--save-mesh", saveMesh, "write the final positions as OBJ (full precision; reads back with --mesh)")->type_name("FILE.obj");
    cli.Text("--save-initial", saveInitial, "write the initial (shaped) mesh as OBJ")->type_name("FILE.obj");
    cli.Text("--save-vtu", saveVtu,
             "write the deformed wall with its fields as VTK XML (ParaView, meshio, PyVista): displacement and rest position per point; membrane "
             "and shell: principal stretches, true stresses (kPa), thickness (mm) and each fibre family's direction, strain and tension (N/mm) "
             "per triangle, the caps marked (cell data 'region'); thesis: spring strain per vertex, in mesh units; the outputs as field data")
        ->type_name("FILE.vtu");
    cli.Text("--save-pvd", savePvd, "membrane and shell: write every load step as DIR/step_NNN.vtu (fields as --save-vtu) and DIR/series.pvd, "
                                    "the series ParaView opens; DIR must be new or empty")
        ->type_name("DIR");
    cli.Flag("--overwrite", overwrite, "replace the files --save-mesh, --save-initial and --save-vtu name when they exist (without it they are refused)");
    cli.Examples(
        "  actuator simulate --model thesis --shape sine --amplitude 4.1 --phase 0.5,pi-0.5\n"
        "  actuator simulate --model thesis --shape abs-sine --amplitude 4 --phase 0,4pi\n"
        "  actuator simulate --model thesis --shape bspline --region middle --control-points \"8,8,0,4,0,0,2\"\n"
        "  actuator simulate --model thesis --shape sine --load stretch --save-mesh stretched.obj\n"
        "  actuator simulate --model thesis --mesh stretched.obj --iterations 5000\n"
        "  actuator simulate --from runs/5.2/evaluations.capnp --index 17 --iterations 20000\n"
        "  actuator simulate --model membrane --shape cylinder --radius-mm 10 --length-mm 60 --thickness-mm 1 --mu-kpa 30 \\\n"
        "                    --ring-vertices 30 --rings 30 --pressure-kpa 1.8\n"
        "  actuator simulate --model shell --shape sine --amplitude 1.3 --material dragon-skin-10 --pressure-kpa 10\n"
        "  actuator simulate --model shell --shape sine --amplitude 1.3 --fibres braid --mesh-check\n"
        "  actuator simulate --model shell --shape sine --amplitude 1.3 --fibres braid --save-vtu inflated.vtu --save-pvd steps/\n");
    if (!cli.Parse(argc, argv, first)) return 0;

    sim::EvalJob job;
    if (cli.Given("--from")) {
        job = ArchivedJob(cli, model, from, index, ModelUse::Simulate);
    } else {
        cli.RefuseIfGiven("--index", "goes with --from ARCHIVE");
        job = BuildJob(cli, shape, model, ModelUse::Simulate);
    }
    CheckMeshPath(cli, "--save-mesh", saveMesh, ".obj");
    CheckMeshPath(cli, "--save-initial", saveInitial, ".obj");
    CheckMeshPath(cli, "--save-vtu", saveVtu, ".vtu");
    const std::vector<std::string> inputs{shape.meshFile, shape.offsets, from};
    if (cli.Given("--save-mesh")) RefuseOutputThatIsInput(saveMesh, "--save-mesh", inputs);
    if (cli.Given("--save-initial")) RefuseOutputThatIsInput(saveInitial, "--save-initial", inputs);
    if (cli.Given("--save-vtu")) RefuseOutputThatIsInput(saveVtu, "--save-vtu", inputs);
    if (cli.Given("--save-mesh") && cli.Given("--save-initial") && saveMesh == saveInitial)
        throw UsageError("--save-mesh and --save-initial name the same file");
    // A saved mesh or field file is a result: written over only when asked to.
    if (!cli.Given("--save-mesh") && !cli.Given("--save-initial") && !cli.Given("--save-vtu"))
        cli.RefuseIfGiven("--overwrite", "goes with --save-mesh, --save-initial or --save-vtu (a --save-pvd folder must be new or empty)");
    for (const auto& [option, path] : {std::pair<const char*, const std::string*>{"--save-mesh", &saveMesh}, {"--save-initial", &saveInitial}, {"--save-vtu", &saveVtu}})
        if (cli.Given(option) && !overwrite && std::filesystem::exists(std::filesystem::symlink_status(*path)))
            throw UsageError(std::string(option) + ": " + Quote(*path) + " already exists; add --overwrite to replace it, or give another name");
    if (meshCheck && !sim::ModelOf(job).physical)
        throw UsageError("--mesh-check: the thesis model's 30 x 30 helix is part of its definition; the check is for membrane and shell");
    if (cli.Given("--save-pvd")) {
        if (!sim::ModelOf(job).physical) throw UsageError("--save-pvd: the thesis model has no load steps (membrane or shell); --save-vtu writes its final mesh");
        CheckNewOrEmptyFolder(savePvd, "--save-pvd");
    }

    std::vector<sim::EvalJob> jobs{job};
    if (meshCheck) jobs.push_back(RefinedJob(job));
    const std::vector<sim::SimResult> results = MakeLocalEvaluator(static_cast<int>(jobs.size()))->EvaluateAll(jobs);
    const sim::SimResult& result = results.front();

    const auto surface = sim::SurfaceOf(job);
    const std::string size = sim::ModelOf(job).meshText(job);
    CreatedFolders folders;  // before the batch: a failed batch removes its files, then the folder it made
    OutputBatch batch;       // every file or none
    if (cli.Given("--save-initial")) WriteFileAtomically(saveInitial, FormatObj(result.initial, surface, "actuator workbench initial mesh: " + size));
    if (cli.Given("--save-mesh")) WriteFileAtomically(saveMesh, FormatObj(result.final, surface, "actuator workbench final mesh: " + size));
    if (cli.Given("--save-vtu")) WriteFileAtomically(saveVtu, FormatVtu(ResultFieldMesh(job, result)));
    if (cli.Given("--save-pvd")) WriteFieldSeries(savePvd, job, result, folders);
    batch.Commit();
    Json out = ResultNumbersJson(result, job);
    out["final_positions_hash"] = fmt::format("{:016x}", sim::PositionsHash(result.final));
    out["shape"] = ShapeJson(job.shape);
    out["model"] = ModelJson(job);
    if (cli.Given("--from")) out["from"] = Json{{"archive", from}, {"index", index}};
    if (meshCheck) out["mesh_check"] = MeshCheckJson(result, jobs.back(), results.back());
    std::cout << out.dump() << "\n";
    return 0;
}

static const RegisterCommand kSimulateCommand{{"simulate", "evaluate one design and print its result as JSON", 10, RunSimulate}};

}  // namespace app
