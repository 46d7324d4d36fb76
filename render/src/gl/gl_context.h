// An offscreen OpenGL 3.3+ core context with its own colour buffer. Each backend module implements
// CreateGlContext(): OSMesa renders into client memory, EGL (surfaceless) into a framebuffer object.
// Private to the backend modules.
#pragma once

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
    // The buffer's pixels after the frame: RGBA8, bottom row first (OpenGL's order). Valid until
    // the next MakeCurrent with another size.
    virtual const std::vector<std::uint8_t>& FinishAndGetPixels() = 0;
    virtual std::string Description() const = 0;  // e.g. "4.5 (Core Profile) Mesa 22.3.6, llvmpipe (osmesa)"
};

// Defined once per module (osmesa_context.cpp or egl_context.cpp). Null with *error set on failure.
std::unique_ptr<GlContext> CreateGlContext(std::string* error);
extern const char* const kBackendName;

}  // namespace render
