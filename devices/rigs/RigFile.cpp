#include "devices/rigs/RigFile.h"

#include <algorithm>
#include <string_view>

namespace activetouch {

namespace {

// The names a rig file uses, read and written from the same tables: a value's index in its table
// is the setting (Finger steps by 12 along the hand's 192 values, parity is "OEN"'s letter).
const std::vector<std::string> kParities{"odd", "even", "none"};
constexpr char kParityLetters[] = "OEN";
const std::vector<std::string> kDialects{"rcx22x", "rcx340"};
constexpr rcx::Dialect kDialectValues[] = {rcx::Dialect::Rcx22x, rcx::Dialect::Rcx340};
const std::vector<std::string> kFingers{"index", "middle", "ring", "little", "thumb"};

/// The index in `allowed` of `key`'s text (default: the first); anything else fails naming them.
std::size_t indexOf(const JsonFields& f, const std::string& key,
                    const std::vector<std::string>& allowed) {
    const std::string v = f.text(key, allowed.front());
    const auto at = std::find(allowed.begin(), allowed.end(), v);
    if (at != allowed.end()) return static_cast<std::size_t>(at - allowed.begin());
    std::string list;
    for (const std::string& a : allowed) list += (list.empty() ? "'" : ", '") + a + "'";
    f.fail(key, "'" + v + "' is not one of " + list);
}

std::string oneOf(const JsonFields& f, const std::string& key,
                  const std::vector<std::string>& allowed) {
    return allowed[indexOf(f, key, allowed)];
}

std::string deviceOf(const JsonFields& f, const std::vector<std::string>& allowed) {
    if (!f.has("device"))
        f.fail("device", "name the device: " + allowed.front() + " or " + allowed.back());
    return oneOf(f, "device", allowed);
}

void readStage(const JsonFields& f, RigConfig& r) {
    if (deviceOf(f, {"simulated", "yamaha"}) == "simulated") {
        f.rejectUnknownKeys({"device"});
        return;
    }
    f.rejectUnknownKeys(
        {"device", "port", "baud", "parity", "dialect", "speed_percent", "search_origin"});
    r.stage = RigConfig::StageKind::Yamaha;
    rcx::YamahaStageSettings& y = r.yamaha;
    y.serial.portName = f.text("port");
    if (y.serial.portName.empty()) f.fail("port", "name the serial port, e.g. /dev/ttyUSB0");
    y.serial.baud = f.integer("baud", 1200, 115200, y.serial.baud);
    y.serial.parity = kParityLetters[indexOf(f, "parity", kParities)];
    y.dialect = kDialectValues[indexOf(f, "dialect", kDialects)];
    y.speedPercent = f.integer("speed_percent", 1, 100, y.speedPercent);
    r.searchOrigin = f.flag("search_origin", true);
}

void readTapper(const JsonFields& f, RigConfig& r) {
    if (deviceOf(f, {"simulated", "nxt"}) == "simulated") {
        f.rejectUnknownKeys({"device"});
        return;
    }
    f.rejectUnknownKeys({"device", "usb_bus", "usb_address", "motor_port", "degrees_per_mm",
                         "full_power_degrees_per_s"});
    r.tapper = RigConfig::TapperKind::Nxt;
    r.usbBus = f.integer("usb_bus", 0, 255, 0);
    r.usbAddress = f.integer("usb_address", 0, 127, 0);
    r.nxt.motorPort = static_cast<std::uint8_t>(indexOf(f, "motor_port", {"A", "B", "C"}));
    r.nxt.degreesPerMm = f.number("degrees_per_mm", 0.1, 10000.0, r.nxt.degreesPerMm);
    r.nxt.fullPowerDegreesPerSecond =
        f.number("full_power_degrees_per_s", 1.0, 100000.0, r.nxt.fullPowerDegreesPerSecond);
}

/// Whether the fingertip is read over YARP.
bool readFingertip(const JsonFields& f, RigConfig& r) {
    if (deviceOf(f, {"simulated", "yarp"}) == "simulated") {
        f.rejectUnknownKeys({"device"});
        return false;
    }
    f.rejectUnknownKeys({"device", "name_server", "name_server_port", "port", "finger", "carrier",
                         "compensate_raw"});
    yarp::YarpFingertipSettings& y = r.yarp;
    // Absent: from the YARP conf file, as YARP's own tools find the name server.
    y.nameServerHost = f.text("name_server", "");
    if (f.has("name_server") && y.nameServerHost.empty())
        f.fail("name_server",
               "give the name server's host, or leave the key out to take it "
               "from the YARP conf file");
    y.nameServerPort =
        f.has("name_server_port") ? f.integer("name_server_port", 1, 65535, 10000) : 0;
    y.port = f.text("port", y.port);
    if (y.port.empty() || y.port[0] != '/')
        f.fail("port", "a YARP port name starts with '/', e.g. /icub/skin/right_hand_comp");
    y.finger = static_cast<yarp::Finger>(12 * indexOf(f, "finger", kFingers));
    y.binaryCarrier = oneOf(f, "carrier", {"binary", "text"}) == "binary";
    y.compensateRaw = f.flag("compensate_raw", false);
    return true;
}

}  // namespace

bool looksLikeRigFile(const Json& json) {
    if (!json.is_object() || json.contains("object") || json.contains("scene") ||
        json.contains("extends"))
        return false;
    for (const char* key : {"stage", "tapper", "fingertip"})
        if (json.contains(key) && json.at(key).is_object() && json.at(key).contains("device"))
            return true;
    return false;
}

RigConfig parseRigFile(const Json& json, const std::string& source, const SceneSpec& scene) {
    const JsonFields f(json, source, "");
    f.rejectUnknownKeys({"description", "stage", "tapper", "fingertip", "time_scale"});
    RigConfig r;
    r.yamaha.softMax = scene.stage.travel_mm;
    if (f.has("stage")) readStage(f.object("stage"), r);
    if (f.has("tapper")) readTapper(f.object("tapper"), r);
    const bool yarpTip = f.has("fingertip") && readFingertip(f.object("fingertip"), r);
    if (r.tapper == RigConfig::TapperKind::Nxt && !yarpTip)
        throw InputError(source, "/fingertip",
                         "the NXT tapper stops on the real fingertip's pressure; add a fingertip "
                         "section with \"device\": \"yarp\"");
    if (r.tapper == RigConfig::TapperKind::Simulated && yarpTip)
        throw InputError(source, "/tapper",
                         "the simulated tapper taps with the simulated fingertip, so a fingertip "
                         "over YARP needs the NXT tapper: set \"device\": \"nxt\" here, or make "
                         "the fingertip simulated");
    // Emulated devices may run faster than real time; real ones never do.
    r.timeScale = f.number("time_scale", 0.01, 1000.0, 1.0);
    r.yamaha.timeScale = r.timeScale;
    r.nxt.timeScale = r.timeScale;
    return r;
}

Json rigFileJson(const RigConfig& r) {
    Json j = Json::object();
    if (r.stage == RigConfig::StageKind::Yamaha) {
        const rcx::YamahaStageSettings& y = r.yamaha;
        j["stage"] = {{"device", "yamaha"},
                      {"port", y.serial.portName},
                      {"baud", y.serial.baud},
                      {"parity", kParities[std::string_view(kParityLetters).find(y.serial.parity)]},
                      {"dialect", kDialects[static_cast<std::size_t>(y.dialect)]},
                      {"speed_percent", y.speedPercent},
                      {"search_origin", r.searchOrigin}};
    } else {
        j["stage"] = {{"device", "simulated"}};
    }
    if (r.tapper == RigConfig::TapperKind::Nxt) {
        j["tapper"] = {{"device", "nxt"},
                       {"usb_bus", r.usbBus},
                       {"usb_address", r.usbAddress},
                       {"motor_port", std::string(1, static_cast<char>('A' + r.nxt.motorPort))},
                       {"degrees_per_mm", r.nxt.degreesPerMm},
                       {"full_power_degrees_per_s", r.nxt.fullPowerDegreesPerSecond}};
        const yarp::YarpFingertipSettings& y = r.yarp;
        j["fingertip"] = {{"device", "yarp"},
                          {"port", y.port},
                          {"finger", kFingers[static_cast<std::size_t>(y.finger) / 12]},
                          {"carrier", y.binaryCarrier ? "binary" : "text"},
                          {"compensate_raw", y.compensateRaw}};
        if (!y.nameServerHost.empty()) j["fingertip"]["name_server"] = y.nameServerHost;
        if (y.nameServerPort > 0) j["fingertip"]["name_server_port"] = y.nameServerPort;
    } else {
        j["tapper"] = {{"device", "simulated"}};
        j["fingertip"] = {{"device", "simulated"}};
    }
    if (r.timeScale != 1.0) j["time_scale"] = r.timeScale;
    return j;
}

RigConfig readRigFile(const std::string& path, const SceneSpec& scene) {
    return parseRigFile(readJsonFile(path), path, scene);
}

}  // namespace activetouch
