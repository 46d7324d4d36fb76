// A material file (docs/guide/materials.md): a silicone the user measured, written by `actuator
// material fit` and read wherever a preset name goes (--material mix.json, an experiment's
// material.file, Python's Material.from_file).
//   {"format": "actuator-material", "version": 1, "name": "my-mix",
//    "material": {"law": "yeoh", "c10_kpa": ..., "stretch_limit": ...}, "fit": {...}}
// "material" holds the material keys of experiment files (sim/fields.h); "fit" says where the
// constants come from and is not read back.
#pragma once

#include <string>

#include "formats/json_out.h"
#include "sim/shell.h"

namespace app {

// True when a --material value names a file rather than a preset (it ends in ".json").
bool IsMaterialFileName(const std::string& value);

// The material's keys that set something (the law, its constants, the limits and the density), as an
// experiment's "material" block would hold them.
Json MaterialFieldsJson(const sim::MaterialDef& material);

// The file's text. `fit` is written as given (an object, or null for none).
std::string MaterialFileText(const std::string& name, const sim::MaterialDef& material, const Json& fit);

// A material file as read: its material (preset Custom), its name ("" when none) and its record of
// the fit (null when none).
struct MaterialFile {
    std::string name;
    sim::MaterialDef material;
    Json fit;
};

// Reads and checks a material file: strict (unknown keys refused), the constants checked as a
// model's are (sim::ShellDefError). Throws UsageError naming the file.
MaterialFile ReadMaterialFile(const std::string& path);

// A --material value: a preset's name or a material file (IsMaterialFileName). Throws UsageError
// listing the presets.
sim::MaterialDef MaterialNamed(const std::string& value, const std::string& what);

}  // namespace app
