#include "core/io/MeshFile.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <cmath>
#include <filesystem>
#include <map>
#include <tuple>

#include "core/common/InputError.h"
#include "core/io/InputFile.h"

namespace activetouch {

namespace fs = std::filesystem;

namespace {

/// Welds vertices that lie within a micrometre of one another into one index.
class Welder {
public:
    explicit Welder(TriangleMesh& mesh) : mesh_(mesh) {}
    std::uint32_t index(double x, double y, double z) {
        const auto key = std::make_tuple(std::llround(x * 1000.0), std::llround(y * 1000.0),
                                         std::llround(z * 1000.0));
        const auto [it, fresh] =
            seen_.emplace(key, static_cast<std::uint32_t>(mesh_.vertices.size()));
        if (fresh) mesh_.vertices.push_back({x, y, z});
        return it->second;
    }

private:
    TriangleMesh& mesh_;
    std::map<std::tuple<long long, long long, long long>, std::uint32_t> seen_;
};

void addNode(const aiScene& scene, const aiNode& node, aiMatrix4x4 transform, double unitsToMm,
             Welder& weld, TriangleMesh& mesh) {
    transform = transform * node.mTransformation;
    for (unsigned m = 0; m < node.mNumMeshes; ++m) {
        const aiMesh& am = *scene.mMeshes[node.mMeshes[m]];
        for (unsigned f = 0; f < am.mNumFaces; ++f) {
            const aiFace& face = am.mFaces[f];
            if (face.mNumIndices != 3) continue;  // points and lines bound nothing
            std::array<std::uint32_t, 3> t{};
            for (unsigned i = 0; i < 3; ++i) {
                const aiVector3D v = transform * am.mVertices[face.mIndices[i]];
                t[i] = weld.index(v.x * unitsToMm, v.y * unitsToMm, v.z * unitsToMm);
            }
            mesh.triangles.push_back(t);
        }
    }
    for (unsigned c = 0; c < node.mNumChildren; ++c)
        addNode(scene, *node.mChildren[c], transform, unitsToMm, weld, mesh);
}

}  // namespace

TriangleMesh readMeshFile(const std::string& path, double unitsToMm, const std::string& source,
                          const std::string& place) {
    {
        std::ifstream probe = openInputFile(path);  // refuses folders, pipes, devices by name
    }
    std::error_code ec;
    const auto bytes = fs::file_size(path, ec);
    if (ec || bytes > kMaxMeshFileBytes)
        throw InputError(source, place,
                         "the mesh file '" + path + "' is over " +
                             std::to_string(kMaxMeshFileBytes >> 20) +
                             " MB; export the object at a coarser resolution");
    Assimp::Importer importer;
    const aiScene* scene =
        importer.ReadFile(path, aiProcess_Triangulate | aiProcess_SortByPType |
                                    aiProcess_FindDegenerates | aiProcess_ValidateDataStructure);
    if (!scene || !scene->mRootNode)
        throw InputError(source, place,
                         "'" + path + "' cannot be read as a mesh (" + importer.GetErrorString() +
                             "); give an STL, OBJ or PLY file of the object");
    TriangleMesh mesh;
    Welder weld(mesh);
    addNode(*scene, *scene->mRootNode, aiMatrix4x4(), unitsToMm, weld, mesh);
    if (mesh.triangles.empty())
        throw InputError(source, place,
                         "'" + path + "' holds no triangle; give the surface of the object");
    for (const auto& v : mesh.vertices)
        for (double c : v)
            if (!std::isfinite(c) || std::abs(c) > 100000.0)
                throw InputError(source, place,
                                 "'" + path +
                                     "' has a vertex beyond 100 m (or not a number): check its "
                                     "units");
    return mesh;
}

}  // namespace activetouch
