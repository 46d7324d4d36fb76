// The GL backends, each a module loaded at run time by name, so that only commands that draw map
// OpenGL (and, through Mesa, LLVM):
//   osmesa  Mesa's OSMesa, software llvmpipe (the default; upstream Mesa dropped OSMesa in 25.1)
//   egl     EGL on Mesa's surfaceless platform, rendering into a framebuffer object: the path that
//           survives OSMesa's removal
// The environment variable ACTUATOR_GL_BACKEND chooses one; SetBackend() does the same in code.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "render/mesh_renderer.h"
#include "render/plot.h"

namespace render {

// What a backend module exports (C linkage: `actuator_render_backend`).
struct BackendApi {
    int abiVersion;  // kBackendAbiVersion of the module's build
    const char* name;
    std::unique_ptr<MeshRenderer> (*createMeshRenderer)(const RenderDef& def, std::string* error);
    std::unique_ptr<PlotRenderer> (*createPlotRenderer)(int width, int height, std::string* error);
};
constexpr int kBackendAbiVersion = 2;

const std::vector<std::string>& BackendNames();  // osmesa, egl

// Chooses the backend for renderers created from now on. False with *error set for an unknown name.
bool SetBackend(const std::string& name, std::string* error);

// The chosen backend, loaded on first call; null with *error set when the module cannot be loaded.
const BackendApi* LoadBackend(std::string* error);

}  // namespace render
