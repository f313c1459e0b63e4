#include "devices/nxt/NxtTelegram.h"

#include <cstdio>

namespace activetouch::nxt {
namespace {

constexpr std::uint8_t kDirectReply = 0x00, kSystemReply = 0x01, kNoReply = 0x80, kReplyType = 0x02;

void put16(Bytes& b, std::uint16_t v) {
    b.push_back(static_cast<std::uint8_t>(v & 0xFF));
    b.push_back(static_cast<std::uint8_t>(v >> 8));
}
void put32(Bytes& b, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) b.push_back(static_cast<std::uint8_t>((v >> (8 * i)) & 0xFF));
}
std::uint16_t get16(const Bytes& b, std::size_t at) {
    return static_cast<std::uint16_t>(b[at] | (b[at + 1] << 8));
}
std::uint32_t get32(const Bytes& b, std::size_t at) {
    return static_cast<std::uint32_t>(b[at]) | (static_cast<std::uint32_t>(b[at + 1]) << 8) |
           (static_cast<std::uint32_t>(b[at + 2]) << 16) |
           (static_cast<std::uint32_t>(b[at + 3]) << 24);
}
Bytes direct(Opcode op, bool reply) {
    return {reply ? kDirectReply : kNoReply, op};
}
std::string hex(std::uint8_t v) {
    char buf[8];
    std::snprintf(buf, sizeof buf, "0x%02X", v);
    return buf;
}
void checkMotorPort(std::uint8_t port) {
    if (port > 2 && port != 0xFF)
        throw TelegramError("motor port " + std::to_string(port) +
                            " does not exist; use 0, 1, 2 (A, B, C) or 0xFF (all)");
}
void checkSensorPort(std::uint8_t port) {
    if (port > 3)
        throw TelegramError("sensor port " + std::to_string(port) +
                            " does not exist; use 0..3 (S1..S4)");
}
void needPayload(const Reply& r, std::size_t n, const char* what) {
    if (r.payload.size() < n)
        throw TelegramError(std::string(what) + " reply has " + std::to_string(r.payload.size()) +
                            " payload bytes, expected " + std::to_string(n));
}

}  // namespace

std::string statusName(std::uint8_t s) {
    switch (s) {
        case 0x00:
            return "ok";
        case 0x20:
            return "pending communication transaction in progress";
        case 0x40:
            return "specified mailbox queue is empty";
        case 0xBD:
            return "request failed (e.g. specified file not found)";
        case 0xBE:
            return "unknown command opcode";
        case 0xBF:
            return "insane packet";
        case 0xC0:
            return "data contains out-of-range values";
        case 0xDD:
            return "communication bus error";
        case 0xDE:
            return "no free memory in communication buffer";
        case 0xDF:
            return "specified channel or connection is not valid";
        case 0xE0:
            return "specified channel or connection not configured or busy";
        case 0xEC:
            return "no active program";
        case 0xED:
            return "illegal size specified";
        case 0xEE:
            return "illegal mailbox queue ID specified";
        case 0xEF:
            return "attempted to access invalid field of a structure";
        case 0xF0:
            return "bad input or output specified";
        case 0xFB:
            return "insufficient memory available";
        case 0xFF:
            return "bad arguments";
        default:
            break;
    }
    if (s >= 0x81 && s <= 0x93) return "file system error " + hex(s);
    return "unknown status " + hex(s);
}

Bytes playTone(std::uint16_t frequencyHz, std::uint16_t durationMs, bool reply) {
    Bytes b = direct(PlayTone, reply);
    put16(b, frequencyHz);
    put16(b, durationMs);
    return b;
}

Bytes setOutputState(std::uint8_t port, int power, std::uint8_t mode, std::uint8_t regulation,
                     int turnRatio, std::uint8_t runState, std::uint32_t tachoLimit, bool reply) {
    checkMotorPort(port);
    if (power < -100 || power > 100)
        throw TelegramError("motor power " + std::to_string(power) + " is outside -100..100");
    if (turnRatio < -100 || turnRatio > 100)
        throw TelegramError("turn ratio " + std::to_string(turnRatio) + " is outside -100..100");
    Bytes b = direct(SetOutputState, reply);
    b.push_back(port);
    b.push_back(static_cast<std::uint8_t>(static_cast<std::int8_t>(power)));
    b.push_back(mode);
    b.push_back(regulation);
    b.push_back(static_cast<std::uint8_t>(static_cast<std::int8_t>(turnRatio)));
    b.push_back(runState);
    put32(b, tachoLimit);
    return b;
}

