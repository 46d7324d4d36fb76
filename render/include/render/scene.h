// What a mesh picture shows, as plain data: panels of positions over one surface, a camera, a colour
// mode, text. No GL here: scenes are built by the app and drawn by a backend loaded at run time.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/colormap.h"
#include "sim/mesh.h"
#include "sim/names.h"
#include "sim/surface.h"

namespace render {

enum class ColorBy {
    Shading,       // one neutral material
    Displacement,  // distance of each vertex from the reference mesh (model units)
    Strain,        // mean |length / rest length - 1| over a vertex's edges (percent)
    Values,        // the panel's own per-vertex values (e.g. principal stretch), labelled by the scene
};

enum class Background { White, Transparent };

struct RenderDef {
    int width = 1024;                 // output image, pixels
    int height = 768;
    int supersample = 2;              // rendered at this multiple and box-filtered down (anti-aliasing)
    Background background = Background::White;
    ColorBy colorBy = ColorBy::Displacement;
    bool wireframe = false;           // draw the edges (springs) over the surface
    bool overlay = true;              // title, parameter lines, captions and colour bar
    double elevationDegrees = 16;     // camera height above the actuator's mid-plane
    double azimuthDegrees = 30;       // camera direction around the actuator's axis
    double textScale = 0;             // body text is 19 px times this; 0: follows the image height
};
RenderDef DefaultRenderDef();

// A line segment drawn over the surface (fibres, cut edges), coloured by `value` on the scene's map,
// or a mark (a painted stripe) drawn thick in red over everything else.
struct Segment {
    float a[3], b[3];
    float value = 0;
    bool mark = false;
};

struct Panel {
    sim::Positions positions;
    sim::Positions reference;    // rest mesh for displacement and strain; empty: at rest, plain material
    std::string caption;         // under the panel, e.g. "before" or "after 10000 iterations"
    double rotationDegrees = 0;  // about the actuator's axis (turntables)
    std::vector<double> values;  // per vertex, for ColorBy::Values
    std::vector<Segment> segments;
};

// A cylinder about the z axis that holds the meshes, whatever their rotation about it: framing on
// it keeps the camera still across a turntable or time-lapse.
struct Framing {
    double radius = 1;
    double zMin = 0;
    double zMax = 1;
};
// Non-finite coordinates are left out: a failed run still frames what it has.
Framing FrameMeshes(const std::vector<const sim::Positions*>& meshes);

// A mark on the colour bar, e.g. the material's stretch limit.
struct ScaleMark {
    double value = 0;
    std::string label;
};

// A named part in a fixed colour (an exploded assembly's pieces).
struct Category {
    std::string label;  // may hold a line break
    Rgb color;
};

struct Scene {
    std::shared_ptr<const sim::Surface> surface;  // the panels' triangles and edges
    std::vector<Panel> panels;           // side by side, one camera, one scale
    int columns = 0;                     // > 0: panels fill a grid this many wide (contact sheets)
    // A grid laid out on two parameters (a 2-D sweep): a label per column above it and per row at
    // its left, and each axis's title. Empty: no labels.
    std::vector<std::string> columnLabels, rowLabels;
    std::string columnTitle, rowTitle;
    std::string title;
    std::vector<std::string> lines;      // overlay text under the title
    std::optional<Framing> framing;      // default: frame every panel
    std::optional<ColorBy> colorBy;      // default: the renderer's mode (RenderDef::colorBy)
    std::optional<double> colorMin;      // bottom of the colour scale; default 0
    std::optional<double> colorMax;      // top of the colour scale; default: the largest value shown
                                         // (for strain, the 98th percentile: see RobustColorMax)
    std::string colorLabel;              // colour bar title; default from the colour mode
    std::vector<ScaleMark> scaleMarks;   // lines across the colour bar
    // Parts, not a scale: with ColorBy::Values a vertex's value is the index of its category, drawn
    // in the category's colour, and a legend of swatches replaces the colour bar.
    std::vector<Category> categories;
};

// Per-vertex values of a colour mode (exposed for tests and for fixed scales across sequences).
// Vertices with a non-finite coordinate get NaN.
std::vector<double> VertexValues(ColorBy colorBy, const sim::Surface& surface, const Panel& panel);

// Spring strain has outliers: at a pinch where the tube meets its axis, rest lengths are nearly zero
// and a few springs reach hundreds of percent. The 98th percentile of the finite values keeps the
// rest readable.
double RobustColorMax(const std::vector<std::vector<double>>& values);

}  // namespace render

template <>
struct sim::EnumNames<render::ColorBy> {
    static constexpr std::array<std::pair<render::ColorBy, const char*>, 3> table{
        {{render::ColorBy::Displacement, "displacement"}, {render::ColorBy::Strain, "strain"}, {render::ColorBy::Shading, "none"}}};
};
template <>
struct sim::EnumNames<render::Background> {
    static constexpr std::array<std::pair<render::Background, const char*>, 2> table{
        {{render::Background::White, "white"}, {render::Background::Transparent, "transparent"}}};
};
