#include "devices/emulators/FakeRcxController.h"

#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace activetouch::emu {
namespace {

using Clock = std::chrono::steady_clock;

std::string upper(std::string s) {
    for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return s;
}

std::string fmt(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.3f", v);
    return b;
}

}  // namespace

FakeRcxController::FakeRcxController(FakeRcxSettings settings) : s_(settings) {
    originDone_ = s_.originDone;
    from_ = to_ = s_.start;
}

FakeRcxController::~FakeRcxController() {
    stop();
}

void FakeRcxController::start() {
    char name[128] = {};
    termios raw{};
    cfmakeraw(&raw);
    if (::openpty(&master_, &slave_, name, &raw, nullptr) != 0)
        throw std::runtime_error("fake RCX controller: cannot open a pseudo-terminal");
    slaveName_ = name;
    ::fcntl(master_, F_SETFL, ::fcntl(master_, F_GETFL) | O_NONBLOCK);
    running_ = true;
    thread_ = std::thread([this] { loop(); });
}

void FakeRcxController::stop() {
    running_ = false;
    if (thread_.joinable()) thread_.join();
    for (int* fd : {&master_, &slave_})
        if (*fd >= 0) {
            ::close(*fd);
            *fd = -1;
        }
}

void FakeRcxController::injectFault(Fault fault, int skip) {
    std::lock_guard lock(mutex_);
    faults_.push_back({fault, skip});
}

Vec2 FakeRcxController::positionLocked(Clock::time_point now) const {
    if (!moving_ || now >= motionEnd_) return to_;
    const double f = std::chrono::duration<double>(now - motionStart_).count() /
                     std::chrono::duration<double>(motionEnd_ - motionStart_).count();
    return from_ + (to_ - from_) * f;
}

Vec2 FakeRcxController::position() {
    std::lock_guard lock(mutex_);
    return positionLocked(Clock::now());
}

bool FakeRcxController::moving() {
    std::lock_guard lock(mutex_);
    return moving_ && Clock::now() < motionEnd_;
}

std::vector<std::string> FakeRcxController::commands() {
    std::lock_guard lock(mutex_);
    return commands_;
}

void FakeRcxController::reply(const std::string& line) {
    out_ += line + "\r\n";
}

void FakeRcxController::startMotion(Vec2 target, double speed, bool) {
    const auto now = Clock::now();
    from_ = positionLocked(now);
    to_ = target;
    motionStart_ = now;
    const double seconds = distance(from_, to_) / speed / s_.timeScale;
    motionEnd_ =
        now + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
    moving_ = true;
    if (s_.dialect == rcx::Dialect::Rcx340) reply("RUN");
}

void FakeRcxController::handle(const std::string& lineIn) {
    std::string line = lineIn;
    if (line.empty()) return;
    if (line[0] != '@') {
        reply("NG=1");  // not a command
        return;
    }
    line.erase(0, 1);
    if (!line.empty() && line[0] == ' ') line.erase(0, 1);
    commands_.push_back(line);
    std::optional<Fault> fault;
    for (auto it = faults_.begin(); it != faults_.end(); ++it) {
        const bool motion = upper(line).rfind("MOVE", 0) == 0 || upper(line) == "ORIGIN";
        if (it->fault == Fault::DropEnd && !motion) continue;
        if (it->skip-- > 0) continue;
        fault = it->fault;
        faults_.erase(it);
        break;
    }
    if (fault == Fault::NoReply) return;
    if (fault == Fault::Vanish) {
        ::close(master_);
        master_ = -1;
        return;
    }
    if (fault == Fault::Garbage) reply("\x7f#%&*!");
    if (fault == Fault::Ng) {
        reply("NG 12: emergency stop (injected)");
        return;
    }
    dropEnd_ = fault == Fault::DropEnd;
    const std::string u = upper(line);
    const bool r340 = s_.dialect == rcx::Dialect::Rcx340;
    if (u == "SERVO ON" || u == "SERVO OFF") {
        servo_ = u == "SERVO ON";
        reply("OK");
    } else if (u == "ORIGIN") {
        if (!servo_) return reply("NG 18: servo off");
        const double speed =
            distance(positionLocked(Clock::now()), {}) / std::max(s_.origin_s, 1e-3);
        startMotion({0.0, 0.0}, std::max(speed, 1.0), true);
        originDone_ = true;
    } else if (u == "?ORIGIN") {
        reply(originDone_ ? "1" : "0");
        reply("OK");
    } else if (u.rfind("MOVE P", 0) == 0) {
        // MOVE P, x y z r a b, S=n
        const auto c1 = line.find(','), c2 = line.find(',', c1 + 1);
        std::istringstream nums(line.substr(c1 + 1, c2 - c1 - 1));
        double x = 0, y = 0;
        const auto s = u.find("S=");
        const int speed = s == std::string::npos ? 100 : std::atoi(u.c_str() + s + 2);
        if (!(nums >> x >> y) || speed < 1 || speed > 100) return reply("NG 2: syntax error");
        if (!servo_) return reply("NG 18: servo off");
        if (!originDone_) return reply("NG 21: origin incomplete");
        if (x < 0 || y < 0 || x > s_.travel.x || y > s_.travel.y)
            return reply("NG 6: soft limit over");
        startMotion({x, y}, s_.fullSpeed_mm_s * speed / 100.0, false);
    } else if (u == "?WHRXY") {
        const Vec2 p = positionLocked(Clock::now());
        const std::string nums = fmt(p.x) + " " + fmt(p.y) + " 0.000 0.000 0.000 0.000";
        reply(r340 ? nums : "[POS] " + nums);
        reply("OK");
    } else if (u == "?VER") {
        reply(r340 ? "RCX340 emulated" : "RCX222 emulated");
        reply("OK");
    } else if (u == "EMGRST" || u == "ALMRST" || u == "AUTO" || u == "MANUAL") {
        reply("OK");
    } else {
        reply("NG 1: unknown command");
    }
}

void FakeRcxController::loop() {
    while (running_) {
        {
            std::lock_guard lock(mutex_);
            if (master_ < 0) {
                // Vanished: nothing more happens on this port.
            } else {
                if (moving_ && Clock::now() >= motionEnd_) {
                    moving_ = false;
                    if (!dropEnd_) reply(s_.dialect == rcx::Dialect::Rcx340 ? "END" : "OK");
                    dropEnd_ = false;
                }
                if (!out_.empty()) {
                    const ssize_t n = ::write(master_, out_.data(), out_.size());
                    if (n > 0) out_.erase(0, static_cast<std::size_t>(n));
                }
            }
        }
        if (master_ < 0) {
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
            continue;
        }
        pollfd p{master_, POLLIN, 0};
        ::poll(&p, 1, 2);
        if (!(p.revents & POLLIN)) continue;
        char buf[256];
        const ssize_t n = ::read(master_, buf, sizeof buf);
        if (n <= 0) continue;
        std::lock_guard lock(mutex_);
        for (ssize_t i = 0; i < n; ++i) {
            const char c = buf[i];
            if (c == '\x03') {  // ETX: stop where it is
                if (moving_) {
                    const Vec2 here = positionLocked(Clock::now());
                    from_ = to_ = here;
                    moving_ = false;
                    commands_.push_back("<ETX>");
                }
                continue;
            }
            if (c == '\n') {
                std::string l = in_;
                in_.clear();
                if (!l.empty() && l.back() == '\r') l.pop_back();
                handle(l);
            } else {
                in_ += c;
            }
        }
    }
}

}  // namespace activetouch::emu
