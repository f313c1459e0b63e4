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

}  // namespace activetouch::yarp
