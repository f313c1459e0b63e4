// Rig files as `check` and `run --rig` read them.
#include "core/common/InputError.h"
#include "core/io/JsonFields.h"
#include "devices/rigs/RigFile.h"
#include "fuzz/FuzzInput.h"

using namespace activetouch;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = fuzz::writeInput("rig.json", data, size);
    try {
        const Json j = readJsonFile(path);
        if (looksLikeRigFile(j)) parseRigFile(j, path, SceneSpec{});
    } catch (const InputError&) {
    }
    return 0;
}
