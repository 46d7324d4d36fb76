#include "formats/solid_io.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>

namespace app {
namespace {

using Vec = std::array<double, 3>;

Vec Normal(const sim::TriangleMesh& m, const std::array<int, 3>& t) {
    const Vec& a = m.vertices[t[0]];
    const Vec& b = m.vertices[t[1]];
    const Vec& c = m.vertices[t[2]];
    const Vec u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    Vec n{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (length > 0)
        for (double& x : n) x /= length;
    return n;
}

template <class T>
void Put(std::string& out, T value) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));  // little-endian machines only (x86-64, arm64), as STL and our PLY header say
    out.append(bytes, sizeof(T));
}

}  // namespace

const char* Extension(SolidFormat format) {
    switch (format) {
        case SolidFormat::Stl: return ".stl";
        case SolidFormat::Obj: return ".obj";
        case SolidFormat::Ply: return ".ply";
    }
    return "";
}

std::string FormatSolid(const sim::TriangleMesh& m, SolidFormat format, bool ascii, const std::string& name) {
    std::string out;
    if (format == SolidFormat::Stl && ascii) {
        out = "solid " + name + "\n";
        for (const auto& t : m.triangles) {
            const Vec n = Normal(m, t);
            out += fmt::format("  facet normal {:.9g} {:.9g} {:.9g}\n    outer loop\n", n[0], n[1], n[2]);
            for (int v : t) out += fmt::format("      vertex {:.9g} {:.9g} {:.9g}\n", m.vertices[v][0], m.vertices[v][1], m.vertices[v][2]);
            out += "    endloop\n  endfacet\n";
        }
        return out + "endsolid " + name + "\n";
    }
    if (format == SolidFormat::Stl) {
        std::string header = "binary STL, mm: " + name;
        header.resize(80, ' ');
        if (header.compare(0, 5, "solid") == 0) header[0] = 'S';  // a binary file must not look like an ASCII one
        out = header;
        Put<std::uint32_t>(out, static_cast<std::uint32_t>(m.triangles.size()));
        for (const auto& t : m.triangles) {
            for (double x : Normal(m, t)) Put<float>(out, static_cast<float>(x));
            for (int v : t)
                for (double x : m.vertices[v]) Put<float>(out, static_cast<float>(x));
            Put<std::uint16_t>(out, 0);
        }
        return out;
    }
    if (format == SolidFormat::Obj) {
        out = "# " + name + " (millimetres; faces counter-clockwise seen from outside)\n";
        for (const Vec& v : m.vertices) out += fmt::format("v {:.17g} {:.17g} {:.17g}\n", v[0], v[1], v[2]);
        for (const auto& t : m.triangles) out += fmt::format("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
        return out;
    }
    out = fmt::format("ply\nformat binary_little_endian 1.0\ncomment {} (millimetres)\nelement vertex {}\nproperty double x\nproperty double y\n"
                      "property double z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
                      name, m.vertices.size(), m.triangles.size());
    for (const Vec& v : m.vertices)
        for (double x : v) Put<double>(out, x);
    for (const auto& t : m.triangles) {
        Put<std::uint8_t>(out, 3);
        for (int v : t) Put<std::int32_t>(out, v);
    }
    return out;
}

bool ParseBinaryStl(const std::string& bytes, sim::TriangleMesh* mesh, std::string* error) {
    if (bytes.size() < 84) {
        *error = "shorter than a binary STL header";
        return false;
    }
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    if (bytes.size() != 84 + 50ull * count) {
        *error = fmt::format("{} bytes, but {} triangles need {}", bytes.size(), count, 84 + 50ull * count);
        return false;
    }
    std::map<Vec, int> index;
    mesh->vertices.clear();
    mesh->triangles.clear();
    for (std::uint32_t k = 0; k < count; ++k) {
        const char* record = bytes.data() + 84 + 50ull * k;
        std::array<int, 3> triangle{};
        for (int c = 0; c < 3; ++c) {
            float xyz[3];
            std::memcpy(xyz, record + 12 + 12 * c, 12);
            const Vec v{xyz[0], xyz[1], xyz[2]};
            const auto [it, inserted] = index.try_emplace(v, static_cast<int>(mesh->vertices.size()));
            if (inserted) mesh->vertices.push_back(v);
            triangle[c] = it->second;
        }
        mesh->triangles.push_back(triangle);
    }
    return true;
}

}  // namespace app
