#include "formats/obj_io.h"

#include <charconv>
#include <cstdio>
#include <sstream>

#include "support/errors.h"
#include "formats/files.h"
#include "support/number_expression.h"

namespace app {

std::string FormatObj(const sim::Positions& p, const sim::Surface& surface, const std::string& comment) {
    std::string out;
    out.reserve(static_cast<size_t>(p.Size()) * 80 + surface.triangles.size() * 24);
    out += "# " + comment + "\n";
    char line[128];
    for (int i = 0; i < p.Size(); ++i) {
        char* end = line;
        *end++ = 'v';
        for (double c : {p.x[i], p.y[i], p.z[i]}) {
            *end++ = ' ';
            end = std::to_chars(end, line + sizeof line, c).ptr;
        }
        *end++ = '\n';
        out.append(line, end);
    }
    for (const auto& t : surface.triangles) {
        std::snprintf(line, sizeof line, "f %d %d %d\n", t[0] + 1, t[1] + 1, t[2] + 1);
        out += line;
    }
    return out;
}

ObjMesh ReadObj(const std::string& path) {
    const std::string text = ReadInputFile(path);
    if (text.find('\0') != std::string::npos) throw UsageError(Quote(path) + " is not a text OBJ file (binary data)");
    ObjMesh mesh;
    sim::Positions& p = mesh.positions;
    std::istringstream lines(text);
    std::string line;
    for (int lineNumber = 1; std::getline(lines, line); ++lineNumber) {
        if (auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
        std::istringstream tokens(line);
        std::string keyword;
        if (!(tokens >> keyword)) continue;
        const std::string where = path + ":" + std::to_string(lineNumber);
        if (keyword == "v") {
            double xyz[3];
            std::string word;
            for (double& c : xyz) {
                if (!(tokens >> word)) throw UsageError(where + ": a 'v' line needs three coordinates");
                c = ParseNumber(word, where);
            }
            if (tokens >> word) {  // optional w
                ParseNumber(word, where);
                if (tokens >> word) throw UsageError(where + ": too many numbers on a 'v' line");
            }
            p.x.push_back(xyz[0]);
            p.y.push_back(xyz[1]);
            p.z.push_back(xyz[2]);
        } else if (keyword == "f") {
            // "f a b c", each corner "v", "v/vt", "v//vn" or "v/vt/vn"; 1-based, or negative from the end.
            std::array<int, 3> t{};
            std::string corner;
            int corners = 0;
            while (tokens >> corner) {
                long long index = 0;
                const auto [end, error] = std::from_chars(corner.data(), corner.data() + corner.size(), index);
                if (error != std::errc() || (end != corner.data() + corner.size() && *end != '/') || index == 0)
                    throw UsageError(where + ": " + Quote(corner) + " is not a vertex index");
                index = index < 0 ? static_cast<long long>(p.Size()) + index : index - 1;
                if (index < 0 || index >= p.Size()) throw UsageError(where + ": vertex " + corner + " comes before it is defined");
                if (corners < 3) t[static_cast<size_t>(corners)] = static_cast<int>(index);
                ++corners;
            }
            if (corners != 3) throw UsageError(where + ": a face of " + std::to_string(corners) + " corners; the actuator's surfaces are triangles");
            mesh.triangles.push_back(t);
        } else if (keyword != "vn" && keyword != "vt" && keyword != "o" && keyword != "g" && keyword != "s" &&
                   keyword != "l" && keyword != "usemtl" && keyword != "mtllib") {
            throw UsageError(where + ": not an OBJ line (starts with " + Quote(keyword) + ")");
        }
    }
    return mesh;
}

}  // namespace app
