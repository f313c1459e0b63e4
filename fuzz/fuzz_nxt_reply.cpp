// NXT direct-command replies: the first byte picks the request the reply answers, the rest is
// the reply as the brick would send it.
#include "devices/nxt/NxtTelegram.h"

using namespace activetouch::nxt;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return 0;
    const Bytes reply(data + 1, data + size);
    try {
        switch (data[0] % 4) {
            case 0: decodeOutputState(decodeReply(reply, getOutputState(data[0] % 3))); break;
            case 1: decodeInputValues(decodeReply(reply, getInputValues(data[0] % 4))); break;
            case 2: decodeBatteryMillivolts(decodeReply(reply, getBatteryLevel())); break;
            default: decodeDeviceInfo(decodeReply(reply, getDeviceInfo())); break;
        }
    } catch (const TelegramError&) {
    }
    return 0;
}
