#include "mesh_io.h"

#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli_options.h"

namespace app {
namespace {

// Calls visit(lineNumber, tokens) for each line with its '#' comment removed.
template <class Visit>
void ForEachLine(const std::string& text, Visit visit) {
    std::istringstream lines(text);
    std::string line;
    int lineNumber = 0;
    while (std::getline(lines, line)) {
        ++lineNumber;
        if (auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
        std::istringstream tokens(line);
        visit(lineNumber, tokens);
    }
}

}  // namespace

std::string ReadTextFile(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw UsageError("cannot read '" + path + "': it is a directory");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw UsageError("cannot open '" + path + "': " + std::strerror(errno));
    std::ostringstream contents;
    contents << in.rdbuf();
    return contents.str();
}

std::string FormatObj(const sim::Positions& p, const sim::MeshDef& def) {
    std::string out;
    out.reserve(static_cast<size_t>(p.Size()) * 80);
    char line[128];
    std::snprintf(line, sizeof line, "# actuator workbench mesh: %d vertices per turn x %d turns, vertices in helix order\n",
                  def.resolution, def.turns);
    out += line;
    // Shortest round-trip text for each coordinate: reading the file back gives the same doubles.
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
    for (const auto& t : sim::Triangles(def)) {
        std::snprintf(line, sizeof line, "f %d %d %d\n", t[0] + 1, t[1] + 1, t[2] + 1);
        out += line;
    }
    return out;
}

sim::Positions ReadObjVertices(const std::string& path) {
    const std::string text = ReadTextFile(path);
    if (text.find('\0') != std::string::npos) throw UsageError("'" + path + "' is not a text OBJ file (binary data)");
    sim::Positions p;
    ForEachLine(text, [&](int lineNumber, std::istringstream& tokens) {
        std::string keyword;
        if (!(tokens >> keyword)) return;
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
        } else if (keyword != "f" && keyword != "vn" && keyword != "vt" && keyword != "o" && keyword != "g" && keyword != "s" &&
                   keyword != "l" && keyword != "usemtl" && keyword != "mtllib") {
            // Faces and the rest are ignored: the model makes its own springs and triangles.
            throw UsageError(where + ": not an OBJ line (starts with '" + keyword.substr(0, 20) + "')");
        }
    });
    return p;
}

std::vector<double> ReadNumberFile(const std::string& path) {
    std::vector<double> values;
    ForEachLine(ReadTextFile(path), [&](int lineNumber, std::istringstream& tokens) {
        std::string word;
        while (tokens >> word) values.push_back(ParseNumber(word, path + ":" + std::to_string(lineNumber)));
    });
    return values;
}

void CheckOutputPath(const std::string& path, const std::string& what) {
    namespace fs = std::filesystem;
    if (path.empty()) throw UsageError(what + ": empty file name");
    const fs::path target(path);
    std::error_code ec;
    if (fs::is_directory(target, ec)) throw UsageError(what + ": '" + path + "' is a directory");
    const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
    if (!fs::is_directory(folder, ec)) throw UsageError(what + ": folder '" + folder.string() + "' does not exist");
    if (access(folder.c_str(), W_OK) != 0) throw UsageError(what + ": cannot write in '" + folder.string() + "'");
}

void WriteFileAtomically(const std::string& path, const std::string& contents) {
    const std::string temporary = path + ".tmp." + std::to_string(getpid());
    std::FILE* file = std::fopen(temporary.c_str(), "wb");
    if (!file) throw UsageError("cannot write '" + path + "': " + std::strerror(errno));
    const bool written = std::fwrite(contents.data(), 1, contents.size(), file) == contents.size();
    const bool flushed = std::fflush(file) == 0 && fsync(fileno(file)) == 0;
    const bool closed = std::fclose(file) == 0;
    if (!written || !flushed || !closed || std::rename(temporary.c_str(), path.c_str()) != 0) {
        const std::string reason = std::strerror(errno);
        std::remove(temporary.c_str());
        throw UsageError("cannot write '" + path + "': " + reason);
    }
}

}  // namespace app
