// Pictures of actuator meshes: one or more panels side by side under one camera and one scale,
// shaded from two sides (the tube is open and its inside shows), coloured by displacement, strain
// or given values with a colour bar, optional wireframe, and Dear ImGui text overlays.
//
// The implementation lives in a GL backend module (OSMesa or EGL) that is loaded the first time a
// renderer is created: commands that draw nothing never map OpenGL or LLVM.
#pragma once

#include <memory>
#include <string>

#include "render/image.h"
#include "render/scene.h"

namespace render {

class MeshRenderer {
public:
    // Loads the backend (see backend.h) on first use. Null with *error set when it cannot be loaded
    // or no OpenGL context can be made.
    static std::unique_ptr<MeshRenderer> Create(const RenderDef& def, std::string* error);
    virtual ~MeshRenderer() = default;

    virtual Image Render(const Scene& scene) = 0;
    virtual const RenderDef& Def() const = 0;
    virtual std::string Description() const = 0;  // the GL implementation and backend
};

}  // namespace render
