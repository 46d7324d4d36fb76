#include "options/model_options.h"

#include "sim/fields.h"

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
    cli.Enum("--model", o.model, "thesis: the 2019 mass-spring model (docs/models/thesis.md); membrane and shell: silicone in mm and kPa at equilibrium (docs/models/shell.md)");
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
    cli.Enum("--material", o.material, "silicone preset (suppliers' data; docs/guide/physical-models.md)");
    cli.Fields(o.materialFields);
    cli.Group("Membrane and shell models: load and solver");
    cli.Fields(o.shell.load);
    cli.Fields(o.shell.solver);
    cli.Group("Membrane and shell models: fibres");
    cli.Fields(o.shell.fibres);
}

namespace {

// The option that decides where a field applies: the load's kind is --load; the others their key's.
std::string DeciderOption(const std::string& decider) { return decider == "kind" ? "--load" : OptionName(decider.c_str()); }

// The options of a def's fields that were given, with their keys.
template <class Def>
std::vector<std::string> GivenKeys(const Cli& cli, const Def& def) {
    std::vector<std::string> names = OptionNames(def), keys;
    for (const auto& name : names)
        if (cli.Given(name)) {
            std::string key = name.substr(2);
            for (char& c : key)
                if (c == '-') c = '_';
            keys.push_back(key);
        }
    return keys;
}

}  // namespace

void RefuseOptionsWithoutEffect(const Cli& cli, const ModelOptions& o, const sim::EvalJob& job, ModelUse use) {
    // The other model's options.
    const std::string model = std::string("--model ") + sim::Name(job.model);
    if (job.model == sim::ModelKind::Thesis) {
        std::vector<std::string> shellOptions{"--material"};
        for (const auto& names : {OptionNames(o.shell.geometry), OptionNames(o.materialFields), OptionNames(o.shell.load), OptionNames(o.shell.solver),
                                  OptionNames(o.shell.fibres)})
            shellOptions.insert(shellOptions.end(), names.begin(), names.end());
        for (const auto& name : shellOptions) cli.RefuseIfGiven(name, "does not apply to --model thesis (it is an option of the membrane and shell models)");
    } else {
        for (const auto& name : OptionNames(o.thesis))
            if (name != "--load") cli.RefuseIfGiven(name, "does not apply to " + model + " (it is an option of the thesis model)");
    }
    if (job.model == sim::ModelKind::Thesis) {
        if (use == ModelUse::RestShape) {
            for (const auto& key : GivenKeys(cli, o.thesis))
                cli.RefuseIfGiven(OptionName(key.c_str()), "does not apply here: nothing is simulated (the part is the rest shape)");
            cli.RefuseIfGiven("--load", "does not apply here: nothing is simulated (the part is the rest shape)");
            return;
        }
        if (use == ModelUse::BothLoads) return;  // both loads are drawn: every constant has an effect
        for (const auto& key : GivenKeys(cli, o.thesis))
            if (const sim::FieldUse u = ThesisFieldUse(job.Thesis().params, key); !u.Applies())
                throw UsageError(OptionName(key.c_str()) + " applies to " + DeciderOption(u.decider) + " " + u.values + ", not " + DeciderOption(u.decider) +
                                 " " + u.now);
        return;
    }
    const std::string nothing = "does not apply here: nothing is simulated (the part is the rest shape, its geometry and silicone)";
    if (use == ModelUse::RestShape) {
        for (const auto& keys : {GivenKeys(cli, o.shell.load), GivenKeys(cli, o.shell.solver), GivenKeys(cli, o.shell.fibres)})
            for (const auto& key : keys) cli.RefuseIfGiven(OptionName(key.c_str()), nothing);
        cli.RefuseIfGiven("--load", nothing);
        cli.RefuseIfGiven("--ends", nothing);
        for (const auto& key : GivenKeys(cli, o.materialFields))
            if (key != "density_kg_per_m3") cli.RefuseIfGiven(OptionName(key.c_str()), "does not apply here: nothing is simulated (of the material, the part uses its density)");
    } else {
        cli.RefuseIfGiven("--density-kg-per-m3", "applies to export (the silicone's mass); nothing here uses it");
    }
    std::vector<std::string> keys;
    for (const auto& part : {GivenKeys(cli, o.shell.geometry), GivenKeys(cli, o.materialFields), GivenKeys(cli, o.shell.load), GivenKeys(cli, o.shell.solver),
                             GivenKeys(cli, o.shell.fibres)})
        keys.insert(keys.end(), part.begin(), part.end());
    for (const auto& key : keys)
        if (const sim::FieldUse u = ShellFieldUse(job.Shell(), key); !u.Applies())
            throw UsageError(OptionName(key.c_str()) + " applies to " + DeciderOption(u.decider) + " " + u.values + ", not " + DeciderOption(u.decider) + " " +
                             u.now);
}

void ApplyModelOptions(const Cli& cli, const ModelOptions& o, sim::EvalJob& job, ModelUse use) {
    job.model = o.model;
    if (o.model == sim::ModelKind::Thesis) {
        job.Thesis().params = o.thesis;
        if (cli.Given("--load")) job.Thesis().params.load = ThesisLoad(o.load, "--load");
        RefuseOptionsWithoutEffect(cli, o, job, use);
        return;
    }
    job.Shell() = o.shell;
    job.Shell().material = MaterialWithOverrides(o.material, o.materialFields, [&](const char* key) { return cli.Given(OptionName(key)); });
    if (cli.Given("--load")) job.Shell().load.kind = ShellLoadOf(o.load, "--load");
    if (cli.Given("--law") && !(sim::ShearModulusKpa(job.Shell().material) > 0)) {
        const sim::MaterialLaw law = job.Shell().material.law;
        throw UsageError("--law " + std::string(sim::Name(law)) + " needs its constants: " +
                         (law == sim::MaterialLaw::NeoHookean     ? "--mu-kpa"
                          : law == sim::MaterialLaw::MooneyRivlin ? "--c10-kpa and --c01-kpa"
                                                                  : "--c10-kpa (and --c20-kpa, --c30-kpa)") +
                         " (the preset " + sim::Name(job.Shell().material.preset) + " has none for it)");
    }
    RefuseOptionsWithoutEffect(cli, o, job, use);
    if (const std::string error = sim::ShellDefError(job.Shell()); !error.empty()) throw UsageError("--model " + std::string(sim::Name(o.model)) + ": " + error);
}

}  // namespace app
