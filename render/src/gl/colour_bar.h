// The one colour bar of every picture (mesh colour scales and heat maps): the map's gradient, nice
// ticks with both ends always labelled, "> max" when values above the top were clipped, and marks
// such as a material's stretch limit. Private to the backend modules.
#pragma once

#include <imgui.h>

#include <string>
#include <vector>

#include "overlay_context.h"
#include "render/colormap.h"
#include "render/scene.h"

namespace render {

struct ColourBar {
    float x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // the gradient's rectangle, frame-buffer pixels, y down
    double min = 0, max = 1;                // values at the bottom and the top
    bool clippedTop = false;                // values above `max` exist (drawn in the top colour)
    std::string label;                      // above the bar; may hold a line break
    float labelX = -1;                      // where the label starts; < 0: at the bar
    std::vector<ScaleMark> marks;
    Rgb (*map)(double t) = &ViridisColor;   // t in [0, 1] from bottom to top
};

void DrawColourBar(ImDrawList* draw, const OverlayContext& overlay, const ColourBar& bar);

}  // namespace render
