#include "options/model_options.h"

#include <algorithm>

#include "formats/archive.h"
#include "materials/material_file.h"
#include "options/shape_options.h"
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
    cli.Text("--material", o.material,
             "silicone: a preset (" + sim::ChoicesBar<sim::MaterialPreset>() + "; `actuator material list`) or a material file FILE.json (`actuator material fit`)")
        ->type_name("NAME|FILE.json")
        ->default_str(o.material);
    cli.Fields(o.materialFields);
    cli.Group("Membrane and shell models: load and solver");
    cli.Fields(o.shell.load);
    cli.Fields(o.shell.solver);
    cli.Group("Membrane and shell models: the top clamp's other degrees of freedom");
    cli.Fields(o.shell.ends);
    cli.Group("Membrane and shell models: fibres");
    cli.Fields(o.shell.fibres);
    cli.Group("Membrane and shell models: the envelope a design must stay in (else outside-envelope)");
    cli.Fields(o.shell.envelope);
    cli.Group("Membrane and shell models: self-contact");
    cli.Fields(o.shell.contact);
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

void RefuseWhereWithoutEffect(const std::string& key, const sim::FieldUse& u) {
    if (!u.Applies())
        throw UsageError(OptionName(key.c_str()) + " applies to " + DeciderOption(u.decider) + " " + u.values + ", not " + DeciderOption(u.decider) + " " + u.now);
}

// [SECTION] Each model's def on the command line. A new def adds one overload of each function of
// this section; the functions after it visit the job's def and never test the model.

// The options that set the def (--load aside: every model has it).
std::vector<std::string> DefOptionNames(const ModelOptions& o, const sim::ThesisDef&) {
    std::vector<std::string> names = OptionNames(o.thesis);
    std::erase(names, "--load");
    return names;
}
std::vector<std::string> DefOptionNames(const ModelOptions& o, const sim::ShellDef&) {
    std::vector<std::string> names{"--material"};
    for (const auto& part : {OptionNames(o.shell.geometry), OptionNames(o.materialFields), OptionNames(o.shell.load), OptionNames(o.shell.ends), OptionNames(o.shell.solver),
                             OptionNames(o.shell.fibres), OptionNames(o.shell.envelope), OptionNames(o.shell.contact)})
        names.insert(names.end(), part.begin(), part.end());
    return names;
}

// The options' material: the preset with the material fields given over it.
sim::MaterialDef MaterialOfOptions(const Cli& cli, const ModelOptions& o) {
    return MaterialWithOverrides(MaterialNamed(o.material, "--material"), o.materialFields, [&](const char* key) { return cli.Given(OptionName(key)); });
}

// A new job's def from the options.
void FillDef(const Cli& cli, const ModelOptions& o, sim::ThesisDef& def) {
    def.params = o.thesis;
    if (cli.Given("--load")) def.params.load = ThesisLoad(o.load, "--load");
}
void FillDef(const Cli& cli, const ModelOptions& o, sim::ShellDef& def) {
    def = o.shell;
    def.material = MaterialOfOptions(cli, o);
    if (cli.Given("--load")) def.load.kind = ShellLoadOf(o.load, "--load");
    if (cli.Given("--law") && !(sim::ShearModulusKpa(def.material) > 0)) {
        const sim::MaterialLaw law = def.material.law;
        throw UsageError("--law " + std::string(sim::Name(law)) + " needs its constants: " +
                         (law == sim::MaterialLaw::NeoHookean     ? "--mu-kpa"
                          : law == sim::MaterialLaw::MooneyRivlin ? "--c10-kpa and --c01-kpa"
                                                                  : "--c10-kpa (and --c20-kpa, --c30-kpa)") +
                         " (the preset " + sim::Name(def.material.preset) + " has none for it)");
    }
}

