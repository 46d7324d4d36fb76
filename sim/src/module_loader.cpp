#include "sim/module_loader.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <vector>

namespace sim {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> SearchDirs() {
    std::vector<fs::path> dirs;
    for (const char* variable : {"ACTUATOR_MODULE_DIR", "ACTUATOR_RENDER_MODULE_DIR"})  // the second: its name before the optimizers
        if (const char* env = std::getenv(variable); env && *env) dirs.emplace_back(env);
    Dl_info info{};
    if (dladdr(reinterpret_cast<void*>(&OpenModuleEntry), &info) && info.dli_fname) {
        const fs::path self = fs::weakly_canonical(fs::path(info.dli_fname));
        dirs.push_back(self.parent_path().parent_path() / "lib" / "actuator");  // PREFIX/bin/actuator
        dirs.push_back(self.parent_path());
        // The Python module: PREFIX/lib/python3.X/dist-packages/actuator*.so (cmake --install), or
        // SITE-PACKAGES/actuator*.so with the modules beside it in actuator.libs/ (pip install python/)
        dirs.push_back(self.parent_path().parent_path().parent_path() / "actuator");
        dirs.push_back(self.parent_path() / "actuator.libs");
    }
    dirs.emplace_back(ACTUATOR_MODULE_BUILD_DIR);
    dirs.emplace_back(ACTUATOR_MODULE_INSTALL_DIR);
    return dirs;
}

}  // namespace

void* OpenModuleEntry(const std::string& file, const char* symbol, const std::string& what, std::string* error) {
    std::string tried;
    for (const fs::path& dir : SearchDirs()) {
        const fs::path path = dir / file;
        std::error_code ec;
        if (!fs::exists(path, ec)) {
            tried += (tried.empty() ? "" : ", ") + dir.string();
            continue;
        }
        void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            if (error) *error = "cannot load the " + what + " (" + path.string() + "): " + dlerror();
            return nullptr;
        }
        void* entry = dlsym(handle, symbol);
        if (!entry) {
            dlclose(handle);
            if (error) *error = path.string() + " is not the " + what + " module of this build (rebuild and reinstall)";
        }
        return entry;
    }
    if (error) *error = "the " + what + " module " + file + " is not installed (looked in " + tried + ")";
    return nullptr;
}

}  // namespace sim
