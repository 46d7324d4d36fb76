// [SECTION] Colour maps and per-vertex values
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

#include "overlay_context.h"
#include "render/colormap.h"
#include "render/gl_context.h"

namespace render {

RenderDef DefaultRenderDef() { return RenderDef{}; }

// ---------------------------------------------------------------------------------------------
// [SECTION] Colour maps and per-vertex values
// ---------------------------------------------------------------------------------------------
namespace {

using Vec3 = Eigen::Vector3f;

Vec3 Viridis(double t) {
    const Rgb c = ViridisColor(t);
    return Vec3(c.r, c.g, c.b);
}

const Vec3 kNeutralMaterial(0.62f, 0.70f, 0.80f);  // Shading mode: a pale blue-grey silicone

}  // namespace

std::vector<double> VertexValues(ColorBy colorBy, const sim::MeshDef& mesh, const sim::Positions& p,
                                 const sim::Positions& reference) {
    const int n = p.Size();
    std::vector<double> values(n, 0.0);
    if (colorBy == ColorBy::Shading || reference.Size() != n) return values;
    if (colorBy == ColorBy::Displacement) {
        for (int i = 0; i < n; ++i)
            values[i] = std::sqrt(std::pow(p.x[i] - reference.x[i], 2) + std::pow(p.y[i] - reference.y[i], 2) +
                                  std::pow(p.z[i] - reference.z[i], 2));
        return values;
    }
    std::vector<int> springs(n, 0);
    auto length = [](const sim::Positions& q, int a, int b) {
        return std::sqrt(std::pow(q.x[b] - q.x[a], 2) + std::pow(q.y[b] - q.y[a], 2) + std::pow(q.z[b] - q.z[a], 2));
    };
    for (int o : sim::SpringOffsets(mesh)) {
        for (int a = 0; a + o < n; ++a) {
            const double rest = length(reference, a, a + o);
            if (rest <= 0) continue;
            const double strain = 100.0 * std::fabs(length(p, a, a + o) / rest - 1.0);
            values[a] += strain;
            values[a + o] += strain;
            ++springs[a];
            ++springs[a + o];
        }
    }
    for (int i = 0; i < n; ++i)
        if (springs[i]) values[i] /= springs[i];
    return values;
}

Framing FrameMeshes(const std::vector<const sim::Positions*>& meshes) {
    Framing f{0, INFINITY, -INFINITY};
    for (const sim::Positions* p : meshes) {
        for (int i = 0; i < p->Size(); ++i) {
            f.radius = std::max(f.radius, std::hypot(p->x[i], p->y[i]));
            f.zMin = std::min(f.zMin, p->z[i]);
            f.zMax = std::max(f.zMax, p->z[i]);
        }
    }
    if (!(f.zMin <= f.zMax)) f = Framing{};
    f.radius = std::max(f.radius, 1e-3);
    return f;
}

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

struct MeshRenderer::State {
    RenderDef def;
    std::unique_ptr<GlContext> context;
    GLuint surfaceProgram = 0, lineProgram = 0;
    GLuint vao = 0, vertexBuffer = 0, triangleBuffer = 0, springBuffer = 0;
    sim::MeshDef indexedMesh{0, 0};  // mesh size the index buffers were built for
    GLsizei triangleIndexCount = 0, springIndexCount = 0;
    OverlayContext overlay;

    void EnsureIndexBuffers(const sim::MeshDef& mesh) {
        if (mesh.resolution == indexedMesh.resolution && mesh.turns == indexedMesh.turns) return;
        std::vector<GLuint> triangles;
        for (const auto& t : sim::Triangles(mesh)) triangles.insert(triangles.end(), {GLuint(t[0]), GLuint(t[1]), GLuint(t[2])});
        std::vector<GLuint> springs;
        const int n = sim::VertexCount(mesh);
        for (int o : sim::SpringOffsets(mesh))
            for (int a = 0; a + o < n; ++a) springs.insert(springs.end(), {GLuint(a), GLuint(a + o)});
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, triangleBuffer);
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, triangles.size() * sizeof(GLuint), triangles.data(), GL_STATIC_DRAW);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, springBuffer);
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, springs.size() * sizeof(GLuint), springs.data(), GL_STATIC_DRAW);
        triangleIndexCount = static_cast<GLsizei>(triangles.size());
        springIndexCount = static_cast<GLsizei>(springs.size());
        indexedMesh = mesh;
    }
};

