// Training and test tap recordings (data/taps.csv), as analyse and check read them.
#include "core/common/InputError.h"
#include "core/records/TapCsv.h"
#include "fuzz/FuzzInput.h"

using namespace activetouch;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = fuzz::writeInput("taps.csv", data, size);
    try {
        std::string cut;
        readTapCsv(path, ClassSet{}, &cut);
    } catch (const InputError&) {
    }
    return 0;
}
