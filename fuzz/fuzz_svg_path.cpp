// SVG path data as a scene's outline reads it, at a fine and a coarse flattening tolerance.
#include "core/common/InputError.h"
#include "core/geometry/SvgPath.h"

using namespace activetouch;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string d(reinterpret_cast<const char*>(data), size);
    for (double tolerance : {0.05, 2.0}) {
        try {
            polygonFromSvgPath(d, tolerance, "fuzz.svg", "/d");
        } catch (const InputError&) {
        }
    }
    return 0;
}