// The options given, written over a stored def (a design from an archive). For the rest shape only
// what shapes the part is taken; the rest is refused by RefuseWithoutEffect or here.
void OverrideDef(const Cli& cli, const ModelOptions& o, sim::ThesisDef& def, ModelUse use) {
    if (use == ModelUse::RestShape || use == ModelUse::CastPart) return;
    cli.CopyGivenFields(o.thesis, def.params);
    if (cli.Given("--load")) def.params.load = ThesisLoad(o.load, "--load");
}
void OverrideDef(const Cli& cli, const ModelOptions& o, sim::ShellDef& def, ModelUse use) {
    cli.CopyGivenFields(o.shell.geometry, def.geometry);
    if (use == ModelUse::CastPart) cli.CopyGivenFields(o.shell.fibres, def.fibres);
    if (use == ModelUse::RestShape || use == ModelUse::CastPart) {
        cli.RefuseIfGiven("--material", "does not go with --from: the material comes from the archive");
        cli.RefuseFields(o.materialFields, "does not go with --from: the material comes from the archive");
        return;
    }
    cli.CopyGivenFields(o.shell.load, def.load);
    cli.CopyGivenFields(o.shell.ends, def.ends);
    cli.CopyGivenFields(o.shell.solver, def.solver);
    // A preset given replaces the stored material (with the fields given over it); fields alone
    // change the stored one.
    if (cli.Given("--material"))
        def.material = MaterialOfOptions(cli, o);
    else
        cli.CopyGivenFields(o.materialFields, def.material);
    cli.CopyGivenFields(o.shell.fibres, def.fibres);
    cli.CopyGivenFields(o.shell.envelope, def.envelope);
    cli.CopyGivenFields(o.shell.contact, def.contact);
    if (cli.Given("--load")) def.load.kind = ShellLoadOf(o.load, "--load");
}

// Refuses the def's options that are given but have no effect on it for `use`.
void RefuseWithoutEffect(const Cli& cli, const ModelOptions& o, const sim::ThesisDef& def, ModelUse use) {
    if (use == ModelUse::RestShape || use == ModelUse::CastPart) {
        for (const auto& key : GivenKeys(cli, o.thesis))
            cli.RefuseIfGiven(OptionName(key.c_str()), "does not apply here: nothing is simulated (the part is the rest shape)");
        cli.RefuseIfGiven("--load", "does not apply here: nothing is simulated (the part is the rest shape)");
        return;
    }
    if (use == ModelUse::BothLoads) return;  // both loads are drawn: every constant has an effect
    for (const auto& key : GivenKeys(cli, o.thesis)) RefuseWhereWithoutEffect(key, sim::ThesisFieldUse(def.params, key));
}
void RefuseWithoutEffect(const Cli& cli, const ModelOptions& o, const sim::ShellDef& def, ModelUse use) {
    const std::string nothing = "does not apply here: nothing is simulated (the part is the rest shape, its geometry and silicone)";
    if (use == ModelUse::RestShape || use == ModelUse::CastPart) {
        for (const auto& keys : {GivenKeys(cli, o.shell.load), GivenKeys(cli, o.shell.ends), GivenKeys(cli, o.shell.solver), GivenKeys(cli, o.shell.envelope),
                                GivenKeys(cli, o.shell.contact)})
            for (const auto& key : keys) cli.RefuseIfGiven(OptionName(key.c_str()), nothing);
        if (use == ModelUse::RestShape)  // export winds the fibres; a drawn solid has none
            for (const auto& key : GivenKeys(cli, o.shell.fibres)) cli.RefuseIfGiven(OptionName(key.c_str()), nothing);
        cli.RefuseIfGiven("--load", nothing);
        cli.RefuseIfGiven("--ends", nothing);
        cli.RefuseIfGiven("--edge-spacing-mm", "does not apply here: the part samples the shape evenly (the rings' grading toward the clamps is the simulation's)");
        for (const auto& key : GivenKeys(cli, o.materialFields))
            if (key != "density_kg_per_m3") cli.RefuseIfGiven(OptionName(key.c_str()), "does not apply here: nothing is simulated (of the material, the part uses its density)");
    }
    for (const auto& part : {GivenKeys(cli, o.shell.geometry), GivenKeys(cli, o.materialFields), GivenKeys(cli, o.shell.load), GivenKeys(cli, o.shell.ends), GivenKeys(cli, o.shell.solver),
                             GivenKeys(cli, o.shell.fibres), GivenKeys(cli, o.shell.envelope), GivenKeys(cli, o.shell.contact)})
        for (const auto& key : part) RefuseWhereWithoutEffect(key, sim::ShellFieldUse(def, key));
}

// Empty when the def can run; checked before the design is (its messages name the model).
std::string DefError(const sim::ThesisDef& def) { return sim::SimParamsError(def.params); }
std::string DefError(const sim::ShellDef& def) { return sim::ShellDefError(def); }

// [SECTION] The job's def, whichever it is.

