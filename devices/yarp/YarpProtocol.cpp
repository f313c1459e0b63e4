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

std::vector<double> parseBinaryVector(const std::vector<std::uint8_t>& p) {
    auto int32 = [&](std::size_t at) {
        std::int32_t v;
        std::memcpy(&v, p.data() + at, 4);
        return v;
    };
    if (p.size() < 8) throw YarpError("the binary message is too short to hold a vector");
    const std::int32_t tag = int32(0), count = int32(4);
    if (tag != 0x10A && tag != 0x114)
        throw YarpError("the binary message's tag is not a vector of doubles (0x10A or 0x114)");
    if (count < 0) throw YarpError("the binary message gives a negative element count");
    const std::size_t body = p.size() - 8;
    std::size_t width = 0;
    if (body == static_cast<std::size_t>(count) * 8)
        width = 8;
    else if (body == static_cast<std::size_t>(count) * 4)
        width = 4;
    else
        throw YarpError("the binary vector claims " + std::to_string(count) +
                        " elements but carries " + std::to_string(body) + " bytes");
    std::vector<double> v(static_cast<std::size_t>(count));
    for (std::size_t i = 0; i < v.size(); ++i) {
        if (width == 8)
            std::memcpy(&v[i], p.data() + 8 + 8 * i, 8);
        else {
            float f;
            std::memcpy(&f, p.data() + 8 + 4 * i, 4);
            v[i] = f;
        }
        if (!std::isfinite(v[i]))
            throw YarpError("the binary vector holds a non-finite value at element " +
                            std::to_string(i));
    }
    return v;
}

std::vector<double> fingertipTaxels(const std::vector<double>& hand, Finger finger) {
    if (hand.size() != 192)
        throw YarpError("a hand skin vector has 192 values (16 patches x 12); this one has " +
                        std::to_string(hand.size()));
    const auto first = hand.begin() + static_cast<int>(finger);
    return std::vector<double>(first, first + 12);
}

void SkinCompensation::calibrate(const std::vector<double>& raw) {
    if (static_cast<int>(raw.size()) != taxels_)
        throw YarpError("a calibration frame has " + std::to_string(raw.size()) +
                        " taxels, expected " + std::to_string(taxels_));
    resting_.push_back(raw);
    finishCalibration();
}

void SkinCompensation::finishCalibration() {
    const auto K = static_cast<std::size_t>(taxels_);
    baseline_.assign(K, 0.0);
    threshold_.assign(K, 1.0);
    for (std::size_t k = 0; k < K; ++k) {
        std::vector<double> drop;
        for (const auto& f : resting_) drop.push_back(255.0 - f[k]);
        double mean = 0;
        for (double d : drop) mean += d;
        mean /= static_cast<double>(drop.size());
        baseline_[k] = mean;
        std::vector<double> deviation;
        for (double d : drop) deviation.push_back(std::abs(d - mean));
        std::sort(deviation.begin(), deviation.end());
        const double p95 = deviation[std::min(
            deviation.size() - 1,
            static_cast<std::size_t>(0.95 * static_cast<double>(deviation.size())))];
        threshold_[k] = std::max(1.0, p95);
    }
}

std::vector<double> SkinCompensation::compensate(const std::vector<double>& raw) {
    if (!calibrated())
        throw YarpError("the skin compensation is not calibrated; record resting frames first");
    if (static_cast<int>(raw.size()) != taxels_)
        throw YarpError("a skin frame has " + std::to_string(raw.size()) + " taxels, expected " +
                        std::to_string(taxels_));
    std::vector<double> out(raw.size());
    for (std::size_t k = 0; k < raw.size(); ++k) {
        const double d = 255.0 - raw[k] - baseline_[k];
        const double gain = d > threshold_[k] ? 0.05 : 0.2;
        baseline_[k] += gain * 0.02 * d / threshold_[k];
        out[k] = std::clamp(d, 0.0, 255.0);
    }
    return out;
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
    events.push_back({Event::Fatal, {}, problem});
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
            if (isMessageHeader(line))
                wantHeader_ = false;
            else
                events.push_back({Event::Bad, {},
                                  "a line where a message header belongs: '" +
                                      line.substr(0, 40) + "'"});
            continue;
        }
        wantHeader_ = true;
        try {
            events.push_back({Event::Values, parseDataLine(line), {}});
        } catch (const YarpError& e) {
            events.push_back({Event::Bad, {}, e.what()});
        }
    }
}

namespace {

std::int32_t int32At(const std::string& b, std::size_t at) {
    std::int32_t v;
    std::memcpy(&v, b.data() + at, 4);
    return v;
}

}  // namespace

void StreamDecoder::decodeBinary(std::vector<Event>& events) {
    // "YA" int32 "RP", block count, block lengths, reply length, then the blocks.
    while (!dead_ && buffered() >= 12) {
        const std::size_t at = start_;
        if (buffer_[at] != 'Y' || buffer_[at + 1] != 'A' || buffer_[at + 6] != 'R' ||
            buffer_[at + 7] != 'P') {
            const std::size_t next = buffer_.find("YA", at + 1);
            events.push_back({Event::Bad, {},
                              "a binary message does not start with its YA..RP marker; skipped "
                              "to the next one"});
            start_ = next == std::string::npos ? buffer_.size() - 1 : next;
            continue;
        }
        const std::int32_t blocks = int32At(buffer_, at + 8);
        if (blocks < 1 || blocks > kMaxBlocks) {
            events.push_back({Event::Bad, {},
                              "a binary message claims " + std::to_string(blocks) + " blocks"});
            start_ = at + 2;
            continue;
        }
        const std::size_t headerBytes = 12 + 4 * static_cast<std::size_t>(blocks) + 4;
        if (buffered() < headerBytes) return;
        std::int64_t total = 0;
        for (int b = 0; b < blocks; ++b) {
            const std::int32_t length = int32At(buffer_, at + 12 + 4 * static_cast<std::size_t>(b));
            if (length < 0 || length > kMaxBlockBytes) {
                fatal(events, "a binary message claims a block of " + std::to_string(length) +
                                  " bytes (at most " + std::to_string(kMaxBlockBytes) +
                                  "); the stream can no longer be framed");
                return;
            }
            total += length;
        }
        if (total > kMaxBlockBytes) {
            fatal(events, "a binary message claims " + std::to_string(total) +
                              " bytes of blocks; the stream can no longer be framed");
            return;
        }
        const std::size_t whole = headerBytes + static_cast<std::size_t>(total);
        if (buffered() < whole) return;
        const std::int32_t lastLength =
            int32At(buffer_, at + 12 + 4 * static_cast<std::size_t>(blocks - 1));
        const char* last = buffer_.data() + at + whole - static_cast<std::size_t>(lastLength);
        const std::vector<std::uint8_t> payload(last, last + lastLength);
        start_ = at + whole;
        try {
            events.push_back({Event::Values, parseBinaryVector(payload), {}});
        } catch (const YarpError& e) {
            events.push_back({Event::Bad, {}, e.what()});
        }
    }
}

}  // namespace activetouch::yarp
