#include "devices/yarp/YarpProtocol.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

namespace activetouch::yarp {

std::string nameServerGreeting() {
    return "CONNACK extern\n";
}
std::string nameServerQuery(const std::string& port) {
    return "d\nquery " + port + "\n";
}
std::string dataGreeting() {
    return "CONNECT extern\r\n";
}
std::string becomeReader() {
    return "r\n";
}

std::optional<Registration> parseRegistration(const std::vector<std::string>& lines) {
    std::optional<Registration> found;
    bool ended = false;
    for (std::string line : lines) {
        while (!line.empty() && (line.back() == '\r' || line.back() == '\n')) line.pop_back();
        if (line.rfind("*** end of message", 0) == 0) {
            ended = true;
            break;
        }
        if (line.rfind("registration ", 0) != 0) continue;
        std::istringstream in(line);
        std::string word;
        Registration r;
        in >> word;  // registration
        while (in >> word) {
            std::string value;
            if (!(in >> value)) break;
            if (word == "name")
                r.port = value;
            else if (word == "ip")
                r.host = value;
            else if (word == "port") {
                char* end = nullptr;
                const long p = std::strtol(value.c_str(), &end, 10);
                if (*end != '\0' || p <= 0 || p > 65535)
                    throw YarpError("the name server gave port '" + value +
                                    "', which is no TCP port");
                r.tcpPort = static_cast<int>(p);
            } else if (word == "type")
                r.carrier = value;
        }
        if (r.host.empty() || r.tcpPort == 0)
            throw YarpError("the name server's registration line lacks an address: '" + line + "'");
        found = r;
    }
    if (!ended) throw YarpError("the name server's reply ended before '*** end of message'");
    return found;
}

bool isMessageHeader(const std::string& raw) {
    std::string line = raw;
    while (!line.empty() && (line.back() == '\r' || line.back() == '\n')) line.pop_back();
    if (line.empty() || (line[0] != 'd' && line[0] != 'D')) return false;
    std::size_t i = 1;
    if (i < line.size() && line[i] == 'o') ++i;
    return i == line.size() || line[i] == ' ';
}

std::vector<double> parseDataLine(const std::string& line) {
    std::istringstream in(line);
    std::vector<double> v;
    std::string token;
    while (in >> token) {
        char* end = nullptr;
        const double x = std::strtod(token.c_str(), &end);
        if (end == token.c_str() || *end != '\0' || !std::isfinite(x))
            throw YarpError("the skin stream sent '" + token + "' where a number was expected");
        v.push_back(x);
    }
    return v;
}

namespace {

void put32(std::string& s, std::int32_t v) {
    const auto u = static_cast<std::uint32_t>(v);
    for (int i = 0; i < 4; ++i) s.push_back(static_cast<char>((u >> (8 * i)) & 0xFF));
}

std::int32_t int32At(const char* p) {
    std::uint32_t v = 0;
    for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(p[i]);
    return static_cast<std::int32_t>(v);
}

std::string hex(std::int32_t v) {
    std::ostringstream o;
    o << "0x" << std::hex << static_cast<std::uint32_t>(v);
    return o.str();
}

/// "YA" int32 "RP": the 8-byte form YARP writes a number in (headers, indices, replies).
std::string yarpNumber(std::int32_t n) {
    std::string s = "YA";
    put32(s, n);
    return s + "RP";
}

/// Bytes as int32 counts and numbers of one width: the element of tag `type` at `p`.
double element(std::int32_t type, const char* p) {
    switch (type) {
        case 0x01:
            return static_cast<double>(int32At(p));
        case 0x20:
            return static_cast<double>(static_cast<std::int8_t>(p[0]));
        case 0x40: {
            std::int16_t v;
            std::memcpy(&v, p, 2);
            return v;
        }
        case 0x11: {
            std::int64_t v;
            std::memcpy(&v, p, 8);
            return static_cast<double>(v);
        }
        case 0x0A: {  // float32 (YARP 4)
            float f;
            std::memcpy(&f, p, 4);
            return f;
        }
        default: {  // 0x14 float64, and 0x0A's float64 before YARP 4
            double d;
            std::memcpy(&d, p, 8);
            return d;
        }
    }
}

std::size_t widthOf(std::int32_t type) {
    switch (type) {
        case 0x01:
            return 4;
        case 0x20:
            return 1;
        case 0x40:
            return 2;
        case 0x11:
            return 8;
        case 0x0A:
            return 4;
        case 0x14:
            return 8;
        default:
            return 0;
    }
}

}  // namespace

std::string binaryConnectionHeader(const std::string& senderName) {
    std::string s = yarpNumber(7777 + 3);  // fast_tcp: the tcp carrier (3) without acknowledgements
    put32(s, static_cast<std::int32_t>(senderName.size() + 1));
    s += senderName;
    s.push_back('\0');
    return s;
}

int parseHeaderReply(const std::string& b) {
    if (b.size() != 8 || b[0] != 'Y' || b[1] != 'A' || b[6] != 'R' || b[7] != 'P')
        throw YarpError(
            "the port did not answer the binary carrier's header with its 8-byte "
            "YA..RP reply");
    return int32At(b.data() + 2);
}

std::string headerReply(int port) {
    return yarpNumber(port);
}

std::string binaryMessage(const std::vector<std::string>& blocks) {
    std::string m = yarpNumber(10);
    m.push_back(static_cast<char>(blocks.size()));
    m.push_back('\1');  // one reply block, empty
    m.append(8, '\xFF');
    for (const std::string& b : blocks) put32(m, static_cast<std::int32_t>(b.size()));
    put32(m, 0);
    for (const std::string& b : blocks) m += b;
    return m;
}

std::string portCommand(char command) {
    std::string s;
    put32(s, 0);
    s += '~';
    s += command;
    s += '\0';
    s += '\1';
    return s;
}

std::string portCommandWithText(const std::string& text) {
    std::string s;
    put32(s, static_cast<std::int32_t>(text.size() + 1));
    s += "~";
    s.push_back('\0');
    s.push_back('\0');
    s.push_back('\1');
    s += text;
    s.push_back('\0');
    return s;
}

std::string reverseRequest() {
    return binaryMessage({portCommand('r')});
}

std::string binaryDataMessage(const std::vector<double>& values, const BinaryFrame& f) {
    // The port command and its envelope share one block; the content follows as YARP lays it.
    const std::string command =
        f.envelope.empty() ? portCommand('D') : portCommandWithText("D " + f.envelope);
    std::string head;
    put32(head, static_cast<std::int32_t>(f.tag));
    put32(head, static_cast<std::int32_t>(values.size()));
    std::string body;
    for (double v : values) {
        if (f.floats) {
            const float x = static_cast<float>(v);
            body.append(reinterpret_cast<const char*>(&x), 4);
        } else {
            body.append(reinterpret_cast<const char*>(&v), 8);
        }
    }
    if (f.layout == BinaryLayout::Bottle) return binaryMessage({command, head + body});
    return binaryMessage({command, head, body});
}

BinaryContent parseBinaryContent(const char* p, std::size_t size) {
    if (size < 8) throw YarpError("the binary message is too short to hold a port command");
    if (p[4] != '~') throw YarpError("the binary message does not begin with a port command ('~')");
    BinaryContent c;
    c.command = p[5];
    std::size_t at = 8;
    if (c.command == '\0') {
        const std::int32_t n = int32At(p);
        if (n < 1 || static_cast<std::size_t>(n) > size - 8)
            throw YarpError("the binary message's port command claims " + std::to_string(n) +
                            " bytes of text but " + std::to_string(size - 8) + " follow");
        if (p[8 + n - 1] != '\0')
            throw YarpError("the binary message's port command text does not end in NUL");
        const std::string text(p + 8, static_cast<std::size_t>(n - 1));
        at += static_cast<std::size_t>(n);
        if (text.empty()) throw YarpError("the binary message's port command text is empty");
        c.command = text[0];
        if (text.size() > 2 && text[1] == ' ') c.envelope = text.substr(2);
    }
    if (c.command != 'd' && c.command != 'D') return c;
    c.values = parseBinaryVector(p + at, size - at);
    return c;
}

std::vector<double> parseBinaryVector(const std::vector<std::uint8_t>& p) {
    return parseBinaryVector(reinterpret_cast<const char*>(p.data()), p.size());
}

std::vector<double> parseBinaryVector(const char* p, std::size_t size) {
    if (size < 8) throw YarpError("the binary message is too short to hold a vector");
    const std::int32_t tag = int32At(p), count = int32At(p + 4);
    if ((tag & ~0xFF) != 0x100)
        throw YarpError("the binary message carries tag " + hex(tag) +
                        ", not a list of numbers (0x114 or 0x10A for a skin vector)");
    if (count < 0) throw YarpError("the binary message gives a negative element count");
    const std::int32_t type = tag & 0xFF;
    const std::size_t body = size - 8, n = static_cast<std::size_t>(count);
    std::vector<double> v;
    if (type == 0) {  // a mixed list: every element carries its own tag
        if (n > body / 5)
            throw YarpError("the binary list claims " + std::to_string(count) +
                            " elements but carries " + std::to_string(body) + " bytes");
        v.reserve(n);
        std::size_t at = 8;
        for (std::size_t i = 0; i < n; ++i) {
            if (size - at < 4)
                throw YarpError("the binary list ends inside element " + std::to_string(i));
            const std::int32_t t = int32At(p + at);
            const std::size_t w = widthOf(t);
            if (w == 0)
                throw YarpError("element " + std::to_string(i) + " of the binary list has tag " +
                                hex(t) + ", which is not a number");
            at += 4;
            if (size - at < w)
                throw YarpError("the binary list ends inside element " + std::to_string(i));
            v.push_back(element(t, p + at));
            at += w;
        }
        if (at != size)
            throw YarpError("the binary list has " + std::to_string(size - at) +
                            " bytes after its last element");
    } else {
        std::size_t w = widthOf(type);
        std::int32_t as = type;
        if (type == 0x0A) {  // float64 before YARP 4, float32 from it: read from the byte count
            if (n > 0 && body == n * 8) {
                w = 8;
                as = 0x14;
            } else if (n > 0 && body == n * 4) {
                w = 4;
                as = 0x0A;
            }
        }
        if (w == 0)
            throw YarpError("the binary message carries a list of tag " + hex(tag) +
                            ", not of numbers");
        if (n > body / w || body != n * w)
            throw YarpError("the binary vector claims " + std::to_string(count) +
                            " elements but carries " + std::to_string(body) + " bytes");
        v.resize(n);
        for (std::size_t i = 0; i < n; ++i) v[i] = element(as, p + 8 + w * i);
    }
    for (std::size_t i = 0; i < v.size(); ++i)
        if (!std::isfinite(v[i]))
            throw YarpError("the binary vector holds a non-finite value at element " +
                            std::to_string(i));
    return v;
}

std::vector<StreamDecoder::Event> StreamDecoder::feed(const char* data, std::size_t size) {
    std::vector<Event> events;
    if (dead_) return events;
    buffer_.append(data, size);
    if (binary_)
        decodeBinary(events);
    else
        decodeText(events);
    // Decoded bytes go once they are half the buffer: each byte is moved at most a few times.
    if (start_ > 0 && start_ * 2 >= buffer_.size()) {
        buffer_.erase(0, start_);
        start_ = 0;
    }
    return events;
}

void StreamDecoder::fatal(std::vector<Event>& events, const std::string& problem) {
    dead_ = true;
    buffer_.clear();
    start_ = 0;
    events.push_back({Event::Fatal, {}, problem, {}});
}

void StreamDecoder::decodeText(std::vector<Event>& events) {
    while (!dead_) {
        const std::size_t nl = buffer_.find('\n', start_);
        if (nl == std::string::npos) {
            if (buffered() > kMaxTextLineBytes)
                fatal(events, "a text line runs past " + std::to_string(kMaxTextLineBytes >> 10) +
                                  " KiB without ending; this is no skin stream");
            return;
        }
        if (nl - start_ > kMaxTextLineBytes) {
            fatal(events, "a text line of " + std::to_string(nl - start_) +
                              " bytes; a skin message is a few kilobytes");
            return;
        }
        std::string line = buffer_.substr(start_, nl - start_);
        start_ = nl + 1;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (wantHeader_) {
            if (isMessageHeader(line)) {
                wantHeader_ = false;
                const std::size_t space = line.find(' ');
                envelope_ = space == std::string::npos ? std::string() : line.substr(space + 1);
            } else
                events.push_back(
                    {Event::Bad,
                     {},
                     "a line where a message header belongs: '" + line.substr(0, 40) + "'",
                     {}});
            continue;
        }
        wantHeader_ = true;
        try {
            events.push_back({Event::Values, parseDataLine(line), {}, envelope_});
        } catch (const YarpError& e) {
            events.push_back({Event::Bad, {}, e.what(), {}});
        }
    }
}

void StreamDecoder::decodeBinary(std::vector<Event>& events) {
    static const std::string kIndex = yarpNumber(10);
    constexpr std::size_t kIndexBytes = 18;  // the marker, two block counts, eight 0xFF
    while (!dead_ && buffered() >= kIndexBytes) {
        const std::size_t at = start_;
        const char* m = buffer_.data() + at;
        const bool padded = std::all_of(m + 10, m + 18, [](char c) { return c == '\xFF'; });
        if (buffer_.compare(at, 8, kIndex) != 0 || !padded) {
            // Lost framing: skip to the next index marker, keeping a partial one at the end.
            const std::size_t next = buffer_.find(kIndex, at + 1);
            events.push_back({Event::Bad,
                              {},
                              "a binary message does not start with its index (YA 10 RP, the "
                              "block counts, eight 0xFF); skipped to the next one",
                              {}});
            start_ = next != std::string::npos ? next : std::max(at + 1, buffer_.size() - 7);
            continue;
        }
        const int data = static_cast<unsigned char>(m[8]), reply = static_cast<unsigned char>(m[9]);
        if (data < 1 || data > kMaxBlocks || reply > kMaxBlocks) {
            events.push_back({Event::Bad,
                              {},
                              "a binary message claims " + std::to_string(data) +
                                  " data blocks and " + std::to_string(reply) + " reply blocks",
                              {}});
            start_ = at + 2;
            continue;
        }
        const std::size_t headerBytes = kIndexBytes + 4 * static_cast<std::size_t>(data + reply);
        if (buffered() < headerBytes) return;
        std::int64_t dataBytes = 0, total = 0;
        for (int b = 0; b < data + reply; ++b) {
            const std::int32_t length = int32At(m + kIndexBytes + 4 * static_cast<std::size_t>(b));
            if (length < 0 || length > kMaxBlockBytes) {
                fatal(events, "a binary message claims a block of " + std::to_string(length) +
                                  " bytes (at most " + std::to_string(kMaxBlockBytes) +
                                  "); the stream can no longer be framed");
                return;
            }
            total += length;
            if (b < data) dataBytes += length;
        }
        if (total > kMaxBlockBytes) {
            fatal(events, "a binary message claims " + std::to_string(total) +
                              " bytes of blocks; the stream can no longer be framed");
            return;
        }
        const std::size_t whole = headerBytes + static_cast<std::size_t>(total);
        if (buffered() < whole) return;
        start_ = at + whole;
        try {
            BinaryContent c = parseBinaryContent(buffer_.data() + at + headerBytes,
                                                 static_cast<std::size_t>(dataBytes));
            if (c.command == 'q') {
                fatal(events, "the publisher closed its port (it sent ~q)");
                return;
            }
            if (c.command != 'd' && c.command != 'D') {
                events.push_back({Event::Bad,
                                  {},
                                  std::string("a port command '~") +
                                      (std::isprint(static_cast<unsigned char>(c.command))
                                           ? std::string(1, c.command)
                                           : hex(static_cast<unsigned char>(c.command))) +
                                      "' where data belongs; skipped",
                                  {}});
                continue;
            }
            events.push_back({Event::Values, std::move(c.values), {}, std::move(c.envelope)});
        } catch (const YarpError& e) {
            events.push_back({Event::Bad, {}, e.what(), {}});
        }
    }
}

}  // namespace activetouch::yarp
