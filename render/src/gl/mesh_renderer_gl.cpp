// [SECTION] Colours
// [SECTION] GL resources: shaders and buffers
// [SECTION] Camera and layout
// [SECTION] Overlay (Dear ImGui draw lists)
// [SECTION] Render
#include <GL/gl.h>
#include <GL/glext.h>

#include "render/mesh_renderer.h"

#include <imgui.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "colour_bar.h"
#include "gl_context.h"
#include "overlay_context.h"
#include "render/colormap.h"

namespace render {

namespace {

using Vec3 = Eigen::Vector3f;

Vec3 Viridis(double t) {
    const Rgb c = ViridisColor(t);
    return Vec3(c.r, c.g, c.b);
}

const Vec3 kNeutralMaterial(0.62f, 0.70f, 0.80f);  // Shading mode: a pale blue-grey silicone

}  // namespace

// ---------------------------------------------------------------------------------------------
// [SECTION] GL resources
// ---------------------------------------------------------------------------------------------
namespace {

const char* kSurfaceVertexShader = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 color;
uniform mat4 viewProjection;
out vec3 vNormal;
out vec3 vColor;
void main() {
    vNormal = normal;
    vColor = color;
    gl_Position = viewProjection * vec4(position, 1.0);
}
)";

// Two-sided lighting: faces seen from inside the open tube are lit with their normal flipped and
// drawn a little darker, so inside and outside read apart. Key light upper left, fill light right.
const char* kSurfaceFragmentShader = R"(#version 330 core
in vec3 vNormal;
in vec3 vColor;
uniform vec3 toCamera;
uniform vec3 keyLight;
uniform vec3 fillLight;
out vec4 fragColor;
void main() {
    vec3 n = normalize(vNormal);
    bool inside = dot(n, toCamera) < 0.0;
    if (inside) n = -n;
    float diffuse = 0.38 + 0.52 * max(dot(n, keyLight), 0.0) + 0.22 * max(dot(n, fillLight), 0.0);
    float specular = 0.18 * pow(max(dot(reflect(-keyLight, n), toCamera), 0.0), 28.0);
    vec3 base = inside ? vColor * 0.62 : vColor;
    fragColor = vec4(min(base * diffuse + vec3(specular), vec3(1.0)), 1.0);
}
)";

const char* kLineVertexShader = R"(#version 330 core
layout(location = 0) in vec3 position;
uniform mat4 viewProjection;
void main() { gl_Position = viewProjection * vec4(position, 1.0); }
)";

const char* kLineFragmentShader = R"(#version 330 core
uniform vec4 lineColor;
out vec4 fragColor;
void main() { fragColor = lineColor; }
)";

GLuint CompileProgram(const char* vertexSource, const char* fragmentSource, std::string* error) {
    auto compile = [&](GLenum type, const char* source) -> GLuint {
        GLuint shader = glCreateShader(type);
        glShaderSource(shader, 1, &source, nullptr);
        glCompileShader(shader);
        GLint ok = 0;
        glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
        if (!ok) {
            char log[1024];
            glGetShaderInfoLog(shader, sizeof log, nullptr, log);
            *error = std::string("shader compile failed: ") + log;
            glDeleteShader(shader);
            return 0;
        }
        return shader;
    };
    const GLuint vs = compile(GL_VERTEX_SHADER, vertexSource);
    if (!vs) return 0;
    const GLuint fs = compile(GL_FRAGMENT_SHADER, fragmentSource);
    if (!fs) return 0;
    const GLuint program = glCreateProgram();
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        *error = "shader link failed";
        return 0;
    }
    return program;
}

// Interleaved vertex data of one panel: position, normal, colour.
struct SurfaceVertex {
    float position[3], normal[3], color[3];
};

}  // namespace

class MeshRendererGl final : public MeshRenderer {
public:
    Image Render(const Scene& scene) override;
    bool Resize(int width, int height) override {
        if (def.textScale <= 0 && height != def.height) return false;
        def.width = width;
        def.height = height;
        return true;
    }
    const RenderDef& Def() const override { return def; }
    std::string Description() const override { return context->Description(); }

