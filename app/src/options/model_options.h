// The model a command evaluates with, from the command line: --model thesis|membrane|shell, the
// thesis model's constants, or the shell models' geometry, material (a preset, then overrides),
// load and solver. Options that do not apply to the chosen model are refused.
#pragma once

#include <functional>
#include <string>

#include "options/cli.h"
#include "sim/batch.h"
#include "sim/fields.h"
#include "sim/model.h"

namespace app {

struct ModelOptions {
    sim::ModelKind model = sim::kDefaultModel;
    std::string load;                       // thesis: inflate|stretch|none; shell: inflate|gas|volume|force|blocked
    sim::SimParams thesis = sim::DefaultSimParams();
    sim::ShellDef shell = sim::DefaultShellDef();
    std::string material = sim::Name(sim::DefaultShellDef().material.preset);  // a preset's name or a material file (FILE.json)
    sim::MaterialDef materialFields = sim::DefaultShellDef().material;  // bound to the overriding options
};

// What a command does with the model, which decides the options that have an effect.
enum class ModelUse {
    Simulate,   // one evaluation under the given load (simulate)
    Weighed,    // evaluations whose silicone is weighed too (characterize: work per gram)
    BothLoads,  // the thesis model under inflation and the stretch test, a shell model under its load (render)
    RestShape,  // nothing simulated: the rest shape, its geometry and its silicone (render --solid)
    CastPart,   // the rest shape, its silicone and its fibres, to wind (export)
};

// Adds the model options (thesis constants unless `withThesis` is false).
void AddModelOptions(Cli& cli, ModelOptions& options, bool withThesis = true);

// The job's model from the options. Refuses options given for the other model, and options that
// have no effect for `use` and the job's model, load, law, ends or fibres (RefuseOptionsWithoutEffect).
// Throws UsageError.
void ApplyModelOptions(const Cli& cli, const ModelOptions& options, sim::EvalJob& job, ModelUse use);

// Refuses every model option given on `cli` that has no effect on `job` (as resolved: from the
// options, or an archive's record with the given ones over it): "--force-n applies to --load force,
// not --load inflate". Throws UsageError.
void RefuseOptionsWithoutEffect(const Cli& cli, const ModelOptions& options, const sim::EvalJob& job, ModelUse use);

// The options given written over a stored job's def (simulate and export --from: the design and
// the model are the archive's), then RefuseOptionsWithoutEffect. Throws UsageError.
void OverrideModelOptions(const Cli& cli, const ModelOptions& options, sim::EvalJob& job, ModelUse use);

// A stored design for `--from ARCHIVE --index K`: refuses the shape options and --model (they come
// from the archive) and a missing --index; `prepare` may change the stored job before the options
// given override its model settings. Throws UsageError.
sim::EvalJob ArchivedJob(const Cli& cli, const ModelOptions& options, const std::string& archive, int index, ModelUse use,
                         const std::function<void(sim::EvalJob&)>& prepare = {});

// Refuses every model option given, --model and --load included, with `why` (render --from draws
// what was stored). Throws UsageError.
void RefuseModelOptions(const Cli& cli, const ModelOptions& options, const std::string& why);

// The load of a thesis or shell model by name; the message lists the model's choices.
sim::Load ThesisLoad(const std::string& name, const std::string& what);
sim::ShellLoad ShellLoadOf(const std::string& name, const std::string& what);

}  // namespace app
