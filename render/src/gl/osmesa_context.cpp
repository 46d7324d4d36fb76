#include <GL/osmesa.h>
#include <GL/gl.h>
#include <GL/glext.h>

#include "gl_context.h"

namespace render {

const char* const kBackendName = "osmesa";

namespace {

class OsMesaContext final : public GlContext {
public:
    explicit OsMesaContext(OSMesaContext context) : context_(context) {}
    ~OsMesaContext() override { OSMesaDestroyContext(context_); }

    bool MakeCurrent(int width, int height) override {
        if (width != width_ || height != height_) {
            buffer_.assign(static_cast<size_t>(width) * height * 4, 0);
            width_ = width;
            height_ = height;
        }
        if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, width, height)) return false;
        RememberDescription();
        return true;
    }

    const std::vector<std::uint8_t>& FinishAndGetPixels() override {
        glFinish();
        return buffer_;
    }

    const char* BackendLabel() const override { return "osmesa"; }

private:
    OSMesaContext context_;
    std::vector<std::uint8_t> buffer_;
    int width_ = 0, height_ = 0;
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