// Each kind of def once (membrane and shell share one), with the models that use it, for
// messages: "the thesis model", "the membrane and shell models".
struct DefOfModels {
    sim::ModelDef def;
    std::string models;
};
std::vector<DefOfModels> DefsOfModels() {
    std::vector<DefOfModels> defs;
    std::vector<std::vector<std::string>> names;
    for (const auto& [kind, name] : sim::EnumNames<sim::ModelKind>::table) {
        sim::ModelDef def = sim::ModelOf(kind).defaultDef();
        auto same = std::find_if(defs.begin(), defs.end(), [&](const DefOfModels& d) { return d.def.index() == def.index(); });
        if (same == defs.end()) {
            defs.push_back({std::move(def), ""});
            names.emplace_back();
            same = defs.end() - 1;
        }
        names[same - defs.begin()].emplace_back(name);
    }
    for (size_t k = 0; k < defs.size(); ++k) {
        std::string text = "the ";
        for (size_t i = 0; i < names[k].size(); ++i) text += (i == 0 ? "" : i + 1 == names[k].size() ? " and " : ", ") + names[k][i];
        defs[k].models = text + (names[k].size() == 1 ? " model" : " models");
    }
    return defs;
}

std::vector<std::string> DefOptionNamesOf(const ModelOptions& o, const sim::ModelDef& def) {
    return std::visit([&](const auto& d) { return DefOptionNames(o, d); }, def);
}

// The options of every other def than the job's, each with the models it belongs to.
void RefuseOtherModelsOptions(const Cli& cli, const ModelOptions& o, const sim::EvalJob& job) {
    const std::vector<std::string> own = DefOptionNamesOf(o, job.def);
    for (const DefOfModels& other : DefsOfModels()) {
        if (other.def.index() == job.def.index()) continue;
        for (const auto& option : DefOptionNamesOf(o, other.def))
            if (std::find(own.begin(), own.end(), option) == own.end())
                cli.RefuseIfGiven(option, "does not apply to --model " + std::string(sim::Name(job.model)) + " (it is an option of " + other.models + ")");
    }
}

}  // namespace

void RefuseOptionsWithoutEffect(const Cli& cli, const ModelOptions& o, const sim::EvalJob& job, ModelUse use) {
    RefuseOtherModelsOptions(cli, o, job);
    std::visit([&](const auto& def) { RefuseWithoutEffect(cli, o, def, use); }, job.def);
}

void ApplyModelOptions(const Cli& cli, const ModelOptions& o, sim::EvalJob& job, ModelUse use) {
    job.SetModel(o.model);
    std::visit([&](auto& def) { FillDef(cli, o, def); }, job.def);
    RefuseOptionsWithoutEffect(cli, o, job, use);
    if (const std::string error = std::visit([](const auto& def) { return DefError(def); }, job.def); !error.empty())
        throw UsageError("--model " + std::string(sim::Name(o.model)) + ": " + error);
}

void OverrideModelOptions(const Cli& cli, const ModelOptions& o, sim::EvalJob& job, ModelUse use) {
    std::visit([&](auto& def) { OverrideDef(cli, o, def, use); }, job.def);
    RefuseOptionsWithoutEffect(cli, o, job, use);
}

void RefuseModelOptions(const Cli& cli, const ModelOptions& o, const std::string& why) {
    cli.RefuseIfGiven("--model", why);
    cli.RefuseIfGiven("--load", why);
    for (const DefOfModels& each : DefsOfModels())
        for (const auto& option : DefOptionNamesOf(o, each.def)) cli.RefuseIfGiven(option, why);
}

sim::EvalJob ArchivedJob(const Cli& cli, const ModelOptions& options, const std::string& archive, int index, ModelUse use,
                         const std::function<void(sim::EvalJob&)>& prepare) {
    for (const auto& name : ShapeOptionNames()) cli.RefuseIfGiven(name, "does not go with --from: the design comes from the archive");
    cli.RefuseIfGiven("--model", "does not go with --from: the model comes from the archive");
    if (!cli.Given("--index")) throw UsageError("--from ARCHIVE needs --index K (list them with actuator inspect)");
    sim::EvalJob job = ReadArchiveRecord(archive, static_cast<std::uint64_t>(index)).job;
    if (prepare) prepare(job);
    // Model settings given on this command line override the stored ones.
    OverrideModelOptions(cli, options, job, use);
    if (const std::string error = sim::JobError(job); !error.empty()) throw UsageError(error);
    return job;
}

}  // namespace app
