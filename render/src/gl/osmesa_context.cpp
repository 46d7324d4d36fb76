#include <GL/osmesa.h>
#include <GL/gl.h>
#include <GL/glext.h>

#include <memory>

#include "gl_context.h"

namespace render {

const char* const kBackendName = "osmesa";

namespace {

class OsMesaContext final : public GlContext {
public:
    explicit OsMesaContext(OSMesaContext context) : context_(context) {}
    ~OsMesaContext() override { OSMesaDestroyContext(context_); }

    bool MakeCurrent(int width, int height) override {
        // Grown, never shrunk, and not zeroed: every frame starts with a clear. A contact sheet's
        // renderer changes size with each sheet, and zeroing a fresh buffer of up to 100 MB (its
        // pages faulted in) cost more than drawing the sheet.
        const size_t bytes = static_cast<size_t>(width) * height * 4;
        if (bytes > capacity_) {
            buffer_ = std::make_unique_for_overwrite<std::uint8_t[]>(bytes);
            capacity_ = bytes;
        }
        if (!OSMesaMakeCurrent(context_, buffer_.get(), GL_UNSIGNED_BYTE, width, height)) return false;
        RememberDescription();
        return true;
    }

    const std::uint8_t* FinishAndGetPixels() override {
        glFinish();
        return buffer_.get();
    }

    const char* BackendLabel() const override { return "osmesa"; }

private:
    OSMesaContext context_;
    std::unique_ptr<std::uint8_t[]> buffer_;
    size_t capacity_ = 0;
};

}  // namespace

std::unique_ptr<GlContext> CreateGlContext(std::string* error) {
    // Debian 12's OSMesa gives a 4.5 core profile on llvmpipe; 3.3 is all the renderer needs.
    const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_STENCIL_BITS, 0,
                              OSMESA_PROFILE, OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 3,
                              OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
    OSMesaContext context = OSMesaCreateContextAttribs(attributes, nullptr);
    if (!context) {
        if (error) *error = "OSMesa could not create an OpenGL 3.3 core context";
        return nullptr;
    }
    return std::make_unique<OsMesaContext>(context);
}

}  // namespace render
