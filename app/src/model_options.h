// The model a command evaluates with, from the command line: --model thesis|membrane|shell, the
// thesis model's constants, or the shell models' geometry, material (a preset, then overrides),
// load and solver. Options that do not apply to the chosen model are refused.
#pragma once

#include <string>

#include "cli.h"
#include "fields.h"
#include "sim/batch.h"

namespace app {

struct ModelOptions {
    sim::ModelKind model = sim::ModelKind::Thesis;
    std::string load;                       // thesis: inflate|stretch|none; shell: inflate|gas|volume|force|blocked
    sim::SimParams thesis = sim::DefaultSimParams();
    sim::ShellDef shell = sim::DefaultShellDef();
    sim::MaterialPreset material = sim::DefaultShellDef().material.preset;
    sim::MaterialDef materialFields = sim::DefaultShellDef().material;  // bound to the overriding options
};

// Adds the model options (thesis constants unless `withThesis` is false).
void AddModelOptions(Cli& cli, ModelOptions& options, bool withThesis = true);

// The job's model from the options. Refuses options given for the other model. Throws UsageError.
void ApplyModelOptions(const Cli& cli, const ModelOptions& options, sim::EvalJob& job);

// The load of a thesis or shell model by name; the message lists the model's choices.
sim::Load ThesisLoad(const std::string& name, const std::string& what);
sim::ShellLoad ShellLoadOf(const std::string& name, const std::string& what);

}  // namespace app
