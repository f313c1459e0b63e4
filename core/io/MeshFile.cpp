#include "core/io/MeshFile.h"

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <sstream>
#include <tuple>

#include "core/common/InputError.h"
#include "core/io/InputFile.h"

namespace activetouch {

namespace fs = std::filesystem;

namespace {

/// Welds vertices that lie within a micrometre of one another into one index.
class Welder {
public:
    Welder(TriangleMesh& mesh, double unitsToMm) : mesh_(mesh), scale_(unitsToMm) {}
    std::uint32_t index(double x, double y, double z) {
        x *= scale_, y *= scale_, z *= scale_;
        const auto key = std::make_tuple(std::llround(x * 1000.0), std::llround(y * 1000.0),
                                         std::llround(z * 1000.0));
        const auto [it, fresh] =
            seen_.emplace(key, static_cast<std::uint32_t>(mesh_.vertices.size()));
        if (fresh) mesh_.vertices.push_back({x, y, z});
        return it->second;
    }

private:
    TriangleMesh& mesh_;
    double scale_;
    std::map<std::tuple<long long, long long, long long>, std::uint32_t> seen_;
};

/// Where a reading went wrong: the file, and the line or byte.
struct Reading {
    const std::string& path;
    const std::string& source;
    const std::string& place;
    double unitsToMm;
    [[noreturn]] void fail(const std::string& where, const std::string& what) const {
        throw InputError(source, place, "'" + path + "', " + where + ": " + what);
    }
};

/// A coordinate: finite and within 100 m of the origin in any units the scene may give.
double coordinate(double v, const Reading& r, const std::string& where) {
    if (!std::isfinite(v) || std::abs(v * r.unitsToMm) > 1e5)
        r.fail(where, "a coordinate that is not a number or lies beyond 100 m; check the units");
    return v;
}

bool isBinaryStl(const std::string& bytes) {
    if (bytes.size() < 84) return false;
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    return 84ull + 50ull * count == bytes.size();
}

void readBinaryStl(const std::string& bytes, const Reading& r, Welder& weld, TriangleMesh& mesh) {
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    for (std::uint32_t t = 0; t < count; ++t) {
        const char* at = bytes.data() + 84 + 50ull * t + 12;  // after the facet's normal
        std::array<std::uint32_t, 3> tri{};
        for (int v = 0; v < 3; ++v) {
            float c[3];
            std::memcpy(c, at + 12 * v, 12);
            const std::string where = "triangle " + std::to_string(t + 1);
            tri[static_cast<std::size_t>(v)] = weld.index(
                coordinate(c[0], r, where), coordinate(c[1], r, where), coordinate(c[2], r, where));
        }
        mesh.triangles.push_back(tri);
    }
}

/// Each line of a text mesh file that holds a word: the word, the rest of the line, and
/// "line N" for messages.
template <typename Read>
void forEachLine(const std::string& text, Read read) {
    std::istringstream in(text);
    std::string line;
    int lineNo = 0;
    while (std::getline(in, line)) {
        ++lineNo;
        std::istringstream words(line);
        std::string word;
        if (words >> word) read(word, words, "line " + std::to_string(lineNo));
    }
}

/// The three coordinates that follow on the line, welded.
std::uint32_t vertexOf(std::istringstream& words, const Reading& r, const std::string& where,
                       Welder& weld) {
    double x, y, z;
    if (!(words >> x >> y >> z)) r.fail(where, "a vertex needs three numbers");
    return weld.index(coordinate(x, r, where), coordinate(y, r, where), coordinate(z, r, where));
}

void readAsciiStl(const std::string& text, const Reading& r, Welder& weld, TriangleMesh& mesh) {
    int inFacet = 0;
    std::array<std::uint32_t, 3> tri{};
    forEachLine(text,
                [&](const std::string& word, std::istringstream& words, const std::string& where) {
                    if (word == "facet") {
                        inFacet = 0;
                    } else if (word == "vertex") {
                        if (inFacet == 3) r.fail(where, "a facet with more than three vertices");
                        tri[static_cast<std::size_t>(inFacet++)] = vertexOf(words, r, where, weld);
                    } else if (word == "endfacet") {
                        if (inFacet != 3) r.fail(where, "a facet ends without three vertices");
                        mesh.triangles.push_back(tri);
                        inFacet = 0;
                    }
                });
}

/// An OBJ face's vertex reference ("7", "7/2", "7//3", "-1/2/3") as an index into `count`
/// vertices read so far.
std::uint32_t objIndex(const std::string& token, std::size_t count, const Reading& r,
                       const std::string& where) {
    char* end = nullptr;
    const long long i = std::strtoll(token.c_str(), &end, 10);
    const long long resolved = i < 0 ? static_cast<long long>(count) + i : i - 1;
    if (end == token.c_str() || (*end != '\0' && *end != '/') || i == 0 || resolved < 0 ||
        resolved >= static_cast<long long>(count))
        r.fail(where, "face vertex '" + token + "' names no vertex read before it");
    return static_cast<std::uint32_t>(resolved);
}

void readObj(const std::string& text, const Reading& r, Welder& weld, TriangleMesh& mesh) {
    std::vector<std::uint32_t> vertices;  // the file's vertex numbers, welded
    forEachLine(
        text, [&](const std::string& word, std::istringstream& words, const std::string& where) {
            if (word == "v") {
                vertices.push_back(vertexOf(words, r, where, weld));
            } else if (word == "f") {
                std::vector<std::uint32_t> face;
                std::string token;
                while (words >> token)
                    face.push_back(vertices[objIndex(token, vertices.size(), r, where)]);
                if (face.size() < 3) r.fail(where, "a face needs three vertices or more");
                for (std::size_t k = 1; k + 1 < face.size(); ++k)  // a polygon, as a fan
                    mesh.triangles.push_back({face[0], face[k], face[k + 1]});
            }  // normals, texture coordinates, groups and materials do not shape the surface
        });
}

}  // namespace

TriangleMesh readMeshFile(const std::string& path, double unitsToMm, const std::string& source,
                          const std::string& place) {
    std::string extension = fs::path(path).extension().string();
    for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    openInputFile(path);  // a folder, device or missing file is named as such first
    if (extension != ".stl" && extension != ".obj")
        throw InputError(source, place,
                         "'" + path + "' is no .stl or .obj file; export the object as STL or OBJ");
    const std::string bytes = readBoundedFile(path, kMaxMeshFileBytes, "a mesh file");
    const Reading r{path, source, place, unitsToMm};
    TriangleMesh mesh;
    Welder weld(mesh, unitsToMm);
    if (extension == ".obj") {
        readObj(bytes, r, weld, mesh);
    } else if (isBinaryStl(bytes)) {
        readBinaryStl(bytes, r, weld, mesh);
    } else {
        const auto first = bytes.find_first_not_of(" \t\r\n");
        if (first == std::string::npos || bytes.compare(first, 5, "solid") != 0)
            r.fail(
                "its start",
                "neither a binary STL (84 bytes and 50 a triangle) nor an ASCII one (\"solid\")");
        readAsciiStl(bytes, r, weld, mesh);
    }
    if (mesh.triangles.empty())
        throw InputError(source, place,
                         "'" + path + "' holds no triangle; give the surface of the object");
    return mesh;
}

}  // namespace activetouch
