#include "model_options.h"

#include "fields.h"

namespace app {
namespace {

struct OptionNameCollector {
    std::vector<std::string>& names;
    void Integer(const char* key, const int&, const char*, long long, long long) { names.push_back(OptionName(key)); }
    void Number(const char* key, const double&, const char*, double, double) { names.push_back(OptionName(key)); }
    template <class E>
    void Enum(const char* key, const E&, const char*) {
        names.push_back(OptionName(key));
    }
};

// The option names of a def struct's fields.
template <class Def>
std::vector<std::string> OptionNames(const Def& def) {
    std::vector<std::string> names;
    VisitFields(def, OptionNameCollector{names});
    return names;
}

}  // namespace

sim::Load ThesisLoad(const std::string& name, const std::string& what) {
    if (auto load = sim::FromName<sim::Load>(name)) return *load;
    throw UsageError(what + ": unknown value " + Quote(name) + " for the thesis model (choose " + sim::Choices<sim::Load>() + ")");
}

sim::ShellLoad ShellLoadOf(const std::string& name, const std::string& what) {
    if (auto load = sim::FromName<sim::ShellLoad>(name)) return *load;
    throw UsageError(what + ": unknown value " + Quote(name) + " for the membrane and shell models (choose " + sim::Choices<sim::ShellLoad>() + ")");
}

void AddModelOptions(Cli& cli, ModelOptions& o, bool withThesis) {
    cli.Group("Model");
    cli.Enum("--model", o.model, "thesis: the 2019 mass-spring model (MODEL.md); membrane and shell: silicone in mm and kPa at equilibrium (SHELL.md)");
    cli.Text("--load", o.load, "thesis: " + sim::ChoicesBar<sim::Load>() + "; membrane and shell: " + sim::ChoicesBar<sim::ShellLoad>())
        ->type_name("NAME")
        ->default_str("inflate");
    if (withThesis) {
        cli.Group("Thesis model");
        cli.Fields(o.thesis, {"load"});
    }
    cli.Group("Membrane and shell models: geometry");
    cli.Fields(o.shell.geometry);
    cli.Group("Membrane and shell models: material");
    cli.Enum("--material", o.material, "silicone preset (suppliers' data; see README)");
    cli.Fields(o.materialFields);
    cli.Group("Membrane and shell models: load and solver");
    cli.Fields(o.shell.load);
    cli.Fields(o.shell.solver);
    cli.Group("Membrane and shell models: fibres");
    cli.Fields(o.shell.fibres);
}

void ApplyModelOptions(const Cli& cli, const ModelOptions& o, sim::EvalJob& job) {
    job.model = o.model;
    const bool thesis = o.model == sim::ModelKind::Thesis;
    const std::string model = std::string("--model ") + sim::Name(o.model);
    std::vector<std::string> shellOptions = OptionNames(o.shell.geometry);
    for (auto* list : {&o.materialFields}) {
        auto names = OptionNames(*list);
        shellOptions.insert(shellOptions.end(), names.begin(), names.end());
    }
    for (const auto& names : {OptionNames(o.shell.load), OptionNames(o.shell.solver), OptionNames(o.shell.fibres)})
        shellOptions.insert(shellOptions.end(), names.begin(), names.end());
    shellOptions.push_back("--material");
    std::vector<std::string> thesisOptions = OptionNames(o.thesis);
    std::erase(thesisOptions, "--load");
    if (thesis) {
        for (const auto& name : shellOptions) cli.RefuseIfGiven(name, "does not apply to --model thesis (it is an option of the membrane and shell models)");
        job.params = o.thesis;
        if (cli.Given("--load")) job.params.load = ThesisLoad(o.load, "--load");
        return;
    }
    for (const auto& name : thesisOptions) cli.RefuseIfGiven(name, "does not apply to " + model + " (it is an option of the thesis model)");
    job.shell = o.shell;
    job.shell.material = MaterialWithOverrides(o.material, o.materialFields, [&](const char* key) { return cli.Given(OptionName(key)); });
    if (cli.Given("--load")) job.shell.load.kind = ShellLoadOf(o.load, "--load");
    if (const std::string error = sim::ShellDefError(job.shell); !error.empty()) throw UsageError(model + ": " + error);
}

}  // namespace app