Bytes setInputMode(std::uint8_t port, std::uint8_t type, std::uint8_t mode, bool reply) {
    checkSensorPort(port);
    Bytes b = direct(SetInputMode, reply);
    b.push_back(port);
    b.push_back(type);
    b.push_back(mode);
    return b;
}

Bytes getOutputState(std::uint8_t port) {
    checkMotorPort(port);
    if (port == 0xFF)
        throw TelegramError("the output state is read one motor at a time; use port 0, 1 or 2");
    Bytes b = direct(GetOutputState, true);
    b.push_back(port);
    return b;
}

Bytes getInputValues(std::uint8_t port) {
    checkSensorPort(port);
    Bytes b = direct(GetInputValues, true);
    b.push_back(port);
    return b;
}

Bytes resetMotorPosition(std::uint8_t port, bool relative, bool reply) {
    checkMotorPort(port);
    Bytes b = direct(ResetMotorPosition, reply);
    b.push_back(port);
    b.push_back(relative ? 1 : 0);
    return b;
}

Bytes getBatteryLevel() {
    return direct(GetBatteryLevel, true);
}
Bytes keepAlive() {
    return direct(KeepAlive, true);
}
Bytes getDeviceInfo() {
    return {kSystemReply, GetDeviceInfo};
}

bool expectsReply(const Bytes& request) {
    return !request.empty() && (request[0] & 0x80) == 0;
}

Reply decodeReply(const Bytes& reply, const Bytes& request) {
    if (request.size() < 2) throw TelegramError("the request is not a telegram");
    if (reply.size() < 3)
        throw TelegramError("the brick's reply has " + std::to_string(reply.size()) +
                            " bytes; a reply has at least 3");
    if (reply[0] != kReplyType)
        throw TelegramError("the brick's reply starts with " + hex(reply[0]) +
                            ", not the reply type 0x02");
    if (reply[1] != request[1])
        throw TelegramError("the brick answered opcode " + hex(reply[1]) +
                            " to a request for opcode " + hex(request[1]) +
                            "; the link is out of step");
    Reply r{reply[1], reply[2], Bytes(reply.begin() + 3, reply.end())};
    if (r.status != 0)
        throw TelegramError("the brick refused opcode " + hex(r.opcode) + ": " +
                            statusName(r.status) + " (status " + hex(r.status) + ")");
    return r;
}

OutputState decodeOutputState(const Reply& r) {
    needPayload(r, 22, "GETOUTPUTSTATE");
    const Bytes& p = r.payload;
    return {p[0],
            p[2],
            p[3],
            p[5],
            static_cast<std::int8_t>(p[1]),
            static_cast<std::int8_t>(p[4]),
            get32(p, 6),
            static_cast<std::int32_t>(get32(p, 10)),
            static_cast<std::int32_t>(get32(p, 14)),
            static_cast<std::int32_t>(get32(p, 18))};
}

InputValues decodeInputValues(const Reply& r) {
    needPayload(r, 13, "GETINPUTVALUES");
    const Bytes& p = r.payload;
    return {p[0],
            p[1] != 0,
            p[2] != 0,
            p[3],
            p[4],
            get16(p, 5),
            get16(p, 7),
            static_cast<std::int16_t>(get16(p, 9)),
            static_cast<std::int16_t>(get16(p, 11))};
}

std::uint16_t decodeBatteryMillivolts(const Reply& r) {
    needPayload(r, 2, "GETBATTERYLEVEL");
    return get16(r.payload, 0);
}

std::uint32_t decodeKeepAliveSleepMs(const Reply& r) {
    needPayload(r, 4, "KEEPALIVE");
    return get32(r.payload, 0);
}

DeviceInfo decodeDeviceInfo(const Reply& r) {
    needPayload(r, 30, "GETDEVICEINFO");
    DeviceInfo d{};
    const Bytes& p = r.payload;
    for (std::size_t i = 0; i < 15 && p[i] != 0; ++i) d.name.push_back(static_cast<char>(p[i]));
    for (std::size_t i = 0; i < 6; ++i) d.bluetoothAddress[i] = p[15 + i];
    d.freeFlash = get32(p, 26);
    return d;
}

}  // namespace activetouch::nxt
