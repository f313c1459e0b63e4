#pragma once
// The LEGO NXT direct-command telegram codec (docs/protocols.md §1): bytes in, messages out, no
// device. Over USB a telegram is the bulk payload itself, at most 64 bytes, little-endian
// integers. A request is [type][opcode][parameters]; 0x00 / 0x01 ask for a reply, 0x80 / 0x81 do
// not (and the brick then sends nothing). A reply is [0x02][opcode][status][payload].
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace activetouch::nxt {

using Bytes = std::vector<std::uint8_t>;

enum Opcode : std::uint8_t {
    PlayTone = 0x03,
    SetOutputState = 0x04,
    SetInputMode = 0x05,
    GetOutputState = 0x06,
    GetInputValues = 0x07,
    ResetMotorPosition = 0x0A,
    GetBatteryLevel = 0x0B,
    KeepAlive = 0x0D,
    GetDeviceInfo = 0x9B,  // a system command
};

/// A telegram the codec refuses to build or a reply it cannot accept, in a sentence.
class TelegramError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// The brick's name for a status byte ("ok", "bad input or output specified", ...).
std::string statusName(std::uint8_t status);

// Requests. `reply` false sends the no-reply variant (0x80 / 0x81).
Bytes playTone(std::uint16_t frequencyHz, std::uint16_t durationMs, bool reply);
/// Motor ports 0, 1, 2 (A, B, C) or 0xFF (all); power -100..100. Throws TelegramError otherwise.
Bytes setOutputState(std::uint8_t port, int power, std::uint8_t mode, std::uint8_t regulation,
                     int turnRatio, std::uint8_t runState, std::uint32_t tachoLimit, bool reply);
/// Sensor ports 0..3 (S1..S4).
Bytes setInputMode(std::uint8_t port, std::uint8_t type, std::uint8_t mode, bool reply);
Bytes getOutputState(std::uint8_t port);
Bytes getInputValues(std::uint8_t port);
Bytes resetMotorPosition(std::uint8_t port, bool relative, bool reply);
Bytes getBatteryLevel();
Bytes keepAlive();
Bytes getDeviceInfo();

/// Whether the brick answers this request at all.
bool expectsReply(const Bytes& request);

// Motor modes and run states.
inline constexpr std::uint8_t MotorOn = 0x01, Brake = 0x02, Regulated = 0x04;
inline constexpr std::uint8_t RegulationIdle = 0, RegulationSpeed = 1, RegulationSync = 2;
inline constexpr std::uint8_t RunIdle = 0x00, RunRampUp = 0x10, RunRunning = 0x20,
                              RunRampDown = 0x40;

struct Reply {
    std::uint8_t opcode = 0;
    std::uint8_t status = 0;
    Bytes payload;  ///< after the status byte
};

/// Checks a reply to `request`: the reply type byte, the echoed opcode and the status. Throws
/// TelegramError naming what is wrong (a short reply, a wrong opcode, a non-zero status).
Reply decodeReply(const Bytes& reply, const Bytes& request);

struct OutputState {
    std::uint8_t port, mode, regulation, runState;
    int power, turnRatio;
    std::uint32_t tachoLimit;
    std::int32_t tachoCount, blockTachoCount, rotationCount;
};
OutputState decodeOutputState(const Reply& reply);

struct InputValues {
    std::uint8_t port;
    bool valid, calibrated;
    std::uint8_t type, mode;
    std::uint16_t raw, normalized;
    std::int16_t scaled, calibratedValue;
};
InputValues decodeInputValues(const Reply& reply);

std::uint16_t decodeBatteryMillivolts(const Reply& reply);
std::uint32_t decodeKeepAliveSleepMs(const Reply& reply);

struct DeviceInfo {
    std::string name;
    std::uint8_t bluetoothAddress[6];
    std::uint32_t freeFlash;
};
DeviceInfo decodeDeviceInfo(const Reply& reply);

}  // namespace activetouch::nxt
