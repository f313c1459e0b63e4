#include "devices/yamaha/RcxProtocol.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace activetouch::rcx {
namespace {

std::string trim(std::string s) {
    while (!s.empty() && (s.back() == '\r' || s.back() == '\n' || s.back() == ' ')) s.pop_back();
    std::size_t start = 0;
    while (start < s.size() && s[start] == ' ') ++start;
    return s.substr(start);
}

std::string upper(std::string s) {
    for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return s;
}

bool numbers(const std::string& text, std::vector<double>& out) {
    std::istringstream in(text);
    out.clear();
    std::string token;
    while (in >> token) {
        char* end = nullptr;
        const double v = std::strtod(token.c_str(), &end);
        if (end == token.c_str() || *end != '\0' || !std::isfinite(v)) return false;
        out.push_back(v);
    }
    return !out.empty();
}

}  // namespace

std::string command(const std::string& text) {
    if (text.find_first_of("\r\n") != std::string::npos)
        throw ProtocolError("a command must not hold a line break");
    const std::string line = "@" + text;
    if (line.size() > 80)
        throw ProtocolError("the command '" + line +
                            "' is longer than the controller's 80 characters");
    return line + "\r\n";
}

std::string servoOn() {
    return command("SERVO ON");
}
std::string servoOff() {
    return command("SERVO OFF");
}
std::string origin() {
    return command("ORIGIN");
}
std::string askOrigin() {
    return command("?ORIGIN");
}
std::string askPosition() {
    return command("?WHRXY");
}
std::string resetAlarm() {
    return command("ALMRST");
}
std::string resetEmergencyStop() {
    return command("EMGRST");
}

std::string moveTo(double x, double y, int speedPercent) {
    if (speedPercent < 1 || speedPercent > 100)
        throw ProtocolError("speed " + std::to_string(speedPercent) + " % is outside 1..100");
    if (!std::isfinite(x) || !std::isfinite(y)) throw ProtocolError("a move target must be finite");
    char buf[96];
    std::snprintf(buf, sizeof buf, "MOVE P, %.3f %.3f 0 0 0 0, S=%d", x, y, speedPercent);
    return command(buf);
}

Reply parseReply(const std::string& raw, Dialect) {
    Reply r;
    r.line = trim(raw);
    const std::string u = upper(r.line);
    if (u == "OK") {
        // Done, in both dialects; whether an RCX22x OK after a move means arrived is unverified,
        // so the stage confirms arrival by polling the position.
        r.kind = Reply::Kind::Ok;
        return r;
    }
    if (u == "RUN") {
        r.kind = Reply::Kind::Running;
        return r;
    }
    if (u == "END") {
        r.kind = Reply::Kind::Ended;
        return r;
    }
    if (u.rfind("WELCOME", 0) == 0) {
        r.kind = Reply::Kind::Welcome;
        return r;
    }
    if (u.rfind("NG", 0) == 0) {
        r.kind = Reply::Kind::Error;
        std::string rest = trim(r.line.substr(2));
        if (!rest.empty() && rest[0] == '=') rest = trim(rest.substr(1));
        // "NG=12" or "NG 12: message" or "NG" alone.
        const auto colon = rest.find(':');
        r.code = trim(colon == std::string::npos ? rest : rest.substr(0, colon));
        r.message = colon == std::string::npos ? std::string() : trim(rest.substr(colon + 1));
        return r;
    }
    // "12.345:message" (an error number with a dot) also reports an error.
    const auto colon = r.line.find(':');
    if (colon != std::string::npos && colon > 0) {
        std::vector<double> tmp;
        if (numbers(r.line.substr(0, colon), tmp) && tmp.size() == 1) {
            r.kind = Reply::Kind::Error;
            r.code = trim(r.line.substr(0, colon));
            r.message = trim(r.line.substr(colon + 1));
            return r;
        }
    }
    std::string body = r.line;
    if (u.rfind("[POS]", 0) == 0) body = r.line.substr(5);
    if (numbers(body, r.values)) {
        r.kind = Reply::Kind::Position;
        return r;
    }
    r.values.clear();
    return r;
}

std::string describeError(const Reply& reply, const std::string& commandText) {
    std::string c = trim(commandText);
    std::string text = "the controller refused '" + c + "'";
    if (!reply.code.empty()) text += " with error " + reply.code;
    if (!reply.message.empty()) text += ": " + reply.message;
    return text;
}

}  // namespace activetouch::rcx
