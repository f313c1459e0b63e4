#include "core/scene/OutlineFile.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "core/common/InputError.h"
#include "core/scene/MeshObject.h"
#include "core/scene/Scene.h"
#include "core/scene/SvgObject.h"

namespace activetouch {

namespace {

std::string lowerExtension(const std::string& path) {
    std::string e = std::filesystem::path(path).extension().string();
    std::transform(e.begin(), e.end(), e.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return e;
}

}  // namespace

bool isMeshFileName(const std::string& path) {
    const std::string e = lowerExtension(path);
    return e == ".stl" || e == ".obj";
}

OutlineFile loadOutlineFile(const std::string& path, const std::string& meshUnits) {
    const std::string e = lowerExtension(path);
    const std::string name = std::filesystem::path(path).filename().string();
    OutlineFile out;
    if (e == ".json") {
        out.polygon = loadPolygonFile(path);
        out.description = "polygon of " + name;
        return out;
    }
    Json object{{"file", path}};
    if (e == ".svg") {
        object["shape"] = "svg_file";
    } else if (isMeshFileName(path)) {
        object["shape"] = "mesh";
        object["units"] = meshUnits;
    } else {
        throw InputError(path, "",
                         "an outline is read from a .json polygon, object or scene, an .svg "
                         "drawing or an .stl or .obj mesh; this file's name ends in none of them");
    }
    try {
        const JsonFields fields(object, path, "");
        if (e == ".svg") {
            SvgFileOutline svg = svgFileOutline(fields, "");
            out.polygon = std::move(svg.outline);
            out.description = svg.element + " of " + name;
            for (const std::string& other : svg.others)
                out.notes.push_back("also drawn, not followed: " + other);
        } else {
            MeshOutline mesh = meshOutline(fields, "");
            out.polygon = std::move(mesh.outline);
            out.height_mm = mesh.height_mm;
            out.description = "slice of " + name + " (" + meshUnits + ")";
        }
    } catch (const InputError& err) {
        throw InputError(path, "", err.problem());
    }
    return out;
}

}  // namespace activetouch
