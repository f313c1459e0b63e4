#include "devices/yarp/YarpFingertip.h"

#include <QByteArray>
#include <QTcpSocket>
#include <cmath>
#include <cstring>
#include <limits>

namespace activetouch::yarp {
namespace {

using Clock = std::chrono::steady_clock;

/// Reads one line within `deadline`; empty optional on timeout or a closed socket.
std::optional<std::string> readLine(QTcpSocket& s, QByteArray& buffer, Clock::time_point deadline) {
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
        if (left <= 0 || s.state() != QAbstractSocket::ConnectedState) return std::nullopt;
        if (s.waitForReadyRead(static_cast<int>(std::min<long long>(left, 100))))
            buffer += s.readAll();
    }
}

std::string where(const YarpFingertipSettings& s) {
    return s.nameServerHost + ":" + std::to_string(s.nameServerPort);
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
    }
    badMessages_ = 0;
    std::promise<std::string> ready;
    auto result = ready.get_future();
    thread_.start([this, &ready] { run(&ready); });
    // The thread answers within its own bounded waits (name server, data port, welcome).
    if (result.wait_for(std::chrono::milliseconds(3 * s_.connectTimeoutMs + 1000)) !=
        std::future_status::ready) {
        thread_.stop();
        throw RigError("YARP: connecting to " + s_.port + " did not finish in time");
    }
    const std::string problem = result.get();
    if (!problem.empty()) {
        thread_.stop();
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
                          bool answered) {
    if (!answered) {
        ready->set_value(problem);
        return;
    }
    std::lock_guard lock(mutex_);
    if (failure_.empty()) failure_ = problem;
    cv_.notify_all();
    if (log_) log_("!!", problem);
}

void YarpFingertip::serve(std::promise<std::string>* ready, bool& answered) {
    QByteArray buffer;
    Registration reg;
    if (const std::string problem = lookUpPort(&reg, buffer); !problem.empty()) {
        ready->set_value(problem);
        return;
    }
    QTcpSocket data;
    if (const std::string problem = openDataPort(data, reg, buffer); !problem.empty()) {
        ready->set_value(problem);
        return;
    }
    data.flush();
    ready->set_value(std::string());
    answered = true;
    readFrames(data, buffer, ready, answered);
}

void YarpFingertip::say(const std::string& direction, const std::string& text) const {
    if (log_) log_(direction, text);
}

std::chrono::steady_clock::time_point YarpFingertip::connectDeadline() const {
    return Clock::now() + std::chrono::milliseconds(s_.connectTimeoutMs);
}

std::string YarpFingertip::lookUpPort(Registration* reg, QByteArray& buffer) {
    QTcpSocket ns;
    ns.connectToHost(QString::fromStdString(s_.nameServerHost),
                     static_cast<quint16>(s_.nameServerPort));
    if (!ns.waitForConnected(s_.connectTimeoutMs)) {
        return "YARP: the name server at " + where(s_) + " does not answer (" +
               ns.errorString().toStdString() +
               "); start yarpserver there or set the name server's address";
    }
    say("->", "CONNACK extern");
    ns.write(QByteArray::fromStdString(nameServerGreeting()));
    const auto welcome = readLine(ns, buffer, connectDeadline());
    if (!welcome || welcome->rfind("Welcome", 0) != 0) {
        return "YARP: the server at " + where(s_) +
               " did not greet like a YARP name server; check its address";
    }
    say("<-", *welcome);
    say("->", "query " + s_.port);
    ns.write(QByteArray::fromStdString(nameServerQuery(s_.port)));
    std::vector<std::string> lines;
    const auto until = connectDeadline();
    for (;;) {
        const auto line = readLine(ns, buffer, until);
        if (!line) {
            return "YARP: the name server at " + where(s_) + " did not finish its answer about " +
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
                   where(s_) +
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
    data.connectToHost(QString::fromStdString(reg.host), static_cast<quint16>(reg.tcpPort));
    if (!data.waitForConnected(s_.connectTimeoutMs)) {
        return "YARP: " + s_.port + " is registered at " + reg.host + ":" +
               std::to_string(reg.tcpPort) + " but refuses connections (" +
               data.errorString().toStdString() + "); is the skin module still running?";
    }
    buffer.clear();
    if (s_.binaryCarrier) {
        const char header[8] = {'Y', 'A', 0x64, 0x1E, 0, 0, 'R', 'P'};
        QByteArray hello(header, 8);
        const std::string name = "/activetouch/reader";
        const std::int32_t n = static_cast<std::int32_t>(name.size() + 1);
        hello.append(reinterpret_cast<const char*>(&n), 4);
        hello.append(name.c_str(), n);
        hello.append("~r\n");
        say("->", "binary header, name " + name + ", ~r");
        data.write(hello);
    } else {
        say("->", "CONNECT extern");
        data.write(QByteArray::fromStdString(dataGreeting()));
        const auto welcome = readLine(data, buffer, connectDeadline());
        if (!welcome || welcome->rfind("Welcome", 0) != 0) {
            return "YARP: " + s_.port +
                   " did not welcome the connection; is it a "
                   "YARP port speaking the text carrier?";
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
                deliver(e.values);
            } catch (const YarpError& err) {
                bad(err.what());
            }
        }
    };
    if (!buffer.isEmpty()) decode(buffer);  // what came with the welcome
    while (!thread_.stopRequested()) {
        {
            std::lock_guard lock(mutex_);
            if (!failure_.empty()) break;
        }
        if (data.state() != QAbstractSocket::ConnectedState) {
            fault("YARP: " + s_.port + " closed the connection; reconnect the fingertip", ready,
                  answered);
            break;
        }
        if (data.bytesAvailable() > 0 || data.waitForReadyRead(50)) decode(data.read(kReadChunk));
    }
    data.abort();
}

void YarpFingertip::deliver(const std::vector<double>& hand) {
    std::vector<double> tip = fingertipTaxels(hand, s_.finger);  // throws for the wrong size
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
