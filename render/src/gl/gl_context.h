// An offscreen OpenGL 3.3+ core context with its own colour buffer. Kept behind this interface
// because upstream Mesa dropped OSMesa in 25.1: an EGL (surfaceless) backend can slot in here.
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
    // The buffer's pixels after glFinish(): RGBA8, bottom row first (OpenGL's order). Valid until
    // the next MakeCurrent with another size.
    virtual const std::vector<std::uint8_t>& FinishAndGetPixels() = 0;
    virtual std::string Description() const = 0;  // e.g. "4.5 (Core Profile) Mesa 22.3.6, llvmpipe"
};

// The OSMesa (software, llvmpipe) backend. Null with *error set when no context can be made.
std::unique_ptr<GlContext> CreateOsMesaContext(std::string* error);

}  // namespace render
