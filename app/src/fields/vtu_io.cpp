#include "fields/vtu_io.h"

#include <cstdint>
#include <cstring>
#include <fmt/format.h>

namespace app {
namespace {

// Base64 (RFC 4648) of bytes, padded.
std::string Base64(const std::vector<unsigned char>& bytes) {
    static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const uint32_t a = bytes[i], b = i + 1 < bytes.size() ? bytes[i + 1] : 0, c = i + 2 < bytes.size() ? bytes[i + 2] : 0;
        const uint32_t triple = (a << 16) | (b << 8) | c;
        out += kAlphabet[(triple >> 18) & 63];
        out += kAlphabet[(triple >> 12) & 63];
        out += i + 1 < bytes.size() ? kAlphabet[(triple >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? kAlphabet[triple & 63] : '=';
    }
    return out;
}

// One array's binary block: a UInt32 byte count, then the values, encoded together (VTK's inline
// binary without compression). The machine is little-endian (x86-64, as the header says).
template <class T>
std::string Block(const std::vector<T>& values) {
    const uint32_t size = static_cast<uint32_t>(values.size() * sizeof(T));
    std::vector<unsigned char> bytes(sizeof size + size);
    std::memcpy(bytes.data(), &size, sizeof size);
    if (size) std::memcpy(bytes.data() + sizeof size, values.data(), size);
    return Base64(bytes);
}

// XML attribute text: the names are ours, but a comment or name must not break the file.
std::string Escaped(const std::string& text) {
    std::string out;
    for (char c : text) {
        if (c == '&') out += "&amp;";
        else if (c == '<') out += "&lt;";
        else if (c == '>') out += "&gt;";
        else if (c == '"') out += "&quot;";
        else out += c;
    }
    return out;
}

std::string DataArray(const FieldArray& a) {
    std::string block;
    if (a.integer) {
        std::vector<int32_t> values(a.values.begin(), a.values.end());
        block = Block(values);
    } else {
        block = Block(a.values);
    }
    // A scalar states no NumberOfComponents (VTK's default is 1): meshio reads an array that states
    // one as (N, 1) rather than (N,).
    const std::string components = a.components > 1 ? fmt::format(" NumberOfComponents=\"{}\"", a.components) : "";
    return fmt::format("        <DataArray type=\"{}\" Name=\"{}\"{} format=\"binary\">{}</DataArray>\n", a.integer ? "Int32" : "Float64",
                       Escaped(a.name), components, block);
}

}  // namespace

std::string FormatVtu(const FieldMesh& mesh) {
    const int n = mesh.points.Size();
    std::string out = "<?xml version=\"1.0\"?>\n";
    out += "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt32\">\n";
    if (!mesh.comment.empty()) {
        std::string comment = mesh.comment;
        for (size_t at; (at = comment.find("--")) != std::string::npos;) comment.replace(at, 2, "- -");  // not allowed in a comment
        out += "<!-- " + comment + " -->\n";
    }
    out += "  <UnstructuredGrid>\n";
    if (!mesh.fieldData.empty()) {
        out += "    <FieldData>\n";
        for (const FieldArray& a : mesh.fieldData) {
            std::string line = DataArray(a);
            line.replace(line.find(" format="), 0, " NumberOfTuples=\"1\"");
            out += line;
        }
        out += "    </FieldData>\n";
    }
    out += fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", n, mesh.triangles.size());
    out += "      <PointData>\n";
    for (const FieldArray& a : mesh.pointData) out += DataArray(a);
    out += "      </PointData>\n      <CellData>\n";
    for (const FieldArray& a : mesh.cellData) out += DataArray(a);
    out += "      </CellData>\n      <Points>\n";
    std::vector<double> xyz(3 * static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
        xyz[3 * i] = mesh.points.x[i];
        xyz[3 * i + 1] = mesh.points.y[i];
        xyz[3 * i + 2] = mesh.points.z[i];
    }
    out += DataArray(FieldArray{"Points", 3, xyz});
    out += "      </Points>\n      <Cells>\n";
    std::vector<int32_t> connectivity, offsets;
    std::vector<uint8_t> types(mesh.triangles.size(), 5);  // VTK_TRIANGLE
    for (const auto& t : mesh.triangles) {
        connectivity.insert(connectivity.end(), t.begin(), t.end());
        offsets.push_back(static_cast<int32_t>(connectivity.size()));
    }
    out += fmt::format("        <DataArray type=\"Int32\" Name=\"connectivity\" format=\"binary\">{}</DataArray>\n", Block(connectivity));
    out += fmt::format("        <DataArray type=\"Int32\" Name=\"offsets\" format=\"binary\">{}</DataArray>\n", Block(offsets));
    out += fmt::format("        <DataArray type=\"UInt8\" Name=\"types\" format=\"binary\">{}</DataArray>\n", Block(types));
    out += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
    return out;
}

std::string FormatPvd(const std::vector<SeriesEntry>& entries) {
    std::string out = "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n";
    for (const SeriesEntry& e : entries)
        out += fmt::format("    <DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{}\"/>\n", e.time, Escaped(e.file));
    out += "  </Collection>\n</VTKFile>\n";
    return out;
}

}  // namespace app
