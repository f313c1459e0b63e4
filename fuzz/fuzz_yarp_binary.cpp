// The YARP binary carrier as the reader thread reads it: the port's reply to the connection
// header, then the message stream (index, port command, envelope, Bottle or Vector content) fed
// in the chunks the first byte picks; and one message's data blocks read on their own.
#include "devices/yarp/YarpProtocol.h"

using namespace activetouch::yarp;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return 0;
    const std::size_t chunk = 1 + data[0] % 128;
    const char* bytes = reinterpret_cast<const char*>(data + 1);
    const std::size_t n = size - 1;
    try {
        parseHeaderReply(std::string(bytes, std::min<std::size_t>(n, 8)));
    } catch (const YarpError&) {
    }
    try {
        parseBinaryContent(bytes, n);
    } catch (const YarpError&) {
    }
    StreamDecoder decoder(true);
    for (std::size_t at = 0; at < n; at += chunk)
        for (const auto& e : decoder.feed(bytes + at, std::min(chunk, n - at)))
            if (e.kind == StreamDecoder::Event::Values && e.values.size() == 192)
                fingertipTaxels(e.values, Finger::Index);
    return 0;
}
