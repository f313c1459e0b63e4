#pragma once
// An emulated YARP name server and skin publisher on loopback TCP (docs/protocols.md §3, §4),
// speaking the bytes a real YARP 4 does: the name server answers CONNACK / query with lines ending
// in \r\n and an <ACK>; the publisher streams a 192-value hand vector at a set rate over the text
// carrier ('d' or 'D' headers, with or without an envelope) or the binary carrier (the header
// reply, the reverse request as a message, the message index, Bottle or Vector layout, tag 0x114
// or 0x10A, with or without a Stamp envelope). The fingertip's 12 values come from a callback.
// Faults: name server down, port unknown, stream stalls (also from the start), malformed
// messages, vectors of the wrong size, raw bytes of any framing, the stream dropping, the port
// closing with ~q.
#include <atomic>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "devices/yarp/YarpProtocol.h"

namespace activetouch::emu {

struct FakeYarpSettings {
    std::string portName = "/icub/skin/right_hand_comp";
    double rate_hz = 50.0;
    int fingerOffset = 0;      ///< first index of the fingertip in the hand vector
    std::string header = "d";  ///< text carrier: "d", "do" or "D"
    /// An envelope with every message: "d 17 1234.5" on the text carrier, a Stamp in the port
    /// command on the binary one.
    bool envelope = false;
    /// Binary carrier: Vector (skinManager's) or Bottle layout, the tag (0x114 float64 in YARP 4,
    /// 0x10A float64 before it) and float32 elements (tag 0x10A in YARP 4).
    yarp::BinaryLayout binaryLayout = yarp::BinaryLayout::Vector;
    std::uint32_t binaryTag = 0x114;
    bool binaryFloats = false;
};

class FakeYarp {
public:
    using Source = std::function<std::vector<double>()>;  ///< 12 values per frame
    FakeYarp(FakeYarpSettings settings, Source fingertip);
    ~FakeYarp();
    FakeYarp(const FakeYarp&) = delete;
    FakeYarp& operator=(const FakeYarp&) = delete;

    /// Listens on loopback (ephemeral ports) and starts serving. Throws std::runtime_error.
    void start();
    void stop();
    int nameServerPort() const { return nameServerPort_; }
    int dataPort() const { return dataPort_; }

    void setNameServerUp(bool up);       ///< down: the listening socket is closed
    void setPortRegistered(bool known);  ///< unknown: queries answer only the end marker
    void setStalled(bool stalled);       ///< stalled: readers get no frames
    void injectMalformedLine();          ///< the next message's data is not numbers
    void injectWrongSize(int values);    ///< the next message carries `values` values
    void setWrongSize(int values);       ///< every message carries `values` values (0: 192)
    /// The next message each reader gets is these bytes, as they are: hostile framing, say.
    void injectRawBytes(std::string bytes);
    /// Closes every reader's connection, as a stream that drops does.
    void dropReaders();
    /// Sends every binary reader ~q and then closes, as a port that is closed does.
    void closePort();
    std::uint64_t framesSent() const { return frames_; }
    int readers() const { return readers_; }

private:
    struct Client;
    void loop();
    void serveNameServer(Client& c);
    void serveData(Client& c);
    /// serveData()'s steps: the carrier's greeting, the binary carrier's name, and the port
    /// command that turns the connection round (true once it came).
    void greet(Client& c);
    void readBinaryName(Client& c);
    bool reversed(Client& c);
    bool reversedBinary(Client& c);
    void publish(Client& c);
    std::vector<double> handVector();  ///< 192 values with the fingertip's, or a faulty size
    std::string textMessage();
    std::string binaryMessage();

    FakeYarpSettings s_;
    Source source_;
    std::thread thread_;
    std::atomic<bool> running_{false};
    std::atomic<bool> nameServerUp_{true}, registered_{true}, stalled_{false};
    std::atomic<bool> malformed_{false}, dropReaders_{false}, closePort_{false};
    std::string raw_;  ///< injectRawBytes's, under rawMutex_
    std::mutex rawMutex_;
    std::atomic<int> wrongSize_{0}, alwaysWrongSize_{0};
    std::atomic<std::uint64_t> frames_{0};
    std::atomic<int> readers_{0};
    int nameServerFd_ = -1, dataFd_ = -1;
    int nameServerPort_ = 0, dataPort_ = 0;
    std::mutex mutex_;
    std::vector<Client> clients_;
    std::uint64_t count_ = 0;
};

}  // namespace activetouch::emu
