// Finds and loads a GL backend module by name. Searched, in order: $ACTUATOR_RENDER_MODULE_DIR, the
// install layout beside the running binary (bin/../lib/actuator), the build tree, the install prefix.
#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <mutex>

#include "render/backend.h"

namespace render {
namespace {

namespace fs = std::filesystem;

std::mutex gMutex;
std::string gChosen;  // empty: not chosen yet (environment, else the default)
const BackendApi* gLoaded = nullptr;

std::string ChosenName() {
    if (!gChosen.empty()) return gChosen;
    const char* env = std::getenv("ACTUATOR_GL_BACKEND");
    return env && *env ? env : BackendNames().front();
}

std::vector<fs::path> SearchDirs() {
    std::vector<fs::path> dirs;
    if (const char* env = std::getenv("ACTUATOR_RENDER_MODULE_DIR"); env && *env) dirs.emplace_back(env);
    Dl_info info{};
    if (dladdr(reinterpret_cast<void*>(&LoadBackend), &info) && info.dli_fname) {
        const fs::path self = fs::weakly_canonical(fs::path(info.dli_fname));
        dirs.push_back(self.parent_path().parent_path() / "lib" / "actuator");  // PREFIX/bin/actuator
        dirs.push_back(self.parent_path());
        // The Python module: PREFIX/lib/python3.X/dist-packages/actuator*.so (cmake --install), or
        // SITE-PACKAGES/actuator*.so with the renderer beside it in actuator.libs/ (pip install python/)
        dirs.push_back(self.parent_path().parent_path().parent_path() / "actuator");
        dirs.push_back(self.parent_path() / "actuator.libs");
    }
    dirs.emplace_back(ACTUATOR_RENDER_BUILD_DIR);
    dirs.emplace_back(ACTUATOR_RENDER_INSTALL_DIR);
    return dirs;
}

}  // namespace

const std::vector<std::string>& BackendNames() {
    static const std::vector<std::string> names{"osmesa", "egl"};
    return names;
}

bool SetBackend(const std::string& name, std::string* error) {
    std::lock_guard lock(gMutex);
    const auto& names = BackendNames();
    if (std::find(names.begin(), names.end(), name) == names.end()) {
        if (error) *error = "unknown GL backend '" + name + "' (choose osmesa or egl)";
        return false;
    }
    if (gLoaded && name != gLoaded->name) gLoaded = nullptr;  // the other module stays mapped; harmless
    gChosen = name;
    return true;
}

const BackendApi* LoadBackend(std::string* error) {
    std::lock_guard lock(gMutex);
    if (gLoaded) return gLoaded;
    const std::string name = ChosenName();
    const auto& names = BackendNames();
    if (std::find(names.begin(), names.end(), name) == names.end()) {
        if (error) *error = "unknown GL backend '" + name + "' in ACTUATOR_GL_BACKEND (choose osmesa or egl)";
        return nullptr;
    }
    const std::string file = "libactuator_render_" + name + ".so";
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
            if (error) *error = "cannot load the " + name + " renderer (" + path.string() + "): " + dlerror();
            return nullptr;
        }
        using Entry = const BackendApi* (*)();
        auto entry = reinterpret_cast<Entry>(dlsym(handle, "actuator_render_backend"));
        const BackendApi* api = entry ? entry() : nullptr;
        if (!api || api->abiVersion != kBackendAbiVersion) {
            if (error) *error = path.string() + " is not a renderer module of this build (rebuild and reinstall)";
            return nullptr;
        }
        gLoaded = api;
        return api;
    }
    if (error) *error = "the " + name + " renderer module " + file + " is not installed (looked in " + tried + ")";
    return nullptr;
}

std::unique_ptr<MeshRenderer> MeshRenderer::Create(const RenderDef& def, std::string* error) {
    const BackendApi* api = LoadBackend(error);
    return api ? api->createMeshRenderer(def, error) : nullptr;
}

std::unique_ptr<PlotRenderer> PlotRenderer::Create(int width, int height, std::string* error) {
    const BackendApi* api = LoadBackend(error);
    return api ? api->createPlotRenderer(width, height, error) : nullptr;
}

}  // namespace render
