// Meshes as an object's outline ("shape": "mesh"), as a scene reads them: the first byte picks the
// file's extension (STL, OBJ, or PLY, which is refused), the rest is the file.
#include "core/common/InputError.h"
#include "core/scene/Scene.h"
#include "fuzz/FuzzInput.h"

using namespace activetouch;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return 0;
    static const char* const kNames[] = {"part.stl", "part.obj", "part.ply"};
    const std::string path = fuzz::writeInput(kNames[data[0] % 3], data + 1, size - 1);
    try {
        parseObject(JsonFields(Json{{"shape", "mesh"}, {"file", path}, {"units", "mm"}},
                               "fuzz.json", "/object"));
    } catch (const InputError&) {
    }
    return 0;
}
