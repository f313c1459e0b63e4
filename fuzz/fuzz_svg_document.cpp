// Whole SVG documents as an object's outline ("shape": "svg_file"), as a scene reads them.
#include "core/common/InputError.h"
#include "core/scene/Scene.h"
#include "fuzz/FuzzInput.h"

using namespace activetouch;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = fuzz::writeInput("drawing.svg", data, size);
    try {
        parseObject(JsonFields(Json{{"shape", "svg_file"}, {"file", path}}, "fuzz.json", "/object"));
    } catch (const InputError&) {
    }
    return 0;
}
