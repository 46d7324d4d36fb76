// Pictures of actuator meshes: one or more panels side by side under one camera and one scale,
// shaded from two sides (the tube is open and its inside shows), coloured by displacement or spring
// strain with a colour bar, optional spring wireframe, and Dear ImGui text overlays.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/image.h"
#include "sim/mesh.h"

namespace render {

enum class ColorBy {
    Shading,       // one neutral material
    Displacement,  // distance of each vertex from the reference mesh (mesh units)
    Strain,        // mean |length / rest length - 1| over a vertex's springs (percent)
};

enum class Background { White, Transparent };

struct RenderDef {
    int width = 1024;                 // output image, pixels
    int height = 768;
    int supersample = 2;              // rendered at this multiple and box-filtered down (anti-aliasing)
    Background background = Background::White;
    ColorBy colorBy = ColorBy::Displacement;
    bool wireframe = false;           // draw the springs over the surface
    bool overlay = true;              // title, parameter lines, captions and colour bar
    double elevationDegrees = 16;     // camera height above the actuator's mid-plane
    double azimuthDegrees = 30;       // camera direction around the actuator's axis
    double textScale = 0;             // body text is 19 px times this; 0: follows the image height
};
RenderDef DefaultRenderDef();

struct Panel {
    sim::Positions positions;
    sim::Positions reference;    // rest mesh for displacement and strain; empty: at rest, plain material
    std::string caption;         // under the panel, e.g. "before" or "after 10000 iterations"
    double rotationDegrees = 0;  // about the actuator's axis (turntables)
};

// A cylinder about the z axis that holds the meshes, whatever their rotation about it: framing on
// it keeps the camera still across a turntable or time-lapse.
struct Framing {
    double radius = 1;
    double zMin = 0;
    double zMax = 1;
};
Framing FrameMeshes(const std::vector<const sim::Positions*>& meshes);

struct Scene {
    sim::MeshDef mesh;
    std::vector<Panel> panels;           // side by side, one camera, one scale
    int columns = 0;                     // > 0: panels fill a grid this many wide (contact sheets)
    std::string title;
    std::vector<std::string> lines;      // overlay text under the title
    std::optional<Framing> framing;      // default: frame every panel
    std::optional<double> colorMax;      // top of the colour scale; default: the largest value shown
                                         // (for strain, the 98th percentile: see RobustColorMax)
};

// Per-vertex values of a colour mode (exposed for tests and for fixed scales across sequences).
std::vector<double> VertexValues(ColorBy colorBy, const sim::MeshDef& mesh, const sim::Positions& positions,
                                 const sim::Positions& reference);

class MeshRenderer {
public:
    // Null with *error set when no OpenGL context can be made.
    static std::unique_ptr<MeshRenderer> Create(const RenderDef& def, std::string* error);
    ~MeshRenderer();
    MeshRenderer(const MeshRenderer&) = delete;
    MeshRenderer& operator=(const MeshRenderer&) = delete;

    Image Render(const Scene& scene);
    const RenderDef& Def() const;
    std::string Description() const;  // the GL implementation

private:
    struct State;
    explicit MeshRenderer(std::unique_ptr<State> state);
    std::unique_ptr<State> state_;
};

}  // namespace render