    RenderDef def;
    std::unique_ptr<GlContext> context;
    GLuint surfaceProgram = 0, lineProgram = 0;
    GLuint vao = 0, vertexBuffer = 0, triangleBuffer = 0, edgeBuffer = 0, segmentBuffer = 0;
    sim::Surface indexed;  // the surface the index buffers hold
    OverlayContext overlay;

    void EnsureIndexBuffers(const sim::Surface& surface) {
        if (surface == indexed) return;
        std::vector<GLuint> edges;
        for (const auto& [a, b] : surface.edges) edges.insert(edges.end(), {GLuint(a), GLuint(b)});
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, edgeBuffer);
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, edges.size() * sizeof(GLuint), edges.data(), GL_STATIC_DRAW);
        indexed = surface;
    }
};

std::unique_ptr<MeshRenderer> CreateGlMeshRenderer(const RenderDef& def, std::string* error) {
    auto r = std::make_unique<MeshRendererGl>();
    r->def = def;
    r->context = CreateGlContext(error);
    if (!r->context) return nullptr;
    const int bufferWidth = def.width * def.supersample, bufferHeight = def.height * def.supersample;
    if (!r->context->MakeCurrent(bufferWidth, bufferHeight)) {
        *error = std::string(kBackendName) + " could not make the context current";
        return nullptr;
    }
    r->surfaceProgram = CompileProgram(kSurfaceVertexShader, kSurfaceFragmentShader, error);
    r->lineProgram = CompileProgram(kLineVertexShader, kLineFragmentShader, error);
    if (!r->surfaceProgram || !r->lineProgram) return nullptr;
    glGenVertexArrays(1, &r->vao);
    glGenBuffers(1, &r->vertexBuffer);
    glGenBuffers(1, &r->triangleBuffer);
    glGenBuffers(1, &r->edgeBuffer);
    glGenBuffers(1, &r->segmentBuffer);

    // Text follows the image size, but never below ~16 px body text: small images stay legible.
    const float textScale = def.textScale > 0 ? float(def.textScale) : std::max(0.85f, def.height / 768.0f);
    if (!r->overlay.Create(def.supersample * textScale, error)) return nullptr;
    return r;
}

// ---------------------------------------------------------------------------------------------
// [SECTION] Camera and layout
// ---------------------------------------------------------------------------------------------
namespace {

struct Rect {
    float x0, y0, x1, y1;  // pixels of the supersampled buffer, y down
    float Width() const { return x1 - x0; }
    float Height() const { return y1 - y0; }
};

// Orthographic camera on the framing cylinder: the same scale for every panel of a scene.
Eigen::Matrix4f ViewProjection(const Framing& framing, const RenderDef& def, float aspect, Vec3* toCamera) {
    const double el = def.elevationDegrees * std::numbers::pi / 180, az = def.azimuthDegrees * std::numbers::pi / 180;
    const Vec3 direction(float(std::cos(el) * std::sin(az)), float(-std::cos(el) * std::cos(az)), float(std::sin(el)));
    const float halfHeightZ = float(framing.zMax - framing.zMin) / 2;
    const Vec3 center(0, 0, float(framing.zMax + framing.zMin) / 2);
    const float r = float(framing.radius);
    const float distance = 4 * (r + halfHeightZ) + 1;
    const Vec3 eye = center + direction * distance;

    const Vec3 forward = (center - eye).normalized();
    const Vec3 right = forward.cross(Vec3::UnitZ()).normalized();
    const Vec3 up = right.cross(forward);
    Eigen::Matrix4f view = Eigen::Matrix4f::Identity();
    view.block<1, 3>(0, 0) = right.transpose();
    view.block<1, 3>(1, 0) = up.transpose();
    view.block<1, 3>(2, 0) = -forward.transpose();
    view(0, 3) = -right.dot(eye);
    view(1, 3) = -up.dot(eye);
    view(2, 3) = forward.dot(eye);

    // Extent of the framing cylinder on screen, with a margin.
    float halfWidth = r * 1.06f;
    float halfHeight = (halfHeightZ * float(std::cos(el)) + r * float(std::sin(el))) * 1.06f;
    if (halfWidth / halfHeight < aspect) halfWidth = halfHeight * aspect;
    else halfHeight = halfWidth / aspect;
    const float nearPlane = distance - 2 * (r + halfHeightZ) - 1, farPlane = distance + 2 * (r + halfHeightZ) + 1;
    Eigen::Matrix4f projection = Eigen::Matrix4f::Zero();
    projection(0, 0) = 1 / halfWidth;
    projection(1, 1) = 1 / halfHeight;
    projection(2, 2) = -2 / (farPlane - nearPlane);
    projection(2, 3) = -(farPlane + nearPlane) / (farPlane - nearPlane);
    projection(3, 3) = 1;
    *toCamera = direction;
    return projection * view;
}

// Normals per vertex, area-weighted over the triangles around it, pointing out of the tube.
std::vector<Vec3> OutwardNormals(const sim::Surface& surface, const std::vector<Vec3>& p) {
    std::vector<Vec3> normals(p.size(), Vec3::Zero());
    for (const auto& t : surface.triangles) {
        const Vec3 n = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]);
        if (!n.allFinite()) continue;
        for (int k : t) normals[k] += n;
    }
    for (auto& n : normals) {
        const float length = n.norm();
        n = length > 0 ? Vec3(n / length) : Vec3::UnitX();
    }
    return normals;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// [SECTION] Overlay
