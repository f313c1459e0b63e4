// The YARP text carrier as the reader thread decodes it, fed in the chunks the first byte
// picks, and the name server's registration reply.
#include <sstream>

#include "devices/yarp/YarpProtocol.h"

using namespace activetouch::yarp;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return 0;
    const std::size_t chunk = 1 + data[0] % 64;
    const char* bytes = reinterpret_cast<const char*>(data + 1);
    StreamDecoder decoder(false);
    for (std::size_t at = 0; at < size - 1; at += chunk)
        for (const auto& e : decoder.feed(bytes + at, std::min(chunk, size - 1 - at)))
            if (e.kind == StreamDecoder::Event::Values && e.values.size() == 192)
                fingertipTaxels(e.values, Finger::Thumb);
    std::vector<std::string> lines;
    std::istringstream in(std::string(bytes, size - 1));
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    try {
        parseRegistration(lines);
    } catch (const YarpError&) {
    }
    return 0;
}
