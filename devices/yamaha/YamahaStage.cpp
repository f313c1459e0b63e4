#include "devices/yamaha/YamahaStage.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

namespace activetouch::rcx {
namespace {

using Clock = std::chrono::steady_clock;

std::string mm(Vec2 p) {
    char b[64];
    std::snprintf(b, sizeof b, "(%.3f, %.3f) mm", p.x, p.y);
    return b;
}

std::string printable(const std::string& s) {
    std::string o;
    for (char c : s) {
        if (c == '\r')
            o += "\\r";
        else if (c == '\n')
            o += "\\n";
        else if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) {
            char b[8];
            std::snprintf(b, sizeof b, "\\x%02X", static_cast<unsigned char>(c));
            o += b;
        } else
            o += c;
    }
    return o;
}

}  // namespace

YamahaStage::YamahaStage(YamahaStageSettings settings, RawLog log)
    : s_(std::move(settings)), log_(std::move(log)) {
    if (s_.speedPercent < 1 || s_.speedPercent > 100 || !(s_.fullSpeed_mm_s > 0) ||
        !(s_.timeScale > 0) || !(s_.softMin.x < s_.softMax.x) || !(s_.softMin.y < s_.softMax.y))
        throw RigError(
            "Yamaha stage: settings out of range (speed 1..100 %, positive full speed, "
            "soft limits with min below max)");
}

YamahaStage::~YamahaStage() {
    disconnect();
}

void YamahaStage::send(const std::string& line) {
    refuseIfInterrupted();
    write(line);
}

bool YamahaStage::write(const std::string& line, bool now) {
    if (log_) log_("->", printable(line));
    if (now) return channel_.writeNow(line, 1000);
    channel_.write(line);
    return true;
}

std::optional<Reply> YamahaStage::await(const std::string& what, int timeoutMs, bool wantEnd) {
    const auto deadline = Clock::now() + std::chrono::milliseconds(timeoutMs);
    // Read in short slices, so that an interrupt (closing) ends the wait within one of them.
    constexpr std::chrono::milliseconds::rep kInterruptCheckMs = 50;
    for (;;) {
        refuseIfInterrupted();
        const auto left =
            std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
        if (left <= 0) return std::nullopt;
        const auto line = channel_.readLine(static_cast<int>(std::min(left, kInterruptCheckMs)));
        if (!line && !channel_.isOpen()) return std::nullopt;
        if (!line) continue;
        Reply r = parseReply(*line, s_.dialect);
        if (log_) log_("<-", printable(*line));
        switch (r.kind) {
            case Reply::Kind::Error:
                throw RigError("Yamaha stage: " + describeError(r, what));
            case Reply::Kind::Other:
                if (log_)
                    log_("!!", "ignored a line the controller should not send: '" +
                                   printable(*line) + "'");
                continue;
            case Reply::Kind::Welcome:
                continue;
            case Reply::Kind::Ended:
                endSeen_ = true;
                if (!wantEnd) continue;
                return r;
            default:
                return r;
        }
    }
}

void YamahaStage::expectOk(const std::string& line, int timeoutMs,
                           const std::atomic<bool>* stopWhen) {
    send(line);
    // One deadline for the whole exchange: a controller repeating RUN cannot hold us forever.
    const auto deadline = Clock::now() + std::chrono::milliseconds(timeoutMs);
    constexpr int kStopCheckMs = 50;
    for (;;) {
        if (stopWhen && stopWhen->load()) {
            stop();
            const std::string command = line.substr(0, line.find_last_not_of("\r\n") + 1);
            throw RigError("Yamaha stage: '" + printable(command) +
                           "' was stopped (ETX) before the controller reported it done; the "
                           "stage stands where it stopped");
        }
        const auto left =
            std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
        const int wait =
            static_cast<int>(stopWhen ? std::min<long long>(left, kStopCheckMs) : left);
        const auto r = left > 0 ? await(line, wait, true) : std::nullopt;
        if (!r && stopWhen && Clock::now() < deadline) continue;  // a slice ended: check again
        if (!r)
            throw RigError("Yamaha stage: no answer to '" + printable(line) + "' within " +
                           std::to_string(timeoutMs) + " ms; check the cable, the port settings (" +
                           std::to_string(s_.serial.baud) + " baud, parity " + s_.serial.parity +
                           ") and the dialect");
        if (r->kind == Reply::Kind::Ok || r->kind == Reply::Kind::Ended) return;
        // RUN: accepted, keep waiting for END.
    }
}