MeshRenderer::MeshRenderer(std::unique_ptr<State> state) : state_(std::move(state)) {}
MeshRenderer::~MeshRenderer() = default;
const RenderDef& MeshRenderer::Def() const { return state_->def; }
std::string MeshRenderer::Description() const { return state_->context->Description(); }

std::unique_ptr<MeshRenderer> MeshRenderer::Create(const RenderDef& def, std::string* error) {
    auto state = std::make_unique<State>();
    state->def = def;
    state->context = CreateOsMesaContext(error);
    if (!state->context) return nullptr;
    const int bufferWidth = def.width * def.supersample, bufferHeight = def.height * def.supersample;
    if (!state->context->MakeCurrent(bufferWidth, bufferHeight)) {
        *error = "OSMesa could not make the context current";
        return nullptr;
    }
    state->surfaceProgram = CompileProgram(kSurfaceVertexShader, kSurfaceFragmentShader, error);
    state->lineProgram = CompileProgram(kLineVertexShader, kLineFragmentShader, error);
    if (!state->surfaceProgram || !state->lineProgram) return nullptr;
    glGenVertexArrays(1, &state->vao);
    glGenBuffers(1, &state->vertexBuffer);
    glGenBuffers(1, &state->triangleBuffer);
    glGenBuffers(1, &state->springBuffer);

    // Text follows the image size, but never below ~16 px body text: small images stay legible.
    const float textScale = def.textScale > 0 ? float(def.textScale) : std::max(0.85f, def.height / 768.0f);
    if (!state->overlay.Create(def.supersample * textScale, error)) return nullptr;
    return std::unique_ptr<MeshRenderer>(new MeshRenderer(std::move(state)));
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
std::vector<Vec3> OutwardNormals(const sim::MeshDef& mesh, const std::vector<Vec3>& p) {
    std::vector<Vec3> normals(p.size(), Vec3::Zero());
    for (const auto& t : sim::Triangles(mesh)) {
        // (i, i+1, i+R+1) winds inward on the helix (it turns clockwise seen from above): negate.
        const Vec3 n = -(p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]);
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

// Spring strain has outliers: at a pinch where the tube meets its axis, rest lengths are nearly zero
// and a few springs reach hundreds of percent. Scaling to the 98th percentile keeps the rest readable.
double RobustColorMax(const std::vector<std::vector<double>>& values) {
    std::vector<double> all;
    for (const auto& panel : values) all.insert(all.end(), panel.begin(), panel.end());
    if (all.empty()) return 0;
    const size_t k = std::min(all.size() - 1, static_cast<size_t>(0.98 * (all.size() - 1)));
    std::nth_element(all.begin(), all.begin() + k, all.end());
    return all[k];
}

std::string FormatTick(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", value);
    return text;
}

// Values above the top of the scale take its colour; the top label then reads "> max".
void DrawColourBar(ImDrawList* draw, ImFont* font, float fontSize, const Rect& strip, double maxValue, bool clipped,
                   const char* label) {
    const float barWidth = strip.Width() * 0.22f;
    const float x0 = strip.x0 + strip.Width() * 0.12f, x1 = x0 + barWidth;
    const float y0 = strip.y0 + fontSize * 3.2f, y1 = strip.y1 - fontSize * 1.2f;
    const int steps = 64;
    for (int s = 0; s < steps; ++s) {
        const float ya = y1 - (y1 - y0) * s / steps, yb = y1 - (y1 - y0) * (s + 1) / steps;
        const Vec3 ca = Viridis(double(s) / steps), cb = Viridis(double(s + 1) / steps);
        const ImU32 bottom = ImGui::ColorConvertFloat4ToU32(ImVec4(ca.x(), ca.y(), ca.z(), 1));
        const ImU32 top = ImGui::ColorConvertFloat4ToU32(ImVec4(cb.x(), cb.y(), cb.z(), 1));
        draw->AddRectFilledMultiColor(ImVec2(x0, yb), ImVec2(x1, ya + 0.5f), top, top, bottom, bottom);
    }
    const ImU32 ink = IM_COL32(30, 30, 30, 255);
    draw->AddRect(ImVec2(x0, y0), ImVec2(x1, y1), ink, 0, 0, fontSize * 0.06f);
    for (int k = 0; k <= 4; ++k) {
        const float y = y1 - (y1 - y0) * k / 4;
        draw->AddLine(ImVec2(x1, y), ImVec2(x1 + barWidth * 0.25f, y), ink, fontSize * 0.06f);
        const std::string tick = (k == 4 && clipped ? "> " : "") + FormatTick(maxValue * k / 4);
        draw->AddText(font, fontSize * 0.85f, ImVec2(x1 + barWidth * 0.35f, y - fontSize * 0.45f), ink, tick.c_str());
    }
    draw->AddText(font, fontSize * 0.85f, ImVec2(strip.x0 + strip.Width() * 0.02f, strip.y0 + fontSize * 0.8f), ink, label);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// [SECTION] Render
// ---------------------------------------------------------------------------------------------

Image MeshRenderer::Render(const Scene& scene) {
    State& s = *state_;
    const RenderDef& def = s.def;
    const int width = def.width * def.supersample, height = def.height * def.supersample;
    s.context->MakeCurrent(width, height);
    s.EnsureIndexBuffers(scene.mesh);

    // Layout: text band on top, captions below, colour bar strip on the right.
    const bool coloured = def.colorBy != ColorBy::Shading;
    const float fontSize = s.overlay.FontSize();
    const float top = def.overlay ? fontSize * (2.2f + 1.25f * scene.lines.size()) : 0.0f;
    const float bottom = def.overlay ? fontSize * 1.8f : 0.0f;
    const float barStrip = def.overlay && coloured ? std::max(width * 0.11f, fontSize * 6.0f) : 0.0f;
    const Rect panelArea{0, top, width - barStrip, float(height) - bottom};
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

    // Colour scale and framing shared by every panel.
    std::vector<std::vector<double>> values;
    double maxValue = 0;
    std::vector<std::vector<Vec3>> rotated;
    for (const Panel& panel : scene.panels) {
        values.push_back(VertexValues(def.colorBy, scene.mesh, panel.positions, panel.reference));
        for (double v : values.back()) maxValue = std::max(maxValue, v);
        const float angle = float(panel.rotationDegrees * std::numbers::pi / 180);
        const Eigen::Matrix3f rotation = Eigen::AngleAxisf(angle, Vec3::UnitZ()).toRotationMatrix();
        std::vector<Vec3> points(panel.positions.Size());
        for (int i = 0; i < panel.positions.Size(); ++i)
            points[i] = rotation * Vec3(float(panel.positions.x[i]), float(panel.positions.y[i]), float(panel.positions.z[i]));
        rotated.push_back(std::move(points));
    }
    const double largestValue = maxValue;
    if (scene.colorMax) maxValue = *scene.colorMax;
    else if (def.colorBy == ColorBy::Strain) maxValue = RobustColorMax(values);
    if (!(maxValue > 0)) maxValue = 1;
    const bool clipped = largestValue > maxValue * (1 + 1e-9);
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

    glBindVertexArray(s.vao);
    for (int k = 0; k < int(scene.panels.size()); ++k) {
        // GL viewports count from the bottom.
        const Rect cell = cellOf(k);
        glViewport(int(cell.x0), int(height - cell.y1), int(cell.Width()), int(cell.Height()));

        const auto normals = OutwardNormals(scene.mesh, rotated[k]);
        std::vector<SurfaceVertex> vertices(rotated[k].size());
        for (size_t i = 0; i < vertices.size(); ++i) {
            // A panel at rest (no reference mesh) has nothing to colour: it gets the plain material,
            // which shows its shape better than the colour map's darkest end.
            const bool atRest = scene.panels[k].reference.Size() == 0;
            const Vec3 c = coloured && !atRest ? Viridis(values[k][i] / maxValue) : kNeutralMaterial;
            vertices[i] = {{rotated[k][i].x(), rotated[k][i].y(), rotated[k][i].z()},
                           {normals[i].x(), normals[i].y(), normals[i].z()},
                           {c.x(), c.y(), c.z()}};
        }
        glBindBuffer(GL_ARRAY_BUFFER, s.vertexBuffer);
        glBufferData(GL_ARRAY_BUFFER, vertices.size() * sizeof(SurfaceVertex), vertices.data(), GL_STREAM_DRAW);
        glEnableVertexAttribArray(0);
        glEnableVertexAttribArray(1);
        glEnableVertexAttribArray(2);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(SurfaceVertex), (void*)offsetof(SurfaceVertex, position));
        glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(SurfaceVertex), (void*)offsetof(SurfaceVertex, normal));
        glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, sizeof(SurfaceVertex), (void*)offsetof(SurfaceVertex, color));

        glUseProgram(s.surfaceProgram);
        glUniformMatrix4fv(glGetUniformLocation(s.surfaceProgram, "viewProjection"), 1, GL_FALSE, viewProjection.data());
        glUniform3fv(glGetUniformLocation(s.surfaceProgram, "toCamera"), 1, toCamera.data());
        glUniform3fv(glGetUniformLocation(s.surfaceProgram, "keyLight"), 1, keyLight.data());
        glUniform3fv(glGetUniformLocation(s.surfaceProgram, "fillLight"), 1, fillLight.data());
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(1.0f, 1.0f);  // the wireframe sits on the surface without z-fighting
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, s.triangleBuffer);
        glDrawElements(GL_TRIANGLES, s.triangleIndexCount, GL_UNSIGNED_INT, nullptr);
        glDisable(GL_POLYGON_OFFSET_FILL);

        if (def.wireframe) {
            glUseProgram(s.lineProgram);
            glUniformMatrix4fv(glGetUniformLocation(s.lineProgram, "viewProjection"), 1, GL_FALSE, viewProjection.data());
            const float lineColor[4] = {0.10f, 0.10f, 0.12f, 1.0f};
            glUniform4fv(glGetUniformLocation(s.lineProgram, "lineColor"), 1, lineColor);
            glDisableVertexAttribArray(1);
            glDisableVertexAttribArray(2);
            glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, s.springBuffer);
            glDrawElements(GL_LINES, s.springIndexCount, GL_UNSIGNED_INT, nullptr);
        }
    }
    glBindVertexArray(0);
    glViewport(0, 0, width, height);

    if (def.overlay) {
        ImDrawList* draw = s.overlay.Begin(width, height);
        const ImU32 ink = IM_COL32(25, 25, 25, 255), grey = IM_COL32(70, 70, 70, 255);
        const float margin = fontSize * 0.7f;
        draw->AddText(s.overlay.TitleFont(), fontSize * 1.37f, ImVec2(margin, margin * 0.8f), ink, scene.title.c_str());
        float y = margin * 0.8f + fontSize * 1.7f;
        for (const std::string& line : scene.lines) {
            draw->AddText(s.overlay.TextFont(), fontSize, ImVec2(margin, y), grey, line.c_str());
            y += fontSize * 1.25f;
        }
        for (int k = 0; k < int(scene.panels.size()); ++k) {
            const std::string& caption = scene.panels[k].caption;
            const ImVec2 size = s.overlay.TextFont()->CalcTextSizeA(fontSize, FLT_MAX, 0, caption.c_str());
            const Rect cell = cellOf(k);
            const float cx = (cell.x0 + cell.x1) / 2;
            const float cy = rows > 1 ? cell.y1 + fontSize * 0.1f : panelArea.y1 + fontSize * 0.3f;
            draw->AddText(s.overlay.TextFont(), fontSize, ImVec2(cx - size.x / 2, cy), ink, caption.c_str());
        }
        if (coloured) {
            const char* label = def.colorBy == ColorBy::Displacement ? "displacement\n(mesh units)" : "spring strain\n(percent)";
            DrawColourBar(draw, s.overlay.TextFont(), fontSize, Rect{panelArea.x1, top, float(width), panelArea.y1}, maxValue, clipped, label);
        }
        s.overlay.End();
    }

    return BoxDownsample(s.context->FinishAndGetPixels().data(), width, height, def.supersample, /*bottomUp=*/true);
}

}  // namespace render
