#pragma once
// A rig file (JSON): which devices a headless run takes its taps on, the same choices as the
// window's Devices panel. Each section names its device; every other key has the panel's default:
//
//   {"stage":     {"device": "yamaha", "port": "/dev/ttyUSB0"},
//    "tapper":    {"device": "nxt"},
//    "fingertip": {"device": "yarp", "port": "/icub/skin/right_hand_comp"}}
//
// A section left out is simulated. The NXT tapper's reflex needs the real fingertip's pressure,
// and the simulated tapper taps with the simulated fingertip, so the two go together.
#include <string>

#include "core/io/JsonFields.h"
#include "core/scene/Scene.h"
#include "devices/rigs/RigAssembly.h"

namespace activetouch {

/// Reads a rig. The stage's soft limits are the scene's stage travel. Throws InputError naming
/// the file, the place and the problem.
RigConfig parseRigFile(const Json& json, const std::string& source, const SceneSpec& scene);
RigConfig readRigFile(const std::string& path, const SceneSpec& scene);

/// The rig file that reads back as `config` (every key written, defaults included; the stage's
/// soft limits and emulator transports are not part of a rig file).
Json rigFileJson(const RigConfig& config);

/// Whether a JSON document is a rig file: stage, tapper or fingertip sections, and no object,
/// scene or extends (which make it a scene or an experiment).
bool looksLikeRigFile(const Json& json);

}  // namespace activetouch
