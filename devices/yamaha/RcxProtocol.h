#pragma once
// The Yamaha RCX controller's line protocol (docs/protocols.md §2): commands are '@' + text + CR LF,
// at most 80 characters; replies are CR LF lines. Two dialects: RCX22x answers OK or NG (and
// [POS] lines for positions); RCX340 answers RUN at once and END when a motion finishes, and a
// line of numbers for positions. Pure text in and out; no port.
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace activetouch::rcx {

enum class Dialect { Rcx22x, Rcx340 };

class ProtocolError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// "@" + command + CR LF; refuses commands over 80 characters or holding a line break.
std::string command(const std::string& text);
std::string servoOn();
std::string servoOff();
std::string origin();
std::string askOrigin();
std::string askPosition();  ///< @?WHRXY: position in mm
std::string resetAlarm();
std::string resetEmergencyStop();
/// @MOVE P, x y z r a b, S=speed (mm, speed 1..100 %). Throws ProtocolError for a bad speed.
std::string moveTo(double x, double y, int speedPercent);
/// The control code that stops motion at once.
inline std::string stop() {
    return std::string(1, '\x03');
}

struct Reply {
    enum class Kind { Ok, Error, Running, Ended, Position, Welcome, Other } kind = Kind::Other;
    std::string code;            ///< for errors: the controller's error number, if any
    std::string message;         ///< for errors: its text
    std::vector<double> values;  ///< for positions: x y z r a b
    std::string line;            ///< the line as received, without CR LF
};

/// Reads one reply line (with or without its CR LF).
Reply parseReply(const std::string& line, Dialect dialect);

/// A sentence for an error reply, naming the command it answered.
std::string describeError(const Reply& reply, const std::string& commandText);

}  // namespace activetouch::rcx
