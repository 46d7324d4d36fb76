// An offscreen OpenGL 3.3+ core context with its own colour buffer. Each backend module implements
// CreateGlContext(): OSMesa renders into client memory, EGL (surfaceless) into a framebuffer object.
// Private to the backend modules.
#pragma once

#include <GL/gl.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace render {

class GlContext {
public:
    virtual ~GlContext() = default;
    // Makes the context current on this thread with a width x height RGBA buffer (resized if needed).
    virtual bool MakeCurrent(int width, int height) = 0;
    // The buffer's pixels after the frame: RGBA8, bottom row first (OpenGL's order), width x height
    // of the last MakeCurrent. Valid until the next MakeCurrent.
    virtual const std::uint8_t* FinishAndGetPixels() = 0;
    // E.g. "4.5 (Core Profile) Mesa 22.3.6, llvmpipe (osmesa)". Read when the context was first made
    // current: later another context (a plot's) may be current on this thread, or none.
    std::string Description() const { return description_.empty() ? std::string("not yet made current (") + BackendLabel() + ")" : description_; }

protected:
    virtual const char* BackendLabel() const = 0;
    // Call right after the context has been made current.
    void RememberDescription() {
        if (!description_.empty()) return;
        auto text = [](GLenum name) {
            const GLubyte* value = glGetString(name);
            return value ? std::string(reinterpret_cast<const char*>(value)) : std::string("unknown");
        };
        description_ = text(GL_VERSION) + ", " + text(GL_RENDERER) + " (" + BackendLabel() + ")";
    }

private:
    std::string description_;
};

// Defined once per module (osmesa_context.cpp or egl_context.cpp). Null with *error set on failure.
std::unique_ptr<GlContext> CreateGlContext(std::string* error);
extern const char* const kBackendName;

}  // namespace render
