// Contour-following recordings (data/following_taps.csv), as replay and check read them.
#include "core/common/InputError.h"
#include "core/records/FollowingRecording.h"
#include "fuzz/FuzzInput.h"

using namespace activetouch;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = fuzz::writeInput("following_taps.csv", data, size);
    try {
        FollowingRecordingContents contents;
        readFollowingRecording(path, &contents);
    } catch (const InputError&) {
    }
    return 0;
}
