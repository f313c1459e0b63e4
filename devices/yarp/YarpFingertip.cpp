#include "devices/yarp/YarpFingertip.h"

#include <QByteArray>
#include <QEventLoop>
#include <QTcpSocket>
#include <QTimer>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>

#include "core/common/InputError.h"

namespace activetouch::yarp {
namespace {

using Clock = std::chrono::steady_clock;

using Stopped = std::function<bool()>;

/// Reads one line within `deadline`; empty optional on timeout, a closed socket or `stopped`.
std::optional<std::string> readLine(QTcpSocket& s, QByteArray& buffer, Clock::time_point deadline,
                                    const Stopped& stopped) {
    for (;;) {
        const int nl = buffer.indexOf('\n');
        if (nl >= 0) {
            std::string line = buffer.left(nl).toStdString();
            buffer.remove(0, nl + 1);
            if (!line.empty() && line.back() == '\r') line.pop_back();
            return line;
        }
        // A reply line past the decoder's cap is no YARP reply: the wait ends as if timed out.
        if (static_cast<std::size_t>(buffer.size()) > StreamDecoder::kMaxTextLineBytes)
            return std::nullopt;
        const auto left =
            std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
        if (left <= 0 || s.state() != QAbstractSocket::ConnectedState || stopped())
            return std::nullopt;
        if (s.waitForReadyRead(static_cast<int>(std::min<long long>(left, 100))))
            buffer += s.readAll();
    }
}

std::string where(const NameServerAddress& a) {
    return a.host + ":" + std::to_string(a.port) + " (" + a.source + ")";
}

/// Reads exactly `n` bytes within `deadline`; fewer on timeout, a closed socket or `stopped`.
QByteArray readExactly(QTcpSocket& s, QByteArray& buffer, int n, Clock::time_point deadline,
                       const Stopped& stopped) {
    while (buffer.size() < n) {
        const auto left =
            std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
        if (left <= 0 || s.state() != QAbstractSocket::ConnectedState || stopped()) break;
        if (s.bytesAvailable() > 0 ||
            s.waitForReadyRead(static_cast<int>(std::min<long long>(left, 100))))
            buffer += s.read(n - buffer.size());
    }
    QByteArray head = buffer.left(n);
    buffer.remove(0, head.size());
    return head;
}

/// Connects `s` to host:port within `ms`, looking at `stopped` between waits of at most
/// DeviceWorker::kStepBound_ms; true once connected. On false, `why` says what happened.
bool connectWithin(QTcpSocket& s, const std::string& host, int port, int ms,
                   const Stopped& stopped, std::string* why) {
    s.connectToHost(QString::fromStdString(host), static_cast<quint16>(port));
    const auto until = Clock::now() + std::chrono::milliseconds(ms);
    while (s.state() != QAbstractSocket::ConnectedState) {
        if (s.state() == QAbstractSocket::UnconnectedState) {
            *why = s.errorString().toStdString();
            return false;
        }
        if (stopped()) {
            *why = "stopped";
            return false;
        }
        if (Clock::now() >= until) {
            *why = "no answer within " + std::to_string(ms) + " ms";
            s.abort();
            return false;
        }
        QEventLoop wait;
        QTimer::singleShot(DeviceWorker::kStepBound_ms, &wait, &QEventLoop::quit);
        QObject::connect(&s, &QAbstractSocket::connected, &wait, &QEventLoop::quit);
        QObject::connect(&s, &QAbstractSocket::errorOccurred, &wait, &QEventLoop::quit);
        wait.exec();
    }
    return true;
}

/// Why a peer that should have greeted with a line starting "Welcome" did not: silent, closed,
/// or something else said.
std::string noWelcome(const QTcpSocket& s, const QByteArray& buffer,
                      const std::optional<std::string>& line, int ms) {
    if (line) return "answered '" + shortened(*line, 60) + "' instead of YARP's welcome";
    if (!buffer.isEmpty())
        return "sent '" + shortened(buffer.left(60).toStdString(), 60) +
               "' without ending its line";
    if (s.state() != QAbstractSocket::ConnectedState)
        return "accepted the connection and closed it without a word";
    return "accepted the connection but said nothing within " + std::to_string(ms) + " ms";
}

}  // namespace

YarpFingertip::YarpFingertip(YarpFingertipSettings settings, RawLog log)
    : s_(std::move(settings)), log_(std::move(log)), compensation_(kFingertipTaxels) {}

YarpFingertip::~YarpFingertip() {
    disconnect();
}

void YarpFingertip::connect() {
    disconnect();
    {
        std::lock_guard lock(mutex_);
        failure_.clear();
        lastProblem_.clear();
        seq_ = 0;
        history_.clear();
        badInRow_ = 0;
        calibrated_ = 0;
        compensation_ = SkinCompensation(kFingertipTaxels);
        lastEnvelope_.clear();
        try {
            nameServer_ = resolveNameServer(s_.nameServerHost, s_.nameServerPort);
        } catch (const YarpError& e) {
            throw RigError(std::string("YARP: ") + e.what());
        }
    }
    badMessages_ = 0;
    stalled_ = false;
    std::promise<std::string> ready;
    auto result = ready.get_future();
    thread_.start([this, &ready] { run(&ready); });
    // The thread answers within its own bounded waits (name server, data port, welcome, the
    // first frame); a stop asked for meanwhile ends them within one step.
    const auto until = Clock::now() + std::chrono::milliseconds(3 * s_.connectTimeoutMs +
                                                                s_.firstFrameTimeoutMs + 1000);
    while (result.wait_for(std::chrono::milliseconds(DeviceWorker::kStepBound_ms)) !=
           std::future_status::ready) {
        if (s_.stop && s_.stop->load()) {
            thread_.stop();
            throw RigError("YARP: connecting to " + s_.port + " was stopped");
        }
        if (Clock::now() > until) {
            thread_.stop();
            throw RigError("YARP: connecting to " + s_.port + " did not finish in time");
        }
    }
    const std::string problem = result.get();
    if (!problem.empty()) {
        thread_.stop();
        // A wait the stop cut short reports what it saw; the stop is what happened.
        if (s_.stop && s_.stop->load())
            throw RigError("YARP: connecting to " + s_.port + " was stopped");
        throw RigError(problem);
    }
    running_ = true;
}

void YarpFingertip::disconnect() {
    thread_.stop();
    running_ = false;
    cv_.notify_all();
}

void YarpFingertip::run(std::promise<std::string>* ready) {
    // Nothing may leave the reader thread: whatever goes wrong in it ends the device in a fault
    // with a message (and answers a connect still waiting), never std::terminate.
    bool answered = false;
    try {
        serve(ready, answered);
    } catch (const std::exception& e) {
        fault(std::string("YARP: reading ") + s_.port + " failed (" + e.what() +
                  "); reconnect the fingertip",
              ready, answered);
    } catch (...) {
        fault("YARP: reading " + s_.port + " failed; reconnect the fingertip", ready, answered);
    }
}

void YarpFingertip::fault(const std::string& problem, std::promise<std::string>* ready,
                          bool& answered) {
    {
        std::lock_guard lock(mutex_);
        if (failure_.empty()) failure_ = problem;
        cv_.notify_all();
    }
    if (!answered) {  // connect() is still waiting: it reports the problem
        answered = true;
        ready->set_value(problem);
        return;
    }
    if (log_) log_("!!", problem);
}

void YarpFingertip::serve(std::promise<std::string>* ready, bool& answered) {
    QByteArray buffer;
    Registration reg;
    if (const std::string problem = lookUpPort(&reg, buffer); !problem.empty()) {
        fault(problem, ready, answered);
        return;
    }
    QTcpSocket data;
    if (const std::string problem = openDataPort(data, reg, buffer); !problem.empty()) {
        fault(problem, ready, answered);
        return;
    }
    data.flush();
    readFrames(data, buffer, ready, answered);
}

void YarpFingertip::say(const std::string& direction, const std::string& text) const {
    if (log_) log_(direction, text);
}

std::function<bool()> YarpFingertip::stopped() const {
    return [this] { return thread_.stopRequested() || (s_.stop && s_.stop->load()); };
}

std::chrono::steady_clock::time_point YarpFingertip::connectDeadline() const {
    return Clock::now() + std::chrono::milliseconds(s_.connectTimeoutMs);
}

std::string YarpFingertip::lookUpPort(Registration* reg, QByteArray& buffer) {
    const NameServerAddress ns = nameServer();
    QTcpSocket server;
    std::string why;
    if (!connectWithin(server, ns.host, ns.port, s_.connectTimeoutMs, stopped(), &why)) {
        return "YARP: the name server at " + where(ns) + " cannot be reached (" + why +
               "); start yarpserver there, or give the name server's address ('yarp conf' "
               "prints where YARP keeps it)";
    }
    say("->", "CONNACK extern");
    server.write(QByteArray::fromStdString(nameServerGreeting()));
    const auto welcome = readLine(server, buffer, connectDeadline(), stopped());
    if (!welcome || welcome->rfind("Welcome", 0) != 0) {
        return "YARP: the server at " + where(ns) + " " +
               noWelcome(server, buffer, welcome, s_.connectTimeoutMs) +
               ", so it is no YARP name server; check its address";
    }
    say("<-", *welcome);
    say("->", "query " + s_.port);
    server.write(QByteArray::fromStdString(nameServerQuery(s_.port)));
    std::vector<std::string> lines;
    const auto until = connectDeadline();
    for (;;) {
        const auto line = readLine(server, buffer, until, stopped());
        if (!line) {
            return "YARP: the name server at " + where(ns) + " did not finish its answer about " +
                   s_.port;
        }
        say("<-", *line);
        lines.push_back(*line);
        if (line->rfind("*** end of message", 0) == 0) break;
    }
    try {
        const auto r = parseRegistration(lines);
        if (!r) {
            return "YARP: the port " + s_.port + " is not registered with the name server at " +
                   where(ns) +
                   "; check the port name ('yarp name list') and that the skin "
                   "module is running";
        }
        *reg = *r;
    } catch (const YarpError& e) {
        return std::string("YARP: ") + e.what();
    }
    return std::string();
}

std::string YarpFingertip::openDataPort(QTcpSocket& data, const Registration& reg,
                                        QByteArray& buffer) {
    std::string why;
    if (!connectWithin(data, reg.host, reg.tcpPort, s_.connectTimeoutMs, stopped(), &why)) {
        return "YARP: " + s_.port + " is registered at " + reg.host + ":" +
               std::to_string(reg.tcpPort) + " but cannot be reached (" + why +
               "); is the skin module still running?";
    }
    buffer.clear();
    if (s_.binaryCarrier) {
        say("->", "binary header (fast_tcp), sender " + s_.readerName);
        data.write(QByteArray::fromStdString(binaryConnectionHeader(s_.readerName)));
        const QByteArray reply = readExactly(data, buffer, 8, connectDeadline(), stopped());
        try {
            const int answered = parseHeaderReply(reply.toStdString());
            say("<-", "header reply, port " + std::to_string(answered));
        } catch (const YarpError& e) {
            return "YARP: " + s_.port + " at " + reg.host + ":" + std::to_string(reg.tcpPort) +
                   " did not answer the binary carrier's header (" +
                   (reply.size() < 8
                        ? "it sent " + std::to_string(reply.size()) + " of the 8 bytes in time"
                        : std::string(e.what())) +
                   "); is it a YARP port? The text carrier is the other choice";
        }
        say("->", "reverse request (~r): become a reader");
        data.write(QByteArray::fromStdString(reverseRequest()));
    } else {
        say("->", "CONNECT extern");
        data.write(QByteArray::fromStdString(dataGreeting()));
        const auto welcome = readLine(data, buffer, connectDeadline(), stopped());
        if (!welcome || welcome->rfind("Welcome", 0) != 0) {
            return "YARP: " + s_.port + " " +
                   noWelcome(data, buffer, welcome, s_.connectTimeoutMs) +
                   "; is it a YARP port speaking the text carrier?";
        }
        say("<-", *welcome);
        say("->", "r");
        data.write(QByteArray::fromStdString(becomeReader()));
    }
    return std::string();
}

void YarpFingertip::readFrames(QTcpSocket& data, const QByteArray& buffer,
                               std::promise<std::string>* ready, bool& answered) {
    StreamDecoder decoder(s_.binaryCarrier);
    auto lastMessage = Clock::now();
    auto decode = [&](const QByteArray& bytes) {
        for (StreamDecoder::Event& e :
             decoder.feed(bytes.constData(), static_cast<std::size_t>(bytes.size()))) {
            if (e.kind == StreamDecoder::Event::Fatal) {
                fault("YARP: " + s_.port + ": " + e.problem + "; reconnect the fingertip", ready,
                      answered);
                return;
            }
            if (e.kind == StreamDecoder::Event::Bad) {
                bad(e.problem);
                continue;
            }
            try {
                deliver(e.values, e.envelope);
                lastMessage = Clock::now();
                if (!answered) {  // the first frame: connect() returns
                    ready->set_value(std::string());
                    answered = true;
                }
                if (stalled_.exchange(false)) say("<-", "frames again after a stall");
            } catch (const YarpError& err) {
                bad(err.what());
            }
        }
    };
    const auto firstFrameBy = Clock::now() + std::chrono::milliseconds(s_.firstFrameTimeoutMs);
    if (!buffer.isEmpty()) decode(buffer);  // what came with the welcome or the header reply
    while (!thread_.stopRequested()) {
        {
            std::lock_guard lock(mutex_);
            if (!failure_.empty()) break;
        }
        if (!answered && Clock::now() > firstFrameBy) {
            const std::string last = lastProblem();
            fault("YARP: connected to " + s_.port + " as a reader, but no frame came within " +
                      std::to_string(s_.firstFrameTimeoutMs) + " ms" +
                      (last.empty() ? "; is the skin module writing to the port?"
                                    : " that could be read (last: " + last + ")"),
                  ready, answered);
            break;
        }
        if (data.state() != QAbstractSocket::ConnectedState) {
            fault("YARP: " + s_.port + " closed the connection; reconnect the fingertip", ready,
                  answered);
            break;
        }
        if (answered && !stalled_ &&
            Clock::now() - lastMessage > std::chrono::milliseconds(s_.stallReportMs)) {
            stalled_ = true;
            const std::string problem = "no frame from " + s_.port + " for " +
                                        std::to_string(s_.stallReportMs) +
                                        " ms: the stream has stalled";
            say("!!", problem);
            std::lock_guard lock(mutex_);
            lastProblem_ = problem;
        }
        if (data.bytesAvailable() > 0 || data.waitForReadyRead(50)) decode(data.read(kReadChunk));
    }
    data.abort();
}

void YarpFingertip::deliver(const std::vector<double>& hand, const std::string& envelope) {
    std::vector<double> tip = fingertipTaxels(hand, s_.finger);  // throws for the wrong size
    {
        std::lock_guard lock(mutex_);
        lastEnvelope_ = envelope;
    }
    if (s_.compensateRaw) {
        if (calibrated_ < s_.calibrationFrames) {
            compensation_.calibrate(tip);
            ++calibrated_;
            return;
        }
        tip = compensation_.compensate(tip);
    }
    std::lock_guard lock(mutex_);
    ++seq_;
    history_.push_back(std::move(tip));
    if (history_.size() > kHistory) history_.pop_front();
    lastFrame_ = Clock::now();
    badInRow_ = 0;
    if (log_ && seq_ % 50 == 1) log_("<-", "frame " + std::to_string(seq_) + " (one in 50 shown)");
    cv_.notify_all();
}

void YarpFingertip::bad(const std::string& problem) {
    ++badMessages_;
    if (log_) log_("!!", problem);
    std::lock_guard lock(mutex_);
    lastProblem_ = problem;
    if (++badInRow_ >= s_.maxBadMessagesInRow) {
        failure_ = "YARP: " + std::to_string(badInRow_) + " messages in a row from " + s_.port +
                   " could not be read (last: " + problem + "); check the port and the finger";
        cv_.notify_all();
    }
}

void YarpFingertip::latestFrame(double* out) const {
    std::lock_guard lock(mutex_);
    if (history_.empty())
        std::fill(out, out + kFingertipTaxels, 0.0);
    else
        std::copy(history_.back().begin(), history_.back().end(), out);
}

std::uint64_t YarpFingertip::waitFrame(std::uint64_t after, int timeoutMs, double* out) {
    std::unique_lock lock(mutex_);
    if (!running_ && failure_.empty())
        throw RigError("YARP fingertip: not connected to " + s_.port + "; connect it first");
    cv_.wait_for(lock, std::chrono::milliseconds(timeoutMs),
                 [&] { return seq_ > after || !failure_.empty() || thread_.stopRequested(); });
    if (!failure_.empty()) throw RigError(failure_);
    if (seq_ <= after) return 0;
    // The frame right after `after` if it is still held (so that a tap sees every frame), else
    // the oldest held; the latest one for a first call.
    const std::uint64_t oldest = seq_ - history_.size() + 1;
    const std::uint64_t want = after == 0 ? seq_ : std::max(after + 1, oldest);
    const auto& f = history_[static_cast<std::size_t>(want - oldest)];
    std::copy(f.begin(), f.end(), out);
    return want;
}

std::uint64_t YarpFingertip::framesReceived() const {
    std::lock_guard lock(mutex_);
    return seq_;
}

std::string YarpFingertip::lastEnvelope() const {
    std::lock_guard lock(mutex_);
    return lastEnvelope_;
}

NameServerAddress YarpFingertip::nameServer() const {
    std::lock_guard lock(mutex_);
    return nameServer_;
}

std::string YarpFingertip::lastProblem() const {
    std::lock_guard lock(mutex_);
    return lastProblem_;
}

double YarpFingertip::secondsSinceFrame() const {
    std::lock_guard lock(mutex_);
    if (seq_ == 0) return std::numeric_limits<double>::infinity();
    return std::chrono::duration<double>(Clock::now() - lastFrame_).count();
}

}  // namespace activetouch::yarp
