#pragma once
// What the run service needs of the simulated rig (docs/design.md §2). The simulated rig itself
// lives in devices/simulated; the window and the command line hand its factory to the runs, so
// that core knows the rig only through this port.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/fingertip/FingertipContactModel.h"
#include "core/geometry/Polygon.h"
#include "core/rig/Rig.h"
#include "core/scene/Scene.h"

namespace activetouch {

/// A rig assembled around one scene: its devices, the object as placed, and what it simulated.
class SceneRig {
public:
    virtual ~SceneRig() = default;
    virtual Rig rig() = 0;
    /// The scene's object as placed in the world, mm.
    virtual const Polygon& object() const = 0;
    /// The physical effects running, by name, in the order the scene lists them.
    virtual std::vector<std::string> activeEffects() const = 0;
    /// Taps simulated so far.
    virtual std::uint64_t tapsSimulated() const = 0;
};

/// Builds simulated rigs.
class SimulatedRigs {
public:
    virtual ~SimulatedRigs() = default;
    /// Refuses a scene whose effects the simulated rig cannot run (an unknown name, a parameter
    /// out of range): throws InputError naming the file, the entry and what to do.
    virtual void checkEffects(const SceneSpec& scene) const = 0;
    /// A rig on the scene's object, with its noise, seed and the effects it lists.
    virtual std::unique_ptr<SceneRig> build(
        const SceneSpec& scene, std::shared_ptr<const FingertipContactModel> model) const = 0;
};

}  // namespace activetouch
