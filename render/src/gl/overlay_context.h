// Dear ImGui set up for drawing into offscreen frames: its own context, DejaVu Sans fonts sized to
// the image, and the OpenGL 3 backend. Text and 2-D shapes go through foreground draw lists, which
// have no window and so no hidden first frame. Private to render/.
#pragma once

#include <imgui.h>

#include <string>
#include <vector>

namespace render {

class OverlayContext {
public:
    // textScale: pixels of the frame buffer per pixel of body text at 19 px (supersampling included).
    // Needs a current GL context. False with *error set on failure.
    bool Create(float textScale, std::string* error);
    ~OverlayContext();

    // Draw between Begin and End; End renders the draw lists into the current framebuffer.
    ImDrawList* Begin(int width, int height);
    void End();

    ImFont* TextFont() const { return textFont_; }
    ImFont* TitleFont() const { return titleFont_; }
    float FontSize() const { return fontSize_; }  // body text size in frame-buffer pixels

    // A title broken at spaces into lines that fit `maxWidth` (`size` shrunk to no less than 80 % first
    // when that saves a line), at most `maxLines`; a title longer still ends its last line with "..."
    // after a whole word. Never cut inside a word or a number.
    struct WrappedTitle {
        float size = 0;
        std::vector<std::string> lines;
        float Height() const { return lines.empty() ? 0.0f : size * (1.0f + 1.12f * (lines.size() - 1)); }
    };
    WrappedTitle WrapTitle(float size, float maxWidth, const std::string& title, int maxLines = 3) const;
    // Draws WrapTitle's lines from (x, y); returns the height used.
    float DrawTitle(ImDrawList* draw, float size, ImVec2 at, float maxWidth, ImU32 colour, const std::string& title) const;

private:
    ImGuiContext* context_ = nullptr;
    bool backendStarted_ = false;
    ImFont* textFont_ = nullptr;
    ImFont* titleFont_ = nullptr;
    float fontSize_ = 19;
};

}  // namespace render
