#pragma once
// A scene (docs/simulated-rig.md): the object on the stage, the fingertip, how the tapper taps, the
// stage, a seed, and the list of physical effects to simulate. Only listed effects run.
#include <cstdint>
#include <string>
#include <vector>

#include "core/common/Limits.h"
#include "core/fingertip/FingertipSpec.h"
#include "core/geometry/Polygon.h"
#include "core/geometry/ShapeLibrary.h"
#include "core/io/JsonFields.h"

namespace activetouch {

struct ObjectSpec {
    std::string shape = "rectangle";  ///< a library name, or "polygon"
    ShapeSize size = defaultShapeSize("rectangle");
    std::vector<Vec2> polygon;  ///< for shape == "polygon", object frame, mm
    double rotationDeg = 0.0;   ///< about the object frame origin
    /// "rotation_deg": "random": each trial on the object turns it by an angle drawn from the
    /// run's seed, uniform over the circle (rotationDeg is then the drawn angle).
    bool rotationDrawn = false;
    Vec2 offset{150.0, 150.0};  ///< where the object frame origin sits on the stage, mm
    double height_mm = 10.0;    ///< top face above the table

    /// The outline on the stage (world frame).
    Polygon outline() const;
    /// The outlines a drawn rotation may give, every 10 degrees (the outline alone otherwise):
    /// what checks before a run must hold for.
    std::vector<Polygon> possibleOutlines() const;
};

/// The tapper's stroke (docs/design.md §3): lower from the retract height at constant speed, stop
/// when the fingertip's total pressure crosses the threshold (or at the stroke limit), hold,
/// return.
struct TapSpec {
    double retractHeight_mm = 12.0;  ///< fingertip first-contact point above the table
    double descentSpeed_mm_s = 25.0;
    double stroke_mm = 5.0;          ///< deepest travel below the retract height
    double contactThreshold = 40.0;  ///< total pressure over all taxels, counts
    double contactTime_s = 0.5;
    double settle_s = 1.5;  ///< pause after the tap window before the next move
    int samples = 50;       ///< T
    double sampleRate_hz = 50.0;
    /// Counts below which a taxel reads as no contact: the least floor a run uses; it measures the
    /// tap-level floor from its own taps in the air (core/validation/ClassRegions.h).
    double noiseFloor = 1.0;

    double window_s() const { return samples / sampleRate_hz; }
    /// Time the worst-case stroke (full stroke down, hold, back up) takes.
    double worstCaseStroke_s() const { return 2.0 * stroke_mm / descentSpeed_mm_s + contactTime_s; }
};

struct StageSpec {
    Vec2 travel_mm{650.0, 300.0};  ///< x 0..travel.x, y 0..travel.y (the paper rig's Yamaha XY-X)
    double speed_mm_s = 50.0;
};

struct EffectSpec {
    std::string name;
    Json parameters;    ///< the effect's own keys (everything but "name")
    std::string place;  ///< JSON pointer of the entry, for errors
};

struct SceneSpec {
    std::string source;  ///< file it came from, for errors
    std::string description;
    ObjectSpec object;
    std::string fingertipName = "icub_fingertip_2010";
    FingertipSpec fingertip;
    TapSpec tap;
    StageSpec stage;
    std::uint64_t seed = 1;
    std::vector<EffectSpec> effects;

    /// Depth below the object's top face at which the stroke limit stops the tip.
    double strokeLimitDepth() const {
        return tap.stroke_mm - (tap.retractHeight_mm - object.height_mm);
    }
    bool lists(const std::string& effect) const;
};

/// Where bundled data lives: $ACTIVETOUCH_RESOURCES, else the source tree's resources/.
std::string resourceDirectory();

/// Loads a fingertip description (resources/fingertip/NAME.json, or a path to a .json file).
FingertipSpec loadFingertip(const std::string& nameOrPath, const std::string& relativeTo,
                            const std::string& source, const std::string& place);

/// Parses an object description (shape or polygon, pose, top height). A mesh's file is found
/// relative to `baseDirectory` (the folder of the file that names it). Throws InputError.
ObjectSpec parseObject(const JsonFields& fields, const std::string& baseDirectory = "");

/// An object's "file" (a mesh, a drawing): relative to `baseDirectory` unless it is absolute.
std::string objectFilePath(const JsonFields& fields, const std::string& baseDirectory);

/// Reads `list`, a list of [x, y] vertices in mm, as an outline. Throws InputError naming
/// `source` and the vertex at `place` + "/i", or `place`, if it is not a usable outline.
std::vector<Vec2> parseVertexList(const Json& list, const std::string& source,
                                  const std::string& place);

/// Reads a polygon file: a list of [x, y] vertices in mm, an object ({"shape": "polygon",
/// "polygon_mm": [...]}; the shape may be left out) or a scene holding such an object. Returns
/// the vertices. Throws InputError naming the file and what it should hold.
std::vector<Vec2> loadPolygonFile(const std::string& path);

/// Why `object` cannot be placed in `scene`'s rig (off the stage, taller than the retract
/// height), or empty. A drawn rotation must fit at every angle.
std::string objectPlacementProblem(const ObjectSpec& object, const SceneSpec& scene);

/// Parses a scene from JSON; `baseDirectory` resolves relative paths. Throws InputError.
SceneSpec parseScene(const Json& json, const std::string& source, const std::string& pointer,
                     const std::string& baseDirectory);
SceneSpec loadScene(const std::string& path);

/// An object as JSON, in the form parseObject reads.
Json objectToJson(const ObjectSpec& object);

/// The scene as JSON, in the form parseScene reads.
Json sceneToJson(const SceneSpec& scene);

}  // namespace activetouch
