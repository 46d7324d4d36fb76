// The entry point of a GL backend module: its name and its two renderer factories.
#include "gl_context.h"
#include "render/backend.h"

namespace render {

std::unique_ptr<MeshRenderer> CreateGlMeshRenderer(const RenderDef& def, std::string* error);
std::unique_ptr<PlotRenderer> CreateGlPlotRenderer(int width, int height, std::string* error);

}  // namespace render

extern "C" __attribute__((visibility("default"))) const render::BackendApi* actuator_render_backend() {
    static const render::BackendApi api{render::kBackendAbiVersion, render::kBackendName, &render::CreateGlMeshRenderer,
                                        &render::CreateGlPlotRenderer};
    return &api;
}
