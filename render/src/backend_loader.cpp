// Finds and loads a GL backend module by name, where sim::OpenModuleEntry looks for the workbench's
// run-time modules.
#include <algorithm>
#include <cstdlib>
#include <mutex>

#include "render/backend.h"
#include "sim/module_loader.h"

namespace render {
namespace {

std::mutex gMutex;
std::string gChosen;  // empty: not chosen yet (environment, else the default)
const BackendApi* gLoaded = nullptr;

std::string ChosenName() {
    if (!gChosen.empty()) return gChosen;
    const char* env = std::getenv("ACTUATOR_GL_BACKEND");
    return env && *env ? env : BackendNames().front();
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
    using Entry = const BackendApi* (*)();
    auto entry = reinterpret_cast<Entry>(sim::OpenModuleEntry("libactuator_render_" + name + ".so", "actuator_render_backend", name + " renderer", error));
    if (!entry) return nullptr;
    const BackendApi* api = entry();
    if (!api || api->abiVersion != kBackendAbiVersion) {
        if (error) *error = "the " + name + " renderer module is not of this build (rebuild and reinstall)";
        return nullptr;
    }
    gLoaded = api;
    return api;
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
