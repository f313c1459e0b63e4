#include "devices/yarp/YarpConf.h"

#include <cstdlib>
#include <filesystem>
#include <system_error>
#include <sstream>
#include <vector>

#include "core/common/InputError.h"
#include "core/io/InputFile.h"
#include "devices/yarp/YarpProtocol.h"

namespace activetouch::yarp {
namespace {

std::string env(const char* name) {
    const char* v = std::getenv(name);
    return v ? std::string(v) : std::string();
}

/// A YARP conf file is a line or a few groups of lines.
constexpr std::size_t kMaxConfBytes = 64u << 10;

/// The text of the conf file at `path`, or nothing if there is none. A folder, a pipe, a device,
/// an unreadable or an oversized file in its place is an error naming it: it is read, like every
/// file, only as a regular file and only up to its bound.
std::optional<std::string> readText(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::exists(std::filesystem::symlink_status(path, ec)) &&
        !std::filesystem::exists(path, ec))
        return std::nullopt;
    try {
        return readBoundedFile(path, kMaxConfBytes, "a YARP conf file");
    } catch (const InputError& e) {
        throw YarpError("the YARP conf file " + e.source() + " cannot be used: " + e.problem() +
                        "; fix it with 'yarp conf <host> <port>' or set the name server for the "
                        "rig");
    }
}

std::vector<std::string> words(const std::string& line) {
    std::vector<std::string> w;
    std::string word;
    for (char c : line) {
        if (c == ' ' || c == '\t' || c == '"' || c == '\r' || c == '\n') {
            if (!word.empty()) w.push_back(word);
            word.clear();
        } else {
            word += c;
        }
    }
    if (!word.empty()) w.push_back(word);
    return w;
}

int portNumber(const std::string& text, const std::string& file) {
    char* end = nullptr;
    const long p = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || p < 1 || p > 65535)
        throw YarpError("the YARP conf file " + file + " gives '" + text +
                        "' as the name server's port, which is no TCP port; fix it with 'yarp "
                        "conf <host> <port>' or set the name server for the rig");
    return static_cast<int>(p);
}

}  // namespace

std::string yarpConfFile() {
    std::string dir = env("YARP_CONFIG_HOME");
    if (dir.empty() && !env("XDG_CONFIG_HOME").empty()) dir = env("XDG_CONFIG_HOME") + "/yarp";
    if (dir.empty() && !env("HOME").empty()) dir = env("HOME") + "/.config/yarp";
    if (dir.empty()) return {};
    std::string space = env("YARP_NAMESPACE");
    if (space.empty()) {
        if (auto text = readText(dir + "/yarp_namespace.conf")) {
            const auto w = words(*text);
            if (!w.empty()) space = w.front();
        }
    } else {
        const auto w = words(space);
        space = w.empty() ? std::string() : w.front();
    }
    if (space.empty() || space == "/root") return dir + "/yarp.conf";
    for (char& c : space)
        if (!((c >= '0' && c <= '9') || (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'))) c = '_';
    return dir + "/" + space + ".conf";
}

std::optional<NameServerAddress> parseYarpConf(const std::string& text, const std::string& file) {
    std::istringstream in(text);
    std::string line;
    std::vector<std::vector<std::string>> lines;
    while (std::getline(in, line)) {
        auto w = words(line);
        if (!w.empty() && w.front()[0] != '#') lines.push_back(std::move(w));
    }
    if (lines.empty()) return std::nullopt;
    NameServerAddress a;
    a.source = file;
    if (lines.front().front()[0] == '[') {
        bool inName = false;
        std::string port;
        for (const auto& w : lines) {
            if (w.front()[0] == '[') {
                inName = w.front() == "[name]";
                continue;
            }
            if (!inName || w.size() < 2) continue;
            if (w[0] == "host") a.host = w[1];
            if (w[0] == "port") port = w[1];
        }
        if (a.host.empty() || port.empty())
            throw YarpError("the YARP conf file " + file +
                            " has no [name] group with a host and a port; fix it with 'yarp conf "
                            "<host> <port>' or set the name server for the rig");
        a.port = portNumber(port, file);
        return a;
    }
    const auto& w = lines.front();
    if (w.size() < 2)
        throw YarpError("the YARP conf file " + file + " reads '" + w.front() +
                        "' where 'host port' belongs; fix it with 'yarp conf <host> <port>' or "
                        "set the name server for the rig");
    a.host = w[0];
    a.port = portNumber(w[1], file);
    return a;
}

NameServerAddress resolveNameServer(const std::string& host, int port) {
    if (!host.empty() && port > 0) return {host, port, "set for the rig"};
    const std::string file = yarpConfFile();
    std::optional<NameServerAddress> conf;
    if (!file.empty())
        if (auto text = readText(file)) conf = parseYarpConf(*text, file);
    if (conf) {
        if (!host.empty()) conf->host = host;
        if (port > 0) conf->port = port;
        if (!host.empty() || port > 0) conf->source = "set for the rig, the rest from " + file;
        return *conf;
    }
    NameServerAddress a{host.empty() ? "127.0.0.1" : host, port > 0 ? port : 10000, {}};
    a.source = host.empty() ? "loopback: no YARP conf file at " +
                                  (file.empty() ? std::string("$HOME/.config/yarp") : file)
                            : "set for the rig; port 10000, no YARP conf file";
    return a;
}

}  // namespace activetouch::yarp
