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
    // Draws the next scenes width x height (the same supersampling, text and camera): a figure whose
    // size follows its content (a contact sheet) reuses its renderer; a new one costs as much as a
    // small figure (the GL context, shaders and font atlas). False when the text's size follows the
    // height (textScale 0): then a new renderer is needed.
    virtual bool Resize(int width, int height) = 0;
    virtual const RenderDef& Def() const = 0;
    virtual std::string Description() const = 0;  // the GL implementation and backend
};

}  // namespace render
