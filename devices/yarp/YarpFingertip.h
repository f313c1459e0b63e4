#pragma once
// The iCub fingertip read over YARP (docs/protocols.md §3, §4): finds the skin port through the
// name server, connects to it as a reader (binary carrier by default, text as an option), and keeps
// the chosen fingertip's latest 12 values, compensating a raw stream skinManager-style if asked.
// The socket lives in the client's own thread; nothing waits without a bound.
#include <QByteArray>
#include <QtGlobal>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <mutex>
#include <string>
#include <vector>

class QTcpSocket;

#include "core/rig/Rig.h"
#include "devices/common/DeviceWorker.h"
#include "devices/yarp/YarpConf.h"
#include "devices/yarp/YarpProtocol.h"

namespace activetouch::yarp {

struct YarpFingertipSettings {
    /// The name server; empty and 0: from the YARP conf file, else 127.0.0.1:10000 (YarpConf.h).
    std::string nameServerHost;
    int nameServerPort = 0;
    std::string port = "/icub/skin/right_hand_comp";
    Finger finger = Finger::Index;
    /// The binary carrier (fast_tcp), as YARP's own ports speak it; false: the text carrier,
    /// which YARP 4's Vector publishers (skinManager's) answer with raw memory.
    bool binaryCarrier = true;
    std::string readerName = "/activetouch/reader";  ///< the name sent in the binary header
    /// The port streams raw values (255 = rest, lower = pressure): compensate them here after
    /// `calibrationFrames` resting frames.
    bool compensateRaw = false;
    int calibrationFrames = 250;  ///< 5 s at 50 Hz, as skinManager
    int connectTimeoutMs = 2000;
    /// After connecting, the first frame must arrive within this, or connect() fails: a port
    /// that accepts a reader but never streams is a fault, not "connected".
    int firstFrameTimeoutMs = 2000;
    /// A stream silent this long is reported as stalled (raw log, lastProblem()); waits for a
    /// frame keep their own bounds, and frames that resume clear it.
    int stallReportMs = 1000;
    /// Messages that cannot be read in a row before the stream counts as failed.
    int maxBadMessagesInRow = 25;
    /// Set (by Ctrl-C, say) while connect() waits: it stops within DeviceWorker::kStepBound_ms.
    const std::atomic<bool>* stop = nullptr;
};

class YarpFingertip final : public TactileSensor {
public:
    using RawLog = std::function<void(const std::string& direction, const std::string& text)>;

    explicit YarpFingertip(YarpFingertipSettings settings, RawLog log = {});
    ~YarpFingertip() override;

    /// Queries the name server and connects to the port as a reader, returning once the first
    /// frame has arrived. Throws RigError naming the name server or port and what to do (server
    /// down, port unknown, refused, no welcome or header reply, no frame in time).
    void connect();
    void disconnect();
    bool connected() const { return running_; }

    int taxelCount() const override { return kFingertipTaxels; }
    void latestFrame(double* out) const override;
    std::uint64_t waitFrame(std::uint64_t after, int timeoutMs, double* out) override;

    std::uint64_t framesReceived() const;
    int badMessages() const { return badMessages_; }
    /// The last message that could not be read, in a sentence (empty if none).
    std::string lastProblem() const;
    /// Seconds since the last good frame (infinity before the first).
    double secondsSinceFrame() const;
    /// Whether the stream has been silent for stallReportMs.
    bool stalled() const { return stalled_; }
    /// The envelope of the last frame ("count time" from a Stamp), empty if it had none.
    std::string lastEnvelope() const;
    /// The name server asked on the last connect, and where its address came from.
    NameServerAddress nameServer() const;
    const YarpFingertipSettings& settings() const { return s_; }

private:
    void run(std::promise<std::string>* ready);
    /// The thread's work: connect, answer `ready`, then read until stopped or failed.
    void serve(std::promise<std::string>* ready, bool& answered);
    // serve's steps. The first two return why they failed, or nothing; each wait is bounded by
    // the connect timeout. `buffer` keeps what came after the last line read.
    std::string lookUpPort(Registration* reg, QByteArray& buffer);
    std::string openDataPort(QTcpSocket& data, const Registration& reg, QByteArray& buffer);
    /// Reads frames until stopped, failed or closed; `buffer`: what came with the welcome.
    void readFrames(QTcpSocket& data, const QByteArray& buffer, std::promise<std::string>* ready,
                    bool& answered);
    void say(const std::string& direction, const std::string& text) const;
    std::chrono::steady_clock::time_point connectDeadline() const;
    /// Whether the reader thread is asked to stop or connect() to give up.
    std::function<bool()> stopped() const;
    /// Ends the device in a fault: sets the failure every wait then reports, and answers
    /// `ready` with it if the connect is still waiting.
    void fault(const std::string& problem, std::promise<std::string>* ready, bool& answered);
    static constexpr qint64 kReadChunk = 64 << 10;  ///< read at most this much per wait
    void deliver(const std::vector<double>& hand, const std::string& envelope);
    void bad(const std::string& problem);

    YarpFingertipSettings s_;
    RawLog log_;
    DeviceWorker thread_{"yarp fingertip"};  ///< reads the data port (its loop waits <= 50 ms)
    std::atomic<bool> running_{false};
    mutable std::mutex mutex_;
    std::condition_variable cv_;
    static constexpr std::size_t kHistory = 256;
    std::deque<std::vector<double>> history_;  ///< the last frames, newest last
    std::uint64_t seq_ = 0;
    std::chrono::steady_clock::time_point lastFrame_{};
    std::string failure_, lastProblem_;
    std::atomic<int> badMessages_{0};
    std::atomic<bool> stalled_{false};
    std::string lastEnvelope_;
    NameServerAddress nameServer_;
    int badInRow_ = 0;
    SkinCompensation compensation_;
    int calibrated_ = 0;
};

}  // namespace activetouch::yarp