void YamahaStage::connect(bool searchOrigin) {
    channel_.open(s_.serial);
    endSeen_ = false;
    try {
        expectOk(servoOn(), s_.replyTimeoutMs);
        if (searchOrigin) home();
        queryPosition();
    } catch (...) {
        channel_.close();
        throw;
    }
}

void YamahaStage::disconnect() {
    if (!channel_.isOpen()) return;
    stop();
    channel_.close();
}

void YamahaStage::home() {
    expectOk(origin(), static_cast<int>(s_.originTimeout_s * 1000.0 / s_.timeScale) + 1000,
             s_.stopOriginSearch);
    queryPosition();
}

bool YamahaStage::withinSoftLimits(Vec2 p) const {
    return p.x >= s_.softMin.x && p.y >= s_.softMin.y && p.x <= s_.softMax.x && p.y <= s_.softMax.y;
}

Vec2 YamahaStage::position() const {
    std::lock_guard lock(mutex_);
    return position_;
}

Vec2 YamahaStage::queryPosition() {
    const std::string q = askPosition();
    send(q);
    const auto r = await(q, s_.replyTimeoutMs);
    if (!r || r->kind != Reply::Kind::Position || r->values.size() < 2)
        throw RigError("Yamaha stage: no position in answer to @?WHRXY within " +
                       std::to_string(s_.replyTimeoutMs) + " ms");
    // The position line is followed by OK.
    const auto ok = await(q, s_.replyTimeoutMs);
    if (!ok || ok->kind != Reply::Kind::Ok)
        throw RigError("Yamaha stage: the position answer did not end with OK");
    std::lock_guard lock(mutex_);
    position_ = {r->values[0], r->values[1]};
    return position_;
}

int YamahaStage::motionTimeoutMs(double distance) const {
    const double speed = s_.fullSpeed_mm_s * s_.speedPercent / 100.0;
    return static_cast<int>((distance / speed / s_.timeScale + s_.motionMargin_s) * 1000.0);
}

void YamahaStage::moveTo(Vec2 target) {
    if (!withinSoftLimits(target))
        throw RigError("Yamaha stage: target " + mm(target) + " is outside the soft limits x " +
                       std::to_string(s_.softMin.x) + ".." + std::to_string(s_.softMax.x) + ", y " +
                       std::to_string(s_.softMin.y) + ".." + std::to_string(s_.softMax.y) +
                       " mm; nothing was sent");
    const Vec2 from = position();
    const int timeout = motionTimeoutMs(distance(from, target));
    const auto deadline = Clock::now() + std::chrono::milliseconds(timeout);
    const std::string line = rcx::moveTo(target.x, target.y, s_.speedPercent);
    endSeen_ = false;
    try {
        send(line);
        const auto ack = await(line, s_.replyTimeoutMs + timeout, true);
        if (!ack)
            throw RigError("Yamaha stage: no answer to the move to " + mm(target) + " within " +
                           std::to_string(s_.replyTimeoutMs + timeout) + " ms");
        if (ack->kind == Reply::Kind::Running && s_.dialect == Dialect::Rcx340) {
            // Accepted; END says the motion finished.
            const auto left =
                std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now())
                    .count();
            const auto end =
                endSeen_ ? ack : await(line, static_cast<int>(std::max<long long>(left, 1)), true);
            if (!end && log_)
                log_("!!", "END did not come for the move to " + mm(target) +
                               "; confirming arrival from the position");
        }
        // Arrival is confirmed by the position, within tolerance.
        for (;;) {
            const Vec2 p = queryPosition();
            if (distance(p, target) <= s_.arrivalTolerance_mm) return;
            if (Clock::now() > deadline)
                throw RigError("Yamaha stage: the stage is at " + mm(p) + ", not at " + mm(target) +
                               ", " + std::to_string(timeout) + " ms after the move was sent");
            std::this_thread::sleep_for(std::chrono::milliseconds(s_.pollPeriodMs));
        }
    } catch (const RigError& e) {
        throw RigError(std::string(e.what()) + (stop() ? "; the stage was sent a stop"
                                                       : "; the stage could not be sent a stop"));
    }
}

bool YamahaStage::stop() noexcept {
    try {
        // Also after an interrupt: stopping is never refused. It is written out before this
        // returns, so a process that ends right after (Ctrl-C, closing) still stops the stage.
        return write(rcx::stop(), true);
    } catch (...) {
        return false;
    }
}

void YamahaStage::interrupt() noexcept {
    interrupted_ = true;
    stop();
}

void YamahaStage::refuseIfInterrupted() const {
    if (interrupted_)
        throw RigError(
            "Yamaha stage: stopped (ETX; the application is closing); the stage stands where it "
            "stopped and takes no further commands");
}

}  // namespace activetouch::rcx
