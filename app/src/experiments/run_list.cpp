// A list of given shapes (thesis chapter 6's stretch tests): each evaluated once under the
// experiment's load, tabulated beside the thesis's number, and pictured before and after.
// Resumable: shapes are archived in order, so a resume continues after the last archived one.
#include <map>
#include <fmt/format.h>

#include "formats/csv.h"
#include "formats/evaluation_log.h"
#include "formats/table.h"
#include "experiments/experiment_runner.h"
#include "formats/files.h"
#include "support/progress.h"
#include "experiments/thesis_check.h"

namespace app {

void RunList(RunContext& c) {
    const Experiment& e = c.e;
    const size_t n = e.shapes.size();
    size_t done = 0;
    for (const ArchiveRecord& r : c.recorder.Existing()) {
        if (done >= n || r.role != Role::Shape || r.id != done) break;
        ++done;
    }
    if (c.options.resume) c.recorder.RollBack(done);

    Progress progress("evaluate " + ExperimentTitle(e), c.options.progress);
    std::vector<sim::EvalJob> jobs;
    std::vector<EvaluationTag> tags;
    for (size_t j = done; j < n; ++j) {
        jobs.push_back(JobOf(e, e.shapes[j].shape));
        tags.push_back({Role::Shape, 0, -1, e.shapes[j].label});
    }
    c.recorder.Evaluate(jobs, tags, [&](std::uint64_t, size_t k, sim::SimResult&&) {
        progress.Update(static_cast<long long>(done + k + 1), static_cast<long long>(n), static_cast<long long>(k + 1), "shapes");
    });

    // Table and figures from the archive: the same whether the run was resumed or not.
    const sim::EvalJob base = JobOf(e, sim::CylinderShape{});
    std::vector<std::string> header{"evaluation", "label", "status"};
    const std::vector<std::string> outputs = sim::OutputNames({base}, false);
    header.insert(header.end(), outputs.begin(), outputs.end());
    header.push_back("thesis_fitness");
    Table table(header);
    std::unique_ptr<render::MeshRenderer> renderer;
    const std::string load = sim::ModelOf(base).loadName(base);
    c.recorder.ForEachRecord(0, n, [&](ArchiveRecord&& r) {
        const LabelledShape& shape = e.shapes[r.id];
        const bool ok = r.result.status == sim::Status::Ok;
        std::vector<std::string> row{std::to_string(r.id), shape.label, sim::Name(r.result.status)};
        std::map<std::string, std::string> cells = OutputCells(r.result, r.job);
        for (const std::string& name : outputs) row.push_back(cells[name]);
        row.push_back(CsvNumber(shape.thesisFitness));
        table.AddRow(row);
        c.outcome.rows.push_back({shape.label, ok ? r.result.fitness : NAN, shape.thesisFitness});
        if (!e.render.figures) return;
        if (!renderer) renderer = MakeRenderer(1024, 768);
        const std::string name = fmt::format("shape_{:02}.png", r.id);
        WritePng((c.dir / name).string(), renderer->Render(BeforeAfterScene(shape.label + "  -  " + load, r.result, r.job)), 6);
        c.outcome.figures.push_back(name);
    });
    WriteFileAtomically((c.dir / "results.csv").string(), table.Csv());

    // The thesis draws conclusions from the order of its numbers (6.1: "the actuator with the smallest
    // radius outperforms the two larger ones"; 6.2's two -2.62s are a tie): how many of those relations
    // hold here.
    std::vector<std::string> names;
    std::vector<double> ours, thesis;
    for (size_t k = 0; k < n && k < c.outcome.rows.size(); ++k)
        if (std::isfinite(c.outcome.rows[k].thesis)) {
            names.push_back(c.outcome.rows[k].quantity);
            ours.push_back(c.outcome.rows[k].ours);
            thesis.push_back(c.outcome.rows[k].thesis);
        }
    if (names.size() >= 2) c.outcome.rows.push_back(OrderRow("pairs in the thesis's order", PairsFromThesisValues(names, ours, thesis)));
}

}  // namespace app
