#pragma once
// Reading an iCub skin stream over YARP (docs/protocols.md §3, §4), as pure codecs: the name-server
// query, the text-carrier data lines, the binary carrier's handshake and messages (Bottle and
// Vector layouts, with and without an envelope), picking one fingertip's 12 values out of the
// 192-value hand vector, and skinManager-style compensation of a raw stream. No sockets here.
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace activetouch::yarp {

class YarpError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Name server (text): CONNACK extern, read "Welcome extern", then "d" and the query.
std::string nameServerGreeting();                      ///< "CONNACK extern\n"
std::string nameServerQuery(const std::string& port);  ///< "d\nquery /port\n"

struct Registration {
    std::string port, host;
    int tcpPort = 0;
    std::string carrier;
};
/// Reads the server's reply lines up to "*** end of message"; nothing if the port is unknown.
/// Throws YarpError for a reply it cannot read.
std::optional<Registration> parseRegistration(const std::vector<std::string>& lines);

// Data connection (text carrier): "CONNECT extern\r\n", read "Welcome extern", then "r\n".
std::string dataGreeting();
std::string becomeReader();

/// Whether `line` is a message header ("d", "do", "D", "do 12 3.4" with an envelope...).
bool isMessageHeader(const std::string& line);
/// The numbers of a data line. Throws YarpError naming the offending token.
std::vector<double> parseDataLine(const std::string& line);

// Binary carrier (fast_tcp, no acknowledgements). The reader sends the connection header and its
// own name; the port answers with 8 bytes of its own; the reader then sends the reverse request
// as a whole message, and from then on every frame arrives as a message: an index (the marker
// "YA" int32 10 "RP", a byte counting data blocks, a byte counting reply blocks, eight 0xFF, one
// int32 length per block), then the data blocks back to back: the port command (int32 n, '~',
// the command, 0, 1, then n bytes of text ending in NUL when the command byte is 0), then the
// content.

/// The connection header (`59 41 64 1E 00 00 52 50`) and the sender's name (int32 length with
/// its NUL, the name, NUL).
std::string binaryConnectionHeader(const std::string& senderName);
/// The port's 8-byte answer to the header: "YA" int32 port "RP". Returns the port number it
/// names; throws YarpError if the bytes are not that.
int parseHeaderReply(const std::string& eightBytes);
/// What a port answers to the header (the emulator's side).
std::string headerReply(int port);
/// A whole message of the given data blocks, with one empty reply block, as YARP writes it.
std::string binaryMessage(const std::vector<std::string>& blocks);
/// The port command block: `command` with no text, or (command 0) the text and its NUL, e.g.
/// "D 338 1795648690.92107" for data with a Stamp envelope.
std::string portCommand(char command);
std::string portCommandWithText(const std::string& text);
/// The "become a reader" request: the message holding the port command '~r'.
std::string reverseRequest();

/// How a publisher lays a frame of numbers out: a Bottle as one block (tag, count and values),
/// a yarp::sig::Vector as two (tag and count, then the values in a block of their own).
enum class BinaryLayout { Bottle, Vector };
struct BinaryFrame {
    BinaryLayout layout = BinaryLayout::Vector;
    std::uint32_t tag = 0x114;  ///< 0x114 (list of float64), or 0x10A (float64 before YARP 4)
    bool floats = false;        ///< float32 elements (tag 0x10A in YARP 4)
    std::string envelope;       ///< a Stamp, "count time"; empty: none
};
/// The data message of `values` as a YARP port sends it (port command, then the content).
std::string binaryDataMessage(const std::vector<double>& values, const BinaryFrame& frame);

/// A message's data blocks, back to back, read: the command ('d' or 'D' for data, 'q' when the
/// publisher closes, others as sent), the envelope text after "d "/"D " if any, and for data
/// the numbers. Throws YarpError naming what cannot be read.
struct BinaryContent {
    char command = 0;
    std::string envelope;
    std::vector<double> values;
};
BinaryContent parseBinaryContent(const char* data, std::size_t size);

/// A message's content after the port command: int32 tag, int32 count, count elements. A list
/// of one numeric type (float64 0x114; 0x10A, float64 before YARP 4 and float32 from it, the
/// element size read from the byte count; int32 0x101, int64 0x111, int8 0x120, int16 0x140), or
/// a mixed list (0x100) whose elements each carry a numeric tag. Throws YarpError for anything
/// else.
std::vector<double> parseBinaryVector(const std::vector<std::uint8_t>& payload);
std::vector<double> parseBinaryVector(const char* data, std::size_t size);

/// A reader connection's byte stream (text or binary carrier) decoded as bytes arrive, with no
/// socket: the reader thread feeds it what it reads, tests and the fuzzer feed it anything. Every
/// length the stream claims is checked before it is trusted, and nothing is buffered without a
/// bound: a line or a frame past its cap ends the stream (the framing is lost), a message that
/// cannot be read is reported and skipped.
class StreamDecoder {
public:
    /// The longest text line and the largest binary block a skin stream has any use for: a
    /// 192-value hand vector is under 4 KiB in either carrier.
    static constexpr std::size_t kMaxTextLineBytes = 64u << 10;
    static constexpr std::int64_t kMaxBlockBytes = 1 << 20;
    static constexpr int kMaxBlocks = 16;  ///< data and reply blocks each

    struct Event {
        enum Kind { Values, Bad, Fatal } kind = Values;
        std::vector<double> values;  ///< Values: the message's numbers
        std::string problem;         ///< Bad, Fatal: in a sentence
        std::string envelope;        ///< Values: the envelope sent with them ("count time"), if any
    };

    explicit StreamDecoder(bool binaryCarrier) : binary_(binaryCarrier) {}
    /// Appends `size` bytes and decodes every whole message in order. After a Fatal event the
    /// stream is dead: further bytes are ignored.
    std::vector<Event> feed(const char* data, std::size_t size);
    bool dead() const { return dead_; }
    std::size_t buffered() const { return buffer_.size() - start_; }

private:
    void decodeText(std::vector<Event>& events);
    void decodeBinary(std::vector<Event>& events);
    void fatal(std::vector<Event>& events, const std::string& problem);

    bool binary_;
    bool dead_ = false;
    bool wantHeader_ = true;  ///< text carrier: a message header line comes next
    std::string envelope_;    ///< text carrier: the envelope of the header just read
    std::string buffer_;
    std::size_t start_ = 0;  ///< where the undecoded bytes begin in buffer_
};

/// The first taxel of each fingertip in the 192-value hand vector.
enum class Finger { Index = 0, Middle = 12, Ring = 24, Little = 36, Thumb = 48 };
/// The 12 values of `finger`. Throws YarpError if the vector is not 192 values long.
std::vector<double> fingertipTaxels(const std::vector<double>& hand, Finger finger);

/// skinManager's compensation of a raw stream (raw 0..255, lower = more pressure, resting near
/// 235): calibrate the baseline and a touch threshold (95th percentile of the noise, at least 1)
/// from resting frames, then report d = 255 - raw - baseline clamped to 0..255, nudging the
/// baseline by gain * 0.02 * d / threshold each frame (gain 0.2 without touch, 0.05 in touch).
class SkinCompensation {
public:
    explicit SkinCompensation(int taxels = 12) : taxels_(taxels) {}
    /// Adds a resting frame to the calibration.
    void calibrate(const std::vector<double>& raw);
    bool calibrated() const { return !baseline_.empty(); }
    /// The compensated frame. Throws YarpError before calibration or for a frame of the wrong size.
    std::vector<double> compensate(const std::vector<double>& raw);
    const std::vector<double>& threshold() const { return threshold_; }

private:
    void finishCalibration();
    int taxels_;
    std::vector<std::vector<double>> resting_;
    std::vector<double> baseline_, threshold_;
};

}  // namespace activetouch::yarp
