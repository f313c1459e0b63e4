// Yamaha RCX reply lines in both dialects, and the sentence an error reply becomes.
#include "devices/yamaha/RcxProtocol.h"

using namespace activetouch::rcx;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string line(reinterpret_cast<const char*>(data), size);
    for (Dialect d : {Dialect::Rcx22x, Dialect::Rcx340}) {
        const Reply r = parseReply(line, d);
        if (r.kind == Reply::Kind::Error) describeError(r, "@ORIGIN");
    }
    return 0;
}
