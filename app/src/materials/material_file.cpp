#include "materials/material_file.h"

#include <map>

#include "formats/files.h"
#include "sim/fields.h"
#include "support/errors.h"

namespace app {
namespace {

constexpr const char* kFormat = "actuator-material";
constexpr int kVersion = 1;

// Writes the keys that set something: zero is every number's "not given".
struct FieldWriter {
    Json& out;
    void Integer(const char*, const int&, const char*, long long, long long) {}
    void Number(const char* key, const double& v, const char*, double, double) {
        if (v != 0) out[key] = v;
    }
    template <class E>
    void Enum(const char* key, const E& v, const char*) {
        out[key] = sim::Name(v);
    }
};

// Reads the material keys from a JSON object, refusing what is not a number in range.
struct FieldReader {
    const Json& in;
    const std::string& where;
    std::map<std::string, bool>& seen;
    void Integer(const char*, int&, const char*, long long, long long) {}
    void Number(const char* key, double& v, const char*, double min, double max) {
        seen[key] = true;
        if (!in.contains(key)) return;
        const Json& value = in.at(key);
        if (!value.is_number()) throw UsageError(where + "'material." + key + "': expected a number, got " + Quote(value.dump()));
        v = value.get<double>();
        if (!(v >= min && v <= max)) throw UsageError(where + "'material." + key + "': " + value.dump() + " is out of range");
    }
    template <class E>
    void Enum(const char* key, E& v, const char*) {
        seen[key] = true;
        if (!in.contains(key)) return;
        const Json& value = in.at(key);
        const auto parsed = value.is_string() ? sim::FromName<E>(value.get<std::string>()) : std::nullopt;
        if (!parsed) throw UsageError(where + "'material." + key + "': expected one of " + sim::Choices<E>() + ", got " + Quote(value.dump()));
        v = *parsed;
    }
};

}  // namespace

bool IsMaterialFileName(const std::string& value) { return value.size() > 5 && value.compare(value.size() - 5, 5, ".json") == 0; }

Json MaterialFieldsJson(const sim::MaterialDef& material) {
    Json out = Json::object();
    VisitFields(material, FieldWriter{out});
    return out;
}

std::string MaterialFileText(const std::string& name, const sim::MaterialDef& material, const Json& fit) {
    Json file = Json::object();
    file["format"] = kFormat;
    file["version"] = kVersion;
    file["name"] = name;
    file["material"] = MaterialFieldsJson(material);
    file["fit"] = fit;
    return file.dump(2) + "\n";
}

MaterialFile ReadMaterialFile(const std::string& path) {
    const std::string where = path + ": ";
    Json root;
    try {
        root = ParseJson(ReadInputFile(path, 1 << 20), path);
    } catch (const Json::exception& error) {
        throw UsageError(where + "not a material file: not valid JSON (" + error.what() + ")");
    }
    if (!root.is_object() || root.value("format", Json()) != kFormat)
        throw UsageError(where + "not a material file (it has no \"format\": \"actuator-material\"; `actuator material fit` writes them)");
    if (root.value("version", Json()) != kVersion)
        throw UsageError(where + "material file version " + root.value("version", Json()).dump() + " is not one this build reads (1)");
    for (const auto& [key, value] : root.items())
        if (key != "format" && key != "version" && key != "name" && key != "material" && key != "fit")
            throw UsageError(where + "'" + key + "': unknown key (a material file has format, version, name, material and fit)");
    if (!root.contains("material") || !root.at("material").is_object()) throw UsageError(where + "'material': missing or not an object");
    const Json& fields = root.at("material");
    sim::MaterialDef material;
    std::map<std::string, bool> seen;
    VisitFields(material, FieldReader{fields, where, seen});
    std::string keys;
    for (const auto& [key, known] : seen) keys += (keys.empty() ? "" : ", ") + key;
    for (const auto& [key, value] : fields.items())
        if (!seen.count(key)) throw UsageError(where + "'material." + key + "': unknown key (choose " + keys + ")");
    material.preset = sim::MaterialPreset::Custom;
    sim::ShellDef check = sim::DefaultShellDef();
    check.material = material;
    if (const std::string error = sim::ShellDefError(check); !error.empty()) throw UsageError(where + error);
    if (root.contains("name") && !root.at("name").is_string()) throw UsageError(where + "'name': expected a string");
    return {root.value("name", std::string()), material, root.value("fit", Json())};
}

sim::MaterialDef MaterialNamed(const std::string& value, const std::string& what) {
    if (IsMaterialFileName(value)) return ReadMaterialFile(value).material;
    if (const auto preset = sim::FromName<sim::MaterialPreset>(value)) return sim::MaterialPresetDef(*preset);
    throw UsageError(what + ": unknown material " + Quote(value) + " (choose " + sim::Choices<sim::MaterialPreset>() +
                     ", or a material file FILE.json from `actuator material fit`)");
}

}  // namespace app
