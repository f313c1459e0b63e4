#pragma once
// A serial line in its own thread: QSerialPort lives in a worker thread; callers on any thread
// write bytes and read CR LF lines with a timeout. A port that vanishes (cable pulled, adapter
// unplugged) fails every later call with a sentence naming it.
#include <condition_variable>
#include <deque>
#include <mutex>
#include <optional>
#include <string>

#include "core/rig/Rig.h"
#include "devices/common/DeviceWorker.h"

class QSerialPort;

namespace activetouch::rcx {

struct SerialSettings {
    std::string portName;  ///< /dev/ttyUSB0, /dev/ttyS0, a pseudo-terminal...
    int baud = 9600;
    int dataBits = 8;
    char parity = 'O';  ///< 'N', 'E' or 'O'
    int stopBits = 1;
    bool hardwareFlowControl = false;
};

class SerialLineChannel {
public:
    SerialLineChannel();
    ~SerialLineChannel();

    /// Opens the port with `settings`. Throws RigError naming the port and the reason.
    void open(const SerialSettings& settings);
    void close();
    bool isOpen() const;

    /// Queues bytes for the port. Throws RigError if the port is closed or has vanished.
    void write(const std::string& bytes);
    /// Writes bytes and returns once the port has handed them to the operating system (at most
    /// `timeoutMs`), so that a process ending right after still sends them: for a stop, which
    /// must reach the controller. False if they were not written in time. Throws as write().
    bool writeNow(const std::string& bytes, int timeoutMs);
    /// The next line (without CR LF), waiting at most `timeoutMs`; nothing on timeout. Throws
    /// RigError if the port has vanished.
    std::optional<std::string> readLine(int timeoutMs);
    /// Drops every line received so far.
    void discardInput();
    const std::string& portName() const { return settings_.portName; }

private:
    /// Throws RigError if the port is closed or has vanished.
    void requireOpen() const;
    void received(const QByteArray& bytes);
    void failed(const std::string& why);

    /// An RCX reply line is under 100 bytes; past these the port fails (see received()).
    static constexpr std::size_t kMaxLineBytes = 4096;
    static constexpr std::size_t kMaxUnreadLines = 1000;

    SerialSettings settings_;
    DeviceWorker thread_{"serial"};  ///< the port's event loop
    QObject* context_ = nullptr;   ///< lives in thread_
    QSerialPort* port_ = nullptr;  ///< lives in thread_
    mutable std::mutex mutex_;
    std::condition_variable cv_;
    std::deque<std::string> lines_;
    std::string partial_, failure_;
    bool open_ = false;
};

}  // namespace activetouch::rcx
