// EGL on Mesa's surfaceless platform: no window system and no pbuffer, so the frame goes to a
// framebuffer object and is read back with glReadPixels (bottom row first, like OSMesa's buffer).
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <GL/glext.h>

#include "gl_context.h"

namespace render {

const char* const kBackendName = "egl";

namespace {

class EglContext final : public GlContext {
public:
    EglContext(EGLDisplay display, EGLContext context) : display_(display), context_(context) {}
    ~EglContext() override {
        if (framebuffer_) {
            eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_);
            glDeleteFramebuffers(1, &framebuffer_);
            glDeleteRenderbuffers(2, renderbuffers_);
        }
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display_, context_);
    }

    bool MakeCurrent(int width, int height) override {
        if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) return false;
        RememberDescription();
        if (!framebuffer_) {
            glGenFramebuffers(1, &framebuffer_);
            glGenRenderbuffers(2, renderbuffers_);
        }
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
        if (width != width_ || height != height_) {
            glBindRenderbuffer(GL_RENDERBUFFER, renderbuffers_[0]);
            glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
            glBindRenderbuffer(GL_RENDERBUFFER, renderbuffers_[1]);
            glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
            glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, renderbuffers_[0]);
            glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, renderbuffers_[1]);
            if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) return false;
            buffer_.resize(static_cast<size_t>(width) * height * 4);  // glReadPixels fills it
            width_ = width;
            height_ = height;
        }
        return true;
    }

    const std::uint8_t* FinishAndGetPixels() override {
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, buffer_.data());
        return buffer_.data();
    }

    const char* BackendLabel() const override { return "egl surfaceless"; }

private:
    EGLDisplay display_;
    EGLContext context_;
    GLuint framebuffer_ = 0, renderbuffers_[2] = {0, 0};
    std::vector<std::uint8_t> buffer_;
    int width_ = 0, height_ = 0;
};

}  // namespace

std::unique_ptr<GlContext> CreateGlContext(std::string* error) {
    auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!getPlatformDisplay) {
        if (error) *error = "EGL has no eglGetPlatformDisplayEXT (needs Mesa's EGL)";
        return nullptr;
    }
    EGLDisplay display = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    EGLint major = 0, minor = 0;
    if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor)) {
        if (error) *error = "EGL could not open Mesa's surfaceless display";
        return nullptr;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        if (error) *error = "EGL has no desktop OpenGL";
        return nullptr;
    }
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3, EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                 EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    if (context == EGL_NO_CONTEXT) {
        if (error) *error = "EGL could not create an OpenGL 3.3 core context";
        return nullptr;
    }
    return std::make_unique<EglContext>(display, context);
}

}  // namespace render
