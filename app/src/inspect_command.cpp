// `actuator inspect ARCHIVE`: list or filter the evaluations of an archive, as a table or JSON.
#include <cmath>
#include <cstdio>
#include <iostream>

#include "archive.h"
#include "cli_options.h"
#include "commands.h"
#include "json_writer.h"

namespace app {
namespace {

std::vector<OptionSpec> Specs() {
    return {
        {"run", "R", "", "only GA run R"},
        {"generation", "G", "", "only GA generation G"},
        {"status", "ok|nan|diverged", "", "only evaluations with this status"},
        {"min-fitness", "F", "", "only evaluations with fitness >= F (implies status ok)"},
        {"max-fitness", "F", "", "only evaluations with fitness <= F (implies status ok)"},
        {"json", "", "", "one JSON object with an array of evaluations instead of a table"},
        {"limit", "N", "all", "show at most N evaluations (after filtering)"},
        {"help", "", "", "show this help"},
    };
}

// B-spline control points (a GA genome) where there are some, else the record's label.
std::string ShapeSummary(const ArchivedEvaluation& e) {
    if (const auto* b = std::get_if<sim::BSplineShape>(&e.shape)) return "[" + sim::GenomeText(b->splines).substr(0, 60) + "]";
    return e.label;
}

}  // namespace

std::string InspectHelp() {
    return "usage: actuator inspect DIR/evaluations.capnp [filters] [--json]\n\n"
           "Lists the evaluations that `sweep`, `evolve` and `reproduce` archived: index, run, generation,\n"
           "status, fitness, contraction and shape. A cut-off archive is read up to its last complete\n"
           "evaluation (a note on stderr says so). Render one again with\n"
           "`actuator render --from DIR/evaluations.capnp --index K --out FOLDER`.\n\nOptions:\n" + FormatOptions(Specs());
}

int RunInspect(int argc, char** argv, int first) {
    const ParsedArgs args = ParseArgs(argc, argv, first, Specs(), 1);
    if (args.Has("help")) {
        std::cout << InspectHelp();
        return 0;
    }
    if (args.positionals.size() != 1) throw UsageError("expected one archive: actuator inspect DIR/evaluations.capnp");
    const int run = args.Has("run") ? ParseInt(args.Get("run"), "--run", 0, 1000000) : -1;
    const int generation = args.Has("generation") ? ParseInt(args.Get("generation"), "--generation", -1, 1000000) : -2;
    const std::string status = args.Has("status") ? ParseChoice(args.Get("status"), "--status", {"ok", "nan", "diverged"}) : "";
    const double minFitness = args.Has("min-fitness") ? ParseNumber(args.Get("min-fitness"), "--min-fitness") : -INFINITY;
    const double maxFitness = args.Has("max-fitness") ? ParseNumber(args.Get("max-fitness"), "--max-fitness") : INFINITY;
    const int limit = args.Has("limit") ? ParseInt(args.Get("limit"), "--limit", 0, 1 << 30) : 1 << 30;
    const bool fitnessFilter = args.Has("min-fitness") || args.Has("max-fitness");

    const ArchiveContents contents = ReadArchive(args.positionals[0], false);
    if (contents.evaluations.empty() && contents.truncated)
        throw UsageError("'" + args.positionals[0] + "' is not an evaluation archive (" + contents.problem + ")");
    std::vector<const ArchivedEvaluation*> shown;
    for (const auto& e : contents.evaluations) {
        if (run >= 0 && e.run != run) continue;
        if (generation >= -1 && e.generation != generation) continue;
        if (!status.empty() && status != sim::StatusName(e.status)) continue;
        if (fitnessFilter && (e.status != sim::Status::Ok || e.fitness < minFitness || e.fitness > maxFitness)) continue;
        if (static_cast<int>(shown.size()) >= limit) break;
        shown.push_back(&e);
    }
    if (args.Has("json")) {
        JsonWriter json;
        json.BeginObject().Key("archive").String(args.positionals[0]).Key("total").Integer(static_cast<long long>(contents.evaluations.size()));
        json.Key("truncated").Bool(contents.truncated).Key("evaluations").BeginArray();
        for (const auto* e : shown) {
            json.BeginObject().Key("index").Integer(static_cast<long long>(e->index)).Key("experiment").String(e->experiment);
            json.Key("run").Integer(e->run).Key("generation").Integer(e->generation).Key("status").String(sim::StatusName(e->status));
            json.Key("fitness").Number(e->status == sim::Status::Ok ? e->fitness : NAN).Key("contraction_percent").Number(e->contractionPercent);
            json.Key("iterations").Integer(e->iterationsRun).Key("elapsed_ms").Number(e->elapsedMs).Key("shape").String(sim::ShapeName(e->shape));
            json.Key("label").String(e->label);
            if (const auto* b = std::get_if<sim::BSplineShape>(&e->shape)) json.Key("control_points").String(sim::GenomeText(b->splines));
            json.EndObject();
        }
        json.EndArray().EndObject();
        std::cout << json.Text() << "\n";
    } else {
        std::printf("%7s %4s %5s %-9s %10s %8s %7s  %s\n", "index", "run", "gen", "status", "fitness", "contr%", "iters", "shape");
        for (const auto* e : shown) {
            const bool ok = e->status == sim::Status::Ok;
            std::printf("%7llu %4d %5s %-9s %10s %8s %7d  %s %s\n", static_cast<unsigned long long>(e->index), e->run,
                        e->generation < 0 ? "-" : std::to_string(e->generation).c_str(), sim::StatusName(e->status),
                        ok ? std::to_string(e->fitness).substr(0, 9).c_str() : "-",
                        ok ? std::to_string(e->contractionPercent).substr(0, 7).c_str() : "-", e->iterationsRun, sim::ShapeName(e->shape),
                        ShapeSummary(*e).c_str());
        }
        std::printf("%zu of %zu evaluations shown\n", shown.size(), contents.evaluations.size());
    }
    if (contents.truncated)
        std::cerr << "note: the archive ends in an incomplete evaluation after " << contents.evaluations.size()
                  << " complete ones (a run cut off while writing); they are all shown\n";
    return 0;
}

}  // namespace app
