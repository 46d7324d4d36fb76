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
    // Glyph metrics exist once the atlas is built: text is measured for the layout (wrapped titles,
    // legends) before the first frame would build it.
    io.Fonts->Build();
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

OverlayContext::WrappedTitle OverlayContext::WrapTitle(float size, float maxWidth, const std::string& title, int maxLines) const {
    std::vector<std::string> words;
    for (size_t at = 0; at < title.size();) {
        const size_t space = title.find(' ', at);
        const size_t end = space == std::string::npos ? title.size() : space;
        if (end > at) words.push_back(title.substr(at, end - at));
        at = end + 1;
    }
    auto widthOf = [&](float s, const std::string& text) { return titleFont_->CalcTextSizeA(s, FLT_MAX, 0, text.c_str()).x; };
    // Greedy filling; a separator "-" between title parts stays with the word after it.
    auto wrap = [&](float s) {
        std::vector<std::string> lines;
        for (const auto& word : words) {
            if (!lines.empty() && widthOf(s, lines.back() + " " + word) <= maxWidth) lines.back() += " " + word;
            else lines.push_back(word);
        }
        for (size_t k = 1; k < lines.size(); ++k)
            if (lines[k - 1].size() > 2 && lines[k - 1].compare(lines[k - 1].size() - 2, 2, " -") == 0) {
                lines[k - 1].resize(lines[k - 1].size() - 2);
                lines[k] = "- " + lines[k];
            }
        return lines;
    };
    WrappedTitle wrapped{size, wrap(size)};
    if (wrapped.lines.size() > 1) {
        const float smaller = size * 0.8f;
        auto fewer = wrap(smaller);
        if (fewer.size() < wrapped.lines.size()) wrapped = {smaller, fewer};
    }
    if (static_cast<int>(wrapped.lines.size()) > maxLines) {
        wrapped.lines.resize(static_cast<size_t>(maxLines));
        std::string& last = wrapped.lines.back();
        while (last.find(' ') != std::string::npos && widthOf(wrapped.size, last + " ...") > maxWidth) last.resize(last.rfind(' '));
        last += " ...";
    }
    return wrapped;
}

float OverlayContext::DrawTitle(ImDrawList* draw, float size, ImVec2 at, float maxWidth, ImU32 colour, const std::string& title) const {
    const WrappedTitle wrapped = WrapTitle(size, maxWidth, title);
    for (size_t k = 0; k < wrapped.lines.size(); ++k)
        draw->AddText(titleFont_, wrapped.size, ImVec2(at.x, at.y + wrapped.size * 1.12f * k), colour, wrapped.lines[k].c_str());
    return wrapped.Height();
}

}  // namespace render
