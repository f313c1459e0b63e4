#include "core/scene/Scene.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "core/common/NumberText.h"
#include "core/geometry/SvgPath.h"
#include "core/scene/MeshObject.h"
#include "core/scene/SvgObject.h"

#ifndef ACTIVETOUCH_RESOURCE_DIR
#define ACTIVETOUCH_RESOURCE_DIR "resources"
#endif

namespace activetouch {
namespace fs = std::filesystem;

Polygon ObjectSpec::outline() const {
    Polygon local = shape == "polygon" ? Polygon(polygon) : libraryShape(shape, size);
    return local.transformed(rotationDeg, offset);
}

std::vector<Polygon> ObjectSpec::possibleOutlines() const {
    if (!rotationDrawn) return {outline()};
    std::vector<Polygon> outlines;
    ObjectSpec turned = *this;
    for (int deg = 0; deg < 360; deg += 10) {
        turned.rotationDeg = deg;
        outlines.push_back(turned.outline());
    }
    return outlines;
}

bool SceneSpec::lists(const std::string& effect) const {
    for (const auto& e : effects)
        if (e.name == effect) return true;
    return false;
}

std::string resourceDirectory() {
    if (const char* env = std::getenv("ACTIVETOUCH_RESOURCES"); env && *env) return env;
    return ACTIVETOUCH_RESOURCE_DIR;
}

FingertipSpec loadFingertip(const std::string& nameOrPath, const std::string& relativeTo,
                            const std::string& source, const std::string& place) {
    fs::path path;
    if (nameOrPath.size() > 5 && nameOrPath.substr(nameOrPath.size() - 5) == ".json") {
        path = fs::path(nameOrPath);
        if (path.is_relative()) path = fs::path(relativeTo) / path;
    } else {
        path = fs::path(resourceDirectory()) / "fingertip" / (nameOrPath + ".json");
    }
    std::error_code ec;
    if (!fs::exists(path, ec))
        throw InputError(source, place,
                         "fingertip '" + shortened(nameOrPath) + "' not found (looked for " +
                             shortened(path.string()) +
                             "); use a name from resources/fingertip/ or a path to a .json file");
    const std::string file = path.string();
    const Json j = readJsonFile(file);
    JsonFields f(j, file, "");
    f.rejectUnknownKeys({"name", "description", "taxels_mm", "body", "mount",
                         "receptive_field_sigma_mm", "counts_per_mm", "grid_step_mm",
                         "max_indentation_mm"});
    FingertipSpec spec;
    spec.name = f.text("name");
    if (!f.has("taxels_mm") || !f.raw("taxels_mm").is_array() || f.raw("taxels_mm").empty())
        f.fail("taxels_mm", "expected a non-empty list of [x, y, z] taxel positions in mm");
    const Json& taxels = f.raw("taxels_mm");
    if (taxels.size() > static_cast<std::size_t>(kMaxTaxels))
        f.fail("taxels_mm", "a fingertip of " + std::to_string(taxels.size()) +
                                " taxels; at most " + std::to_string(kMaxTaxels) +
                                " (a whole iCub hand has 192)");
    for (std::size_t i = 0; i < taxels.size(); ++i) {
        const Json& t = taxels[i];
        if (!t.is_array() || t.size() != 3 || !t[0].is_number() || !t[1].is_number() ||
            !t[2].is_number())
            throw InputError(file, "/taxels_mm/" + std::to_string(i),
                             "expected [x, y, z] in mm, found " + describeJson(t));
        for (int c = 0; c < 3; ++c)
            if (!std::isfinite(t[c].get<double>()) || std::abs(t[c].get<double>()) > 100.0)
                throw InputError(file, "/taxels_mm/" + std::to_string(i),
                                 "a taxel lies " + describeJson(t[c]) +
                                     " mm from the fingertip's frame; taxels lie within 100 mm");
        spec.taxels.push_back({t[0].get<double>(), t[1].get<double>(), t[2].get<double>()});
    }
    const JsonFields body = f.object("body");
    body.rejectUnknownKeys({"radius_mm", "cap_start_mm", "tip_end_mm"});
    spec.radius = body.number("radius_mm", 1.0, 30.0);
    spec.capStart = body.number("cap_start_mm", -100.0, 100.0);
    spec.tipEnd = body.number("tip_end_mm", spec.capStart + 0.5, 200.0);
    const JsonFields mount = f.object("mount");
    mount.rejectUnknownKeys({"tilt_deg", "heading_deg"});
    spec.mountTiltDeg = mount.number("tilt_deg", 2.0, 88.0);
    spec.mountHeadingDeg = mount.number("heading_deg", -360.0, 360.0);
    spec.receptiveFieldSigma = f.number("receptive_field_sigma_mm", 0.1, 10.0);
    spec.countsPerMm = f.number("counts_per_mm", 1.0, 10000.0);
    spec.gridStep = f.number("grid_step_mm", 0.1, 2.0, 0.5);
    spec.maxIndentation = f.number("max_indentation_mm", 0.5, 20.0, 6.0);
    return spec;
}

namespace {

/// A library shape's sizes as the file gives them. One of width and height alone scales the
/// whole shape (its arms and opening too, unless given) and keeps its aspect; both set each.
ShapeSize scaledShapeSize(const std::string& shape, const JsonFields& f) {
    ShapeSize size = defaultShapeSize(shape);
    double scale = 1.0;
    if (f.has("width_mm") != f.has("height_mm"))
        scale = f.has("width_mm") ? f.number("width_mm", 1.0, 1000.0) / size.width
                                  : f.number("height_mm", 1.0, 1000.0) / size.height;
    size.width = f.number("width_mm", 1.0, 1000.0, scale * size.width);
    size.height = f.number("height_mm", 1.0, 1000.0, scale * size.height);
    size.arm = f.number("arm_mm", 1.0, 1000.0, shapeHasArms(shape) ? scale * size.arm : 1.0);
    size.opening = f.number("opening_mm", 1.0, 1000.0, shape == "C" ? scale * size.opening : 1.0);
    return size;
}

/// An outline drawn as SVG path data: flattened within the tolerance, centred on its bounding
/// box and turned the right way up (SVG's y axis points down).
std::vector<Vec2> svgOutline(const JsonFields& f) {
    if (!f.has("svg_path") || !f.raw("svg_path").is_string())
        f.fail("svg_path", "an svg object needs 'svg_path': the d of one closed SVG path, mm");
    const double tolerance = f.number("svg_tolerance_mm", 0.001, 5.0, kDefaultSvgTolerance_mm);
    const Polygon drawn = polygonFromSvgPath(f.raw("svg_path").get<std::string>(), tolerance,
                                             f.source(), f.placeOf("svg_path"));
    return centredOnBox(drawn.vertices(), true);
}

}  // namespace

std::string objectFilePath(const JsonFields& f, const std::string& baseDirectory) {
    fs::path file(f.text("file"));
    if (file.is_relative() && !baseDirectory.empty()) file = fs::path(baseDirectory) / file;
    return file.string();
}

ObjectSpec parseObject(const JsonFields& f, const std::string& baseDirectory) {
    ObjectSpec o;
    f.rejectUnknownKeys({"shape", "width_mm", "height_mm", "arm_mm", "opening_mm", "polygon_mm",
                         "svg_path", "svg_tolerance_mm", "sides", "across_corners_mm",
                         "rotation_deg", "offset_mm", "top_height_mm", "file", "units",
                         "slice_height_mm", "element"});
    o.shape = f.text("shape");
    if (o.shape == "mesh") {
        const MeshOutline mesh = meshOutline(f, baseDirectory);
        o.polygon = mesh.outline;
        o.height_mm = mesh.height_mm;
        o.shape = "polygon";
    } else if (o.shape == "svg_file") {
        o.polygon = svgFileOutline(f, baseDirectory).outline;
        o.shape = "polygon";
    } else if (o.shape == "regular_polygon") {
        // A many-sided training object: one edge facing straight down (outward normal 270 deg),
        // the others every 360 / sides degrees from it.
        const int sides = f.integer("sides", 3, 360);
        const double across = f.number("across_corners_mm", 1.0, 1000.0);
        const double pi = 3.14159265358979323846;
        for (int i = 0; i < sides; ++i) {
            const double a = -pi / 2 - pi / sides + 2.0 * pi * i / sides;
            o.polygon.push_back({0.5 * across * std::cos(a), 0.5 * across * std::sin(a)});
        }
        o.shape = "polygon";
    } else if (o.shape == "svg") {
        o.polygon = svgOutline(f);
        o.shape = "polygon";
    } else if (o.shape == "polygon") {
        if (!f.has("polygon_mm") || !f.raw("polygon_mm").is_array())
            f.fail("polygon_mm",
                   "a polygon object needs 'polygon_mm': a list of [x, y] vertices in mm");
        o.polygon = parseVertexList(f.raw("polygon_mm"), f.source(), f.placeOf("polygon_mm"));
    } else {
        const auto name = libraryShapeName(o.shape);
        if (!name)
            f.fail("shape", "unknown shape '" + o.shape + "'; use a library shape (" +
                                libraryShapeList() +
                                "), polygon with polygon_mm, regular_polygon with sides and "
                                "across_corners_mm, or svg with svg_path");
        o.shape = *name;
        o.size = scaledShapeSize(o.shape, f);
        try {
            libraryShape(o.shape, o.size);
        } catch (const std::invalid_argument& e) {
            throw InputError(f.source(), f.pointer(),
                             std::string("the ") + o.shape + " sizes make no outline: " + e.what());
        }
    }
    if (f.has("rotation_deg") && f.raw("rotation_deg").is_string()) {
        if (f.raw("rotation_deg").get<std::string>() != "random")
            f.fail("rotation_deg",
                   "rotation_deg is a number of degrees, or \"random\" for an angle drawn from "
                   "the seed for each trial");
        o.rotationDrawn = true;
    } else {
        o.rotationDeg = f.number("rotation_deg", -360.0, 360.0, 0.0);
    }
    o.offset = f.point("offset_mm", o.offset);
    o.height_mm = f.number("top_height_mm", 0.1, 500.0, o.height_mm);
    try {
        o.outline();  // placed, the outline must still be one the geometry can work with
    } catch (const std::invalid_argument& e) {
        throw InputError(f.source(), f.placeOf("offset_mm"),
                         "placed at (" + numberText(o.offset.x) + ", " + numberText(o.offset.y) +
                             ") mm, the object's outline is not usable: " + e.what());
    }
    return o;
}

std::vector<Vec2> parseVertexList(const Json& v, const std::string& source,
                                  const std::string& place) {
    std::vector<Vec2> vertices;
    for (std::size_t i = 0; i < v.size(); ++i) {
        if (!v[i].is_array() || v[i].size() != 2 || !v[i][0].is_number() || !v[i][1].is_number())
            throw InputError(source, place + "/" + std::to_string(i),
                             "expected a vertex [x, y] in mm, found " + describeJson(v[i]));
        vertices.push_back({v[i][0].get<double>(), v[i][1].get<double>()});
    }
    if (auto problem = Polygon::problemWith(vertices))
        throw InputError(source, place, "the polygon is not a usable outline: " + *problem);
    return vertices;
}

std::vector<Vec2> loadPolygonFile(const std::string& path) {
    const Json j = readJsonFile(path);
    if (j.is_array()) return parseVertexList(j, path, "");
    const bool scene = j.is_object() && j.contains("object");
    Json object = scene ? j["object"] : j;
    if (!object.is_object())
        throw InputError(path, scene ? "/object" : "",
                         "expected a list of [x, y] vertices in mm, an object with 'polygon_mm' "
                         "or a scene whose object has one; found " +
                             describeJson(object));
    if (!object.contains("shape")) object["shape"] = "polygon";
    const ObjectSpec o = parseObject(JsonFields(object, path, scene ? "/object" : ""));
    if (o.shape != "polygon")
        throw InputError(path, scene ? "/object/shape" : "/shape",
                         "the object is a library shape ('" + o.shape +
                             "'), not a polygon; choose it in the shape list instead");
    return o.polygon;
}

std::string objectPlacementProblem(const ObjectSpec& object, const SceneSpec& scene) {
    if (object.height_mm >= scene.tap.retractHeight_mm)
        return "the object's top (" + numberText(object.height_mm) +
               " mm) is not below the tapper's retract height (" +
               numberText(scene.tap.retractHeight_mm) +
               " mm); raise tap.retract_height_mm or use a lower object";
    if (scene.tap.stroke_mm - (scene.tap.retractHeight_mm - object.height_mm) <= 0.0)
        return "the stroke ends above the object's top face, so no tap can touch it; lengthen the "
               "stroke or lower the retract height";
    Vec2 lo{1e300, 1e300}, hi{-1e300, -1e300};
    for (const Polygon& outline : object.possibleOutlines()) {
        lo = {std::min(lo.x, outline.boundingBoxMin().x),
              std::min(lo.y, outline.boundingBoxMin().y)};
        hi = {std::max(hi.x, outline.boundingBoxMax().x),
              std::max(hi.y, outline.boundingBoxMax().y)};
    }
    if (lo.x < 0 || lo.y < 0 || hi.x > scene.stage.travel_mm.x || hi.y > scene.stage.travel_mm.y)
        return "the object (x " + numberText(lo.x) + ".." + numberText(hi.x) + ", y " +
               numberText(lo.y) + ".." + numberText(hi.y) +
               " mm) does not fit inside the stage travel (0.." +
               numberText(scene.stage.travel_mm.x) + ", 0.." + numberText(scene.stage.travel_mm.y) +
               " mm" + (object.rotationDrawn ? ", turned any way" : "") +
               "); move it with offset_mm or make it smaller";
    return {};
}

namespace {

TapSpec parseTap(const JsonFields& f) {
    TapSpec t;
    f.rejectUnknownKeys({"retract_height_mm", "descent_speed_mm_s", "stroke_mm",
                         "contact_threshold_counts", "contact_time_s", "settle_s", "samples",
                         "sample_rate_hz", "noise_floor_counts"});
    t.retractHeight_mm = f.number("retract_height_mm", 0.1, 500.0, t.retractHeight_mm);
    t.descentSpeed_mm_s = f.number("descent_speed_mm_s", 0.1, 1000.0, t.descentSpeed_mm_s);
    t.stroke_mm = f.number("stroke_mm", 0.1, 100.0, t.stroke_mm);
    t.contactThreshold = f.number("contact_threshold_counts", 0.01, 3000.0, t.contactThreshold);
    t.contactTime_s = f.number("contact_time_s", 0.0, 10.0, t.contactTime_s);
    t.settle_s = f.number("settle_s", 0.0, 60.0, t.settle_s);
    t.samples = f.integer("samples", 1, kMaxTapSamples, t.samples);
    t.sampleRate_hz = f.number("sample_rate_hz", 1.0, 10000.0, t.sampleRate_hz);
    t.noiseFloor = f.number("noise_floor_counts", 0.0, 255.0, t.noiseFloor);
    if (t.worstCaseStroke_s() > t.window_s() + 1e-9)
        throw InputError(f.source(), f.pointer(),
                         "a full stroke (down " + numberText(t.stroke_mm) +
                             " mm, hold, back up) takes " + numberText(t.worstCaseStroke_s()) +
                             " s but the tap window is " + numberText(t.window_s()) +
                             " s; shorten the stroke, speed up the descent or record more samples");
    return t;
}

}  // namespace

SceneSpec parseScene(const Json& json, const std::string& source, const std::string& pointer,
                     const std::string& baseDirectory) {
    JsonFields f(json, source, pointer);
    // "provenance": where a measured scene's values came from (free form, for people).
    f.rejectUnknownKeys(
        {"description", "provenance", "object", "fingertip", "tap", "stage", "seed", "effects"});
    SceneSpec s;
    s.source = source;
    s.description = f.text("description", "");
    s.object = parseObject(f.object("object"), baseDirectory);
    s.fingertipName = f.text("fingertip", s.fingertipName);
    s.fingertip = loadFingertip(s.fingertipName, baseDirectory, source, f.placeOf("fingertip"));
    if (f.has("tap"))
        s.tap = parseTap(f.object("tap"));
    else
        s.tap = parseTap(JsonFields(Json::object(), source, f.placeOf("tap")));
    if (f.has("stage")) {
        const JsonFields st = f.object("stage");
        st.rejectUnknownKeys({"travel_mm", "speed_mm_s"});
        s.stage.travel_mm = st.point("travel_mm", s.stage.travel_mm);
        if (!(s.stage.travel_mm.x > 0 && s.stage.travel_mm.y > 0))
            st.fail("travel_mm", "stage travel must be positive on both axes");
        if (s.stage.travel_mm.x > kMaxStageTravel_mm || s.stage.travel_mm.y > kMaxStageTravel_mm)
            st.fail("travel_mm", "a stage travel of (" + numberText(s.stage.travel_mm.x) + ", " +
                                     numberText(s.stage.travel_mm.y) +
                                     ") mm is beyond any XY stage (at most " +
                                     numberText(kMaxStageTravel_mm) +
                                     " mm on each axis); give the stage's travel in mm");
        s.stage.speed_mm_s = st.number("speed_mm_s", 0.1, 2000.0, s.stage.speed_mm_s);
    }
    s.seed = static_cast<std::uint64_t>(f.integer("seed", 0, 2147483647L, 1));

    if (const std::string problem = objectPlacementProblem(s.object, s); !problem.empty()) {
        // Name the setting most likely at fault.
        std::string place = f.placeOf("object");
        if (problem.find("retract height") != std::string::npos)
            place += "/top_height_mm";
        else if (problem.find("stroke ends") != std::string::npos)
            place = f.placeOf("tap") + "/stroke_mm";
        throw InputError(source, place, problem);
    }

    if (f.has("effects")) {
        const Json& list = f.raw("effects");
        if (!list.is_array())
            f.fail("effects",
                   "expected a list of effects, e.g. [{\"name\": \"taxel_noise\", "
                   "\"sigma_counts\": 2}]");
        for (std::size_t i = 0; i < list.size(); ++i) {
            const std::string place = f.placeOf("effects") + "/" + std::to_string(i);
            JsonFields e(list[i], source, place);
            EffectSpec spec;
            spec.name = e.text("name");
            spec.parameters = list[i];
            spec.parameters.erase("name");
            spec.place = place;
            if (s.lists(spec.name))
                e.fail("name", "effect '" + spec.name + "' is listed twice; list each effect once");
            s.effects.push_back(std::move(spec));
        }
    }
    return s;
}

SceneSpec loadScene(const std::string& path) {
    const Json j = readJsonFile(path);
    return parseScene(j, path, "", fs::path(path).parent_path().string());
}

Json objectToJson(const ObjectSpec& object) {
    Json o;
    o["shape"] = object.shape;
    if (object.shape == "polygon") {
        Json poly = Json::array();
        for (Vec2 v : object.polygon) poly.push_back({v.x, v.y});
        o["polygon_mm"] = poly;
    } else {
        o["width_mm"] = object.size.width;
        o["height_mm"] = object.size.height;
        if (shapeHasArms(object.shape)) o["arm_mm"] = object.size.arm;
        if (object.shape == "C") o["opening_mm"] = object.size.opening;
    }
    if (object.rotationDrawn)
        o["rotation_deg"] = "random";
    else
        o["rotation_deg"] = object.rotationDeg;
    o["offset_mm"] = {object.offset.x, object.offset.y};
    o["top_height_mm"] = object.height_mm;
    return o;
}

Json sceneToJson(const SceneSpec& s) {
    Json j;
    if (!s.description.empty()) j["description"] = s.description;
    j["object"] = objectToJson(s.object);
    j["fingertip"] = s.fingertipName;
    j["tap"] = {{"retract_height_mm", s.tap.retractHeight_mm},
                {"descent_speed_mm_s", s.tap.descentSpeed_mm_s},
                {"stroke_mm", s.tap.stroke_mm},
                {"contact_threshold_counts", s.tap.contactThreshold},
                {"contact_time_s", s.tap.contactTime_s},
                {"settle_s", s.tap.settle_s},
                {"samples", s.tap.samples},
                {"sample_rate_hz", s.tap.sampleRate_hz},
                {"noise_floor_counts", s.tap.noiseFloor}};
    j["stage"] = {{"travel_mm", {s.stage.travel_mm.x, s.stage.travel_mm.y}},
                  {"speed_mm_s", s.stage.speed_mm_s}};
    j["seed"] = s.seed;
    Json effects = Json::array();
    for (const auto& e : s.effects) {
        Json entry = e.parameters;
        entry["name"] = e.name;
        effects.push_back(entry);
    }
    j["effects"] = effects;
    return j;
}

}  // namespace activetouch
