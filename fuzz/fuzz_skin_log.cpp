// Skin logs from YARP's data dumper, taxel maps and pose logs, as import reads them: the input is
// read as each of the three, and a log that reads is cut into taps with and without poses.
#include "core/common/InputError.h"
#include "core/records/DumperLog.h"
#include "core/records/TapCutting.h"
#include "fuzz/FuzzInput.h"

using namespace activetouch;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = fuzz::writeInput("data.log", data, size);
    TaxelMap map;
    map.valuesPerFrame = 14;
    for (int k = 0; k < 12; ++k) map.valueOf.push_back(k + 2);
    std::vector<PoseLogEntry> poses{{0.0, {1, 1}, 1}, {0.5, {2, 2}, 2}};
    try {
        const SkinStream s = readDumperLog(path, map);
        TapCutting c;
        c.samplesPerTap = 3;
        c.reflexThreshold = 20;
        c.leadFrames = 1;
        std::string cut;
        cutTaps(s, nullptr, c, path, "", &cut);
        cutTaps(s, &poses, c, path, "poses.log", &cut);
    } catch (const InputError&) {
    }
    try {
        readTaxelMap(path, 12);
    } catch (const InputError&) {
    }
    try {
        readPoseLog(path, RecordingBounds{});
    } catch (const InputError&) {
    }
    return 0;
}
