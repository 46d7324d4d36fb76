#include "overlay_context.h"

#include <algorithm>

#include <filesystem>

#include "imgui_impl_opengl3.h"

namespace render {

bool OverlayContext::Create(float textScale, std::string* error) {
    IMGUI_CHECKVERSION();
    context_ = ImGui::CreateContext();
    ImGui::SetCurrentContext(context_);
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.LogFilename = nullptr;
    fontSize_ = 19.0f * textScale;
    // DejaVu Sans from Debian's fonts-dejavu-core; ImGui's built-in bitmap font if it is missing
    // (still legible, smaller).
    const char* regular = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
    const char* bold = "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf";
    std::error_code ec;
    if (std::filesystem::exists(regular, ec) && std::filesystem::exists(bold, ec)) {
        textFont_ = io.Fonts->AddFontFromFileTTF(regular, fontSize_);
        titleFont_ = io.Fonts->AddFontFromFileTTF(bold, 26.0f * textScale);
    }
    if (!textFont_ || !titleFont_) {
        ImFontConfig config;
        config.SizePixels = 13.0f * textScale;
        textFont_ = titleFont_ = io.Fonts->AddFontDefault(&config);
    }
    if (!ImGui_ImplOpenGL3_Init("#version 330 core")) {
        *error = "Dear ImGui's OpenGL 3 backend failed to start";
        return false;
    }
    backendStarted_ = true;
    return true;
}

OverlayContext::~OverlayContext() {
    if (!context_) return;
    ImGui::SetCurrentContext(context_);
    if (backendStarted_) ImGui_ImplOpenGL3_Shutdown();
    ImGui::DestroyContext(context_);
}

ImDrawList* OverlayContext::Begin(int width, int height) {
    ImGui::SetCurrentContext(context_);
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(float(width), float(height));
    io.DeltaTime = 1.0f / 30;
    ImGui_ImplOpenGL3_NewFrame();
    ImGui::NewFrame();
    return ImGui::GetForegroundDrawList();
}

void OverlayContext::End() {
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void OverlayContext::DrawTitle(ImDrawList* draw, float size, ImVec2 at, float maxWidth, ImU32 colour, const std::string& title) const {
    float width = titleFont_->CalcTextSizeA(size, FLT_MAX, 0, title.c_str()).x;
    if (width > maxWidth) size = std::max(size * 0.65f, size * maxWidth / width);
    std::string text = title;
    while (text.size() > 4 && titleFont_->CalcTextSizeA(size, FLT_MAX, 0, text.c_str()).x > maxWidth) {
        text.resize(text.size() - 4);
        while (!text.empty() && (static_cast<unsigned char>(text.back()) & 0xC0) == 0x80) text.pop_back();  // whole UTF-8 characters
        text += "...";
    }
    draw->AddText(titleFont_, size, at, colour, text.c_str());
}

}  // namespace render