// ---------------------------------------------------------------------------------------------
namespace {


}  // namespace

// ---------------------------------------------------------------------------------------------
// [SECTION] Render
// ---------------------------------------------------------------------------------------------

Image MeshRendererGl::Render(const Scene& scene) {
    const int width = def.width * def.supersample, height = def.height * def.supersample;
    context->MakeCurrent(width, height);
    static const sim::Surface kNoSurface;
    const sim::Surface& surface = scene.surface ? *scene.surface : kNoSurface;
    EnsureIndexBuffers(surface);
    const ColorBy colorBy = scene.colorBy.value_or(def.colorBy);

    // Layout: text band on top, captions below, colour bar strip on the right.
    const bool coloured = colorBy != ColorBy::Shading;
    const float fontSize = overlay.FontSize();
    // A long title wraps onto more lines (never cut mid-number): the text band grows with it.
    const float titleExtra = def.overlay ? std::max(0.0f, overlay.WrapTitle(fontSize * 1.37f, width - 1.4f * fontSize, scene.title).Height() - fontSize * 1.37f) : 0.0f;
    const float top = def.overlay ? fontSize * (2.2f + 1.25f * scene.lines.size()) + titleExtra : 0.0f;
    const float bottom = def.overlay ? fontSize * 1.8f : 0.0f;
    // A legend of parts is as wide as its longest line, beside a swatch.
    const bool legend = colorBy == ColorBy::Values && !scene.categories.empty();
    float legendText = 0;
    for (const Category& category : scene.categories)
        legendText = std::max(legendText, overlay.TextFont()->CalcTextSizeA(fontSize, FLT_MAX, 0, category.label.c_str()).x);
    const float barStrip = !def.overlay || !coloured ? 0.0f
                           : legend              ? legendText + fontSize * 3.0f
                                                 : std::max(width * 0.11f, fontSize * 6.0f);
    // A grid on two parameters keeps a band above for the column labels and one at the left for the
    // row labels, each under its axis title.
    const bool axisLabels = def.overlay && (!scene.columnLabels.empty() || !scene.rowLabels.empty());
    float rowBand = 0;
    if (axisLabels) {
        float labels = 0, title = 0;
        for (const std::string& label : scene.rowLabels) labels = std::max(labels, overlay.TextFont()->CalcTextSizeA(fontSize, FLT_MAX, 0, label.c_str()).x);
        for (size_t at = 0; at <= scene.rowTitle.size();) {  // the title is drawn one word per line
            const size_t end = std::min(scene.rowTitle.find(' ', at), scene.rowTitle.size());
            const std::string word = scene.rowTitle.substr(at, end - at);
            title = std::max(title, overlay.TitleFont()->CalcTextSizeA(fontSize, FLT_MAX, 0, word.c_str()).x);
            at = end + 1;
        }
        rowBand = labels + title + fontSize * 1.4f;
    }
    const float columnBand = axisLabels ? fontSize * 2.7f : 0.0f;
    const Rect panelArea{rowBand, top + columnBand, width - barStrip, float(height) - bottom};
    const int panelCount = std::max<int>(1, scene.panels.size());
    // Panels fill a grid: one row by default, `columns` wide for contact sheets. In a grid each
    // cell keeps a caption band of its own; a single row has its captions under the panel area.
    const int columns = scene.columns > 0 ? std::min(scene.columns, panelCount) : panelCount;
    const int rows = (panelCount + columns - 1) / columns;
    const float captionBand = rows > 1 && def.overlay ? fontSize * 1.3f : 0.0f;
    auto cellOf = [&](int k) {
        const float w = panelArea.Width() / columns, h = panelArea.Height() / rows;
        const float x0 = panelArea.x0 + (k % columns) * w, y0 = panelArea.y0 + (k / columns) * h;
        return Rect{x0, y0, x0 + w, y0 + h - captionBand};
    };

    // Colour scale and framing shared by every panel; non-finite values and positions are left out.
    std::vector<std::vector<double>> values;
    double largestValue = -INFINITY, smallestValue = INFINITY;
    std::vector<std::vector<Vec3>> rotated;
    for (const Panel& panel : scene.panels) {
        values.push_back(VertexValues(colorBy, surface, panel));
        for (double v : values.back())
            if (std::isfinite(v)) {
                largestValue = std::max(largestValue, v);
                smallestValue = std::min(smallestValue, v);
            }
        const float angle = float(panel.rotationDegrees * std::numbers::pi / 180);
        const Eigen::Matrix3f rotation = Eigen::AngleAxisf(angle, Vec3::UnitZ()).toRotationMatrix();
        std::vector<Vec3> points(panel.positions.Size());
        for (int i = 0; i < panel.positions.Size(); ++i)
            points[i] = rotation * Vec3(float(panel.positions.x[i]), float(panel.positions.y[i]), float(panel.positions.z[i]));
        rotated.push_back(std::move(points));
    }
    double minValue = scene.colorMin ? *scene.colorMin : colorBy == ColorBy::Values && std::isfinite(smallestValue) ? smallestValue : 0.0;
    double maxValue = largestValue;
    if (scene.colorMax) maxValue = *scene.colorMax;
    else if (colorBy == ColorBy::Strain) maxValue = RobustColorMax(values);
    if (!(maxValue > minValue) || !std::isfinite(maxValue)) maxValue = minValue + 1;
    const bool clipped = std::isfinite(largestValue) && largestValue > maxValue + 1e-9 * std::fabs(maxValue);
    std::vector<const sim::Positions*> all;
    for (const Panel& panel : scene.panels) all.push_back(&panel.positions);
    const Framing framing = scene.framing ? *scene.framing : FrameMeshes(all);

    const bool transparent = def.background == Background::Transparent;
    glViewport(0, 0, width, height);
    glClearColor(1, 1, 1, transparent ? 0 : 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);

    Vec3 toCamera;
    const Eigen::Matrix4f viewProjection = ViewProjection(framing, def, cellOf(0).Width() / cellOf(0).Height(), &toCamera);
    // Lights fixed relative to the camera: key from the upper left, fill from the right.
    const Vec3 forward = -toCamera;
    const Vec3 right = forward.cross(Vec3::UnitZ()).normalized();
    const Vec3 up = right.cross(forward);
    const Vec3 keyLight = (toCamera * 0.8f - right * 0.55f + up * 0.6f).normalized();
    const Vec3 fillLight = (toCamera * 0.5f + right * 0.8f - up * 0.1f).normalized();
    auto colourOf = [&](double v) {
        if (legend) {
            const Rgb c = scene.categories[std::clamp<long>(std::lround(v), 0, long(scene.categories.size()) - 1)].color;
            return Vec3(c.r, c.g, c.b);
        }
        return Viridis((v - minValue) / (maxValue - minValue));
    };

    glBindVertexArray(vao);
    for (int k = 0; k < int(scene.panels.size()); ++k) {
        const Panel& panel = scene.panels[k];
        // GL viewports count from the bottom.
        const Rect cell = cellOf(k);
        glViewport(int(cell.x0), int(height - cell.y1), int(cell.Width()), int(cell.Height()));
        const int n = static_cast<int>(rotated[k].size());
        // A panel without the surface's vertices (a design that could not be built has no mesh)
        // shows only its caption.
        if (n != surface.vertexCount) continue;

        const auto normals = OutwardNormals(surface, rotated[k]);
        // A panel at rest (no reference mesh and no values) has nothing to colour: it gets the plain
        // material, which shows its shape better than the colour map's darkest end.
        const bool atRest = colorBy == ColorBy::Values ? panel.values.empty() : panel.reference.Size() == 0;
        std::vector<SurfaceVertex> vertices(n);
        for (int i = 0; i < n; ++i) {
            const Vec3 c = coloured && !atRest && std::isfinite(values[k][i]) ? colourOf(values[k][i]) : kNeutralMaterial;
            vertices[i] = {{rotated[k][i].x(), rotated[k][i].y(), rotated[k][i].z()},
                           {normals[i].x(), normals[i].y(), normals[i].z()},
                           {c.x(), c.y(), c.z()}};
        }
        // Only triangles whose corners are all finite: a failed run still shows what it has.
        std::vector<GLuint> triangles;
        triangles.reserve(surface.triangles.size() * 3);
        for (const auto& t : surface.triangles) {
            if (t[0] >= n || t[1] >= n || t[2] >= n) continue;
            if (!rotated[k][t[0]].allFinite() || !rotated[k][t[1]].allFinite() || !rotated[k][t[2]].allFinite()) continue;
            triangles.insert(triangles.end(), {GLuint(t[0]), GLuint(t[1]), GLuint(t[2])});
        }
        glBindBuffer(GL_ARRAY_BUFFER, vertexBuffer);
        glBufferData(GL_ARRAY_BUFFER, vertices.size() * sizeof(SurfaceVertex), vertices.data(), GL_STREAM_DRAW);
        glEnableVertexAttribArray(0);
        glEnableVertexAttribArray(1);
        glEnableVertexAttribArray(2);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(SurfaceVertex), (void*)offsetof(SurfaceVertex, position));
        glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(SurfaceVertex), (void*)offsetof(SurfaceVertex, normal));
        glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, sizeof(SurfaceVertex), (void*)offsetof(SurfaceVertex, color));

        glUseProgram(surfaceProgram);
        glUniformMatrix4fv(glGetUniformLocation(surfaceProgram, "viewProjection"), 1, GL_FALSE, viewProjection.data());
        glUniform3fv(glGetUniformLocation(surfaceProgram, "toCamera"), 1, toCamera.data());
        glUniform3fv(glGetUniformLocation(surfaceProgram, "keyLight"), 1, keyLight.data());
        glUniform3fv(glGetUniformLocation(surfaceProgram, "fillLight"), 1, fillLight.data());
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(1.0f, 1.0f);  // lines sit on the surface without z-fighting
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, triangleBuffer);
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, triangles.size() * sizeof(GLuint), triangles.data(), GL_STREAM_DRAW);
        glDrawElements(GL_TRIANGLES, GLsizei(triangles.size()), GL_UNSIGNED_INT, nullptr);
        glDisable(GL_POLYGON_OFFSET_FILL);

        glUseProgram(lineProgram);
        glUniformMatrix4fv(glGetUniformLocation(lineProgram, "viewProjection"), 1, GL_FALSE, viewProjection.data());
        if (def.wireframe) {
            const float lineColor[4] = {0.10f, 0.10f, 0.12f, 1.0f};
            glUniform4fv(glGetUniformLocation(lineProgram, "lineColor"), 1, lineColor);
            glDisableVertexAttribArray(1);
            glDisableVertexAttribArray(2);
            glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, edgeBuffer);
            glDrawElements(GL_LINES, GLsizei(2 * surface.edges.size()), GL_UNSIGNED_INT, nullptr);
        }
        if (!panel.segments.empty()) {
            // Segments (fibres) in the scene's colour map, drawn per colour band to keep one shader.
            const float angle = float(panel.rotationDegrees * std::numbers::pi / 180);
            const Eigen::Matrix3f rotation = Eigen::AngleAxisf(angle, Vec3::UnitZ()).toRotationMatrix();
            glDisableVertexAttribArray(1);
            glDisableVertexAttribArray(2);
            glBindBuffer(GL_ARRAY_BUFFER, segmentBuffer);
            constexpr int kBands = 16, kMarks = kBands;  // the last band: marks
            std::vector<std::vector<float>> bands(kBands + 1);
            for (const Segment& segment : panel.segments) {
                const double t = std::clamp((segment.value - minValue) / (maxValue - minValue), 0.0, 1.0);
                auto& band = segment.mark ? bands[kMarks] : bands[std::min(kBands - 1, int(t * kBands))];
                const Vec3 a = rotation * Vec3(segment.a[0], segment.a[1], segment.a[2]);
                const Vec3 b = rotation * Vec3(segment.b[0], segment.b[1], segment.b[2]);
                if (!a.allFinite() || !b.allFinite()) continue;
                band.insert(band.end(), {a.x(), a.y(), a.z(), b.x(), b.y(), b.z()});
            }
            glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
            for (int band = 0; band <= kBands; ++band) {
                if (bands[band].empty()) continue;
                const Vec3 c = band == kMarks ? Vec3(0.85f, 0.1f, 0.1f) : Vec3(Viridis((band + 0.5) / kBands) * 0.85f);
                const float lineColor[4] = {c.x(), c.y(), c.z(), 1.0f};
                glUniform4fv(glGetUniformLocation(lineProgram, "lineColor"), 1, lineColor);
                glBufferData(GL_ARRAY_BUFFER, bands[band].size() * sizeof(float), bands[band].data(), GL_STREAM_DRAW);
                glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
                glLineWidth(float(def.supersample) * (band == kMarks ? 3.0f : 1.0f));
                glDrawArrays(GL_LINES, 0, GLsizei(bands[band].size() / 3));
            }
            glLineWidth(1.0f);
        }
    }
    glBindVertexArray(0);
    glViewport(0, 0, width, height);

    if (def.overlay) {
        ImDrawList* draw = overlay.Begin(width, height);
        const ImU32 ink = IM_COL32(25, 25, 25, 255), grey = IM_COL32(70, 70, 70, 255);
        const float margin = fontSize * 0.7f;
        const float titleHeight = overlay.DrawTitle(draw, fontSize * 1.37f, ImVec2(margin, margin * 0.8f), width - 2 * margin, ink, scene.title);
        float y = margin * 0.8f + fontSize * 0.33f + std::max(titleHeight, fontSize * 1.37f);
        for (const std::string& line : scene.lines) {
            draw->AddText(overlay.TextFont(), fontSize, ImVec2(margin, y), grey, line.c_str());
            y += fontSize * 1.25f;
        }
        if (axisLabels) {
            const ImU32 axisInk = IM_COL32(40, 40, 40, 255);
            const float w = panelArea.Width() / columns, h = panelArea.Height() / rows;
            const ImVec2 titleSize = overlay.TextFont()->CalcTextSizeA(fontSize, FLT_MAX, 0, scene.columnTitle.c_str());
            draw->AddText(overlay.TitleFont(), fontSize, ImVec2((panelArea.x0 + panelArea.x1 - titleSize.x) / 2, top), axisInk, scene.columnTitle.c_str());
            for (int c = 0; c < int(scene.columnLabels.size()) && c < columns; ++c) {
                const ImVec2 size = overlay.TextFont()->CalcTextSizeA(fontSize, FLT_MAX, 0, scene.columnLabels[c].c_str());
                draw->AddText(overlay.TextFont(), fontSize, ImVec2(panelArea.x0 + (c + 0.5f) * w - size.x / 2, top + fontSize * 1.35f), ink,
                              scene.columnLabels[c].c_str());
            }
            // The row axis's title runs down the left edge, one word per line.
            std::string rowTitle = scene.rowTitle;
            for (char& ch : rowTitle)
                if (ch == ' ') ch = '\n';
            draw->AddText(overlay.TitleFont(), fontSize, ImVec2(fontSize * 0.3f, panelArea.y0), axisInk, rowTitle.c_str());
            for (int r = 0; r < int(scene.rowLabels.size()) && r < rows; ++r) {
                const ImVec2 size = overlay.TextFont()->CalcTextSizeA(fontSize, FLT_MAX, 0, scene.rowLabels[r].c_str());
                draw->AddText(overlay.TextFont(), fontSize, ImVec2(panelArea.x0 - size.x - fontSize * 0.4f, panelArea.y0 + (r + 0.5f) * h - size.y / 2), ink,
                              scene.rowLabels[r].c_str());
            }
        }
        for (int k = 0; k < int(scene.panels.size()); ++k) {
            const std::string& caption = scene.panels[k].caption;
            const ImVec2 size = overlay.TextFont()->CalcTextSizeA(fontSize, FLT_MAX, 0, caption.c_str());
            const Rect cell = cellOf(k);
            const float cx = (cell.x0 + cell.x1) / 2;
            const float cy = rows > 1 ? cell.y1 + fontSize * 0.1f : panelArea.y1 + fontSize * 0.3f;
            draw->AddText(overlay.TextFont(), fontSize, ImVec2(cx - size.x / 2, cy), ink, caption.c_str());
        }
        if (coloured && legend) {
            // Swatches down the strip, each with its label (its lines beside it).
            float ly = top + fontSize * 1.2f;
            const float x0 = panelArea.x1 + fontSize * 0.6f, side = fontSize * 1.1f;
            if (!scene.colorLabel.empty()) {
                draw->AddText(overlay.TitleFont(), fontSize, ImVec2(x0, ly), ink, scene.colorLabel.c_str());
                ly += fontSize * 1.6f;
            }
            for (const Category& category : scene.categories) {
                const ImU32 fill = IM_COL32(int(category.color.r * 255), int(category.color.g * 255), int(category.color.b * 255), 255);
                draw->AddRectFilled(ImVec2(x0, ly), ImVec2(x0 + side, ly + side), fill);
                draw->AddRect(ImVec2(x0, ly), ImVec2(x0 + side, ly + side), grey);
                draw->AddText(overlay.TextFont(), fontSize, ImVec2(x0 + side + fontSize * 0.5f, ly), ink, category.label.c_str());
                ly += overlay.TextFont()->CalcTextSizeA(fontSize, FLT_MAX, 0, category.label.c_str()).y + fontSize * 0.7f;
            }
        } else if (coloured) {
            std::string label = scene.colorLabel;
            if (label.empty())
                label = colorBy == ColorBy::Displacement ? "displacement\n(mesh units)" : colorBy == ColorBy::Strain ? "spring strain\n(percent)" : "value";
            const Rect strip{panelArea.x1, top, float(width), panelArea.y1};
            ColourBar bar;
            bar.x0 = strip.x0 + strip.Width() * 0.12f;
            bar.x1 = bar.x0 + strip.Width() * 0.22f;
            bar.y0 = strip.y0 + fontSize * 3.2f;
            // Room under the bar for the marks off its scale, two lines each.
            int offScale = 0;
            for (const ScaleMark& mark : scene.scaleMarks) offScale += !(mark.value >= minValue && mark.value <= maxValue);
            bar.y1 = strip.y1 - fontSize * (1.2f + 1.6f * offScale);
            bar.min = minValue;
            bar.max = maxValue;
            bar.clippedTop = clipped;
            bar.label = label;
            bar.labelX = strip.x0 + strip.Width() * 0.02f;
            bar.marks = scene.scaleMarks;
            DrawColourBar(draw, overlay, bar);
        }
        overlay.End();
    }

    return BoxDownsample(context->FinishAndGetPixels(), width, height, def.supersample, /*bottomUp=*/true);
}

}  // namespace render
