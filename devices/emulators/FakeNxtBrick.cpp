#include "devices/emulators/FakeNxtBrick.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <thread>

namespace activetouch::emu {
namespace {

void put32(nxt::Bytes& b, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

}  // namespace

FakeNxtBrick::FakeNxtBrick(FakeNxtSettings settings)
    : s_(std::move(settings)), last_(std::chrono::steady_clock::now()) {}

void FakeNxtBrick::advance() {
    const auto now = std::chrono::steady_clock::now();
    const double dt = std::chrono::duration<double>(now - last_).count() * s_.timeScale;
    last_ = now;
    for (Motor& m : motors_) {
        if (!(m.mode & nxt::MotorOn) || m.power == 0 || m.runState == nxt::RunIdle) continue;
        const double speed = m.power / 100.0 * s_.fullPowerDegreesPerSecond;
        m.tacho += speed * dt;
        if (m.limit > 0 && std::abs(m.tacho - m.runStart) >= m.limit) {
            // The firmware stops at the limit, a little past it.
            const double dir = m.power > 0 ? 1.0 : -1.0;
            m.tacho = m.runStart + dir * (m.limit + std::abs(speed) * s_.brakeOvershoot_s);
            m.power = 0;
            m.runState = nxt::RunIdle;
        }
    }
}

void FakeNxtBrick::injectFault(Fault fault, std::uint8_t opcode, int skip, std::uint8_t status) {
    std::lock_guard lock(mutex_);
    faults_.push_back({fault, opcode, skip, status});
}

bool FakeNxtBrick::unplugged() const {
    std::lock_guard lock(mutex_);
    return unplugged_;
}

void FakeNxtBrick::replug() {
    std::lock_guard lock(mutex_);
    unplugged_ = false;
}

double FakeNxtBrick::rotationDegrees(std::uint8_t port) {
    std::lock_guard lock(mutex_);
    advance();
    return motors_.at(port).tacho - motors_.at(port).rotationStart;
}

bool FakeNxtBrick::motorRunning(std::uint8_t port) {
    std::lock_guard lock(mutex_);
    advance();
    const Motor& m = motors_.at(port);
    return (m.mode & nxt::MotorOn) && m.power != 0 && m.runState != nxt::RunIdle;
}

int FakeNxtBrick::power(std::uint8_t port) {
    std::lock_guard lock(mutex_);
    return motors_.at(port).power;
}

int FakeNxtBrick::requestsHandled() const {
    std::lock_guard lock(mutex_);
    return handled_;
}

nxt::Bytes FakeNxtBrick::outputStateReply(std::uint8_t port, std::uint8_t status) {
    const Motor& m = motors_[port];
    nxt::Bytes r{0x02,
                 nxt::GetOutputState,
                 status,
                 port,
                 static_cast<std::uint8_t>(m.power),
                 m.mode,
                 m.regulation,
                 static_cast<std::uint8_t>(m.turn),
                 m.runState};
    put32(r, m.limit);
    put32(r, static_cast<std::uint32_t>(static_cast<std::int32_t>(std::lround(m.tacho))));
    put32(r, static_cast<std::uint32_t>(
                 static_cast<std::int32_t>(std::lround(m.tacho - m.blockStart))));
    put32(r, static_cast<std::uint32_t>(
                 static_cast<std::int32_t>(std::lround(m.tacho - m.rotationStart))));
    return r;
}

std::optional<FakeNxtBrick::Armed> FakeNxtBrick::takeFault(std::uint8_t op) {
    for (auto it = faults_.begin(); it != faults_.end(); ++it) {
        if (it->opcode != 0 && it->opcode != op) continue;
        if (it->skip-- > 0) continue;
        const Armed fault = *it;
        faults_.erase(it);
        return fault;
    }
    return std::nullopt;
}

std::uint8_t FakeNxtBrick::setOutputState(const nxt::Bytes& q) {
    if (q.size() != 12) return 0xED;
    if (q[2] > 2 && q[2] != 0xFF) return 0xC0;
    std::uint32_t limit = 0;
    std::memcpy(&limit, q.data() + 8, 4);
    for (std::uint8_t p = 0; p < 3; ++p) {
        if (q[2] != 0xFF && q[2] != p) continue;
        Motor& m = motors_[p];
        const int newPower = static_cast<std::int8_t>(q[3]);
        if (newPower == 0 && (q[4] & nxt::Brake) && m.power != 0 && m.runState != nxt::RunIdle) {
            // Braking: the motor turns on for a moment.
            m.tacho += m.power / 100.0 * s_.fullPowerDegreesPerSecond * s_.brakeOvershoot_s;
        }
        m.power = newPower;
        m.mode = q[4];
        m.regulation = q[5];
        m.turn = static_cast<std::int8_t>(q[6]);
        m.runState = q[7];
        m.limit = limit;
        m.runStart = m.tacho;
    }
    return 0x00;
}

std::uint8_t FakeNxtBrick::command(const nxt::Bytes& q, nxt::Bytes& payload) {
    const std::uint8_t type = q[0], op = q[1];
    auto portOk = [&](std::size_t at, std::uint8_t max) { return q.size() > at && q[at] <= max; };
    switch (op) {
        case nxt::PlayTone:
            return q.size() != 6 ? 0xED : 0x00;
        case nxt::SetOutputState:
            return setOutputState(q);
        case nxt::SetInputMode:
            return portOk(2, 3) ? 0x00 : 0xC0;
        case nxt::GetInputValues:
            if (!portOk(2, 3)) return 0xC0;
            payload = {q[2], 1, 0, 0x01, 0x20, 0, 0, 0, 0, 0, 0, 0, 0};
            return 0x00;
        case nxt::ResetMotorPosition:
            if (!portOk(2, 2)) return 0xC0;
            if (q.size() > 3 && q[3])
                motors_[q[2]].blockStart = motors_[q[2]].tacho;
            else
                motors_[q[2]].rotationStart = motors_[q[2]].tacho;
            return 0x00;
        case nxt::GetBatteryLevel:
            payload = {static_cast<std::uint8_t>(s_.batteryMillivolts & 0xFF),
                       static_cast<std::uint8_t>(s_.batteryMillivolts >> 8)};
            return 0x00;
        case nxt::KeepAlive:
            put32(payload, s_.sleepMs);
            return 0x00;
        case nxt::GetDeviceInfo: {
            if (type != 0x01 && type != 0x81) return 0xBE;
            payload.assign(30, 0);
            std::memcpy(payload.data(), s_.name.data(), std::min<std::size_t>(s_.name.size(), 14));
            const std::uint8_t bt[6] = {0x00, 0x16, 0x53, 0x0A, 0x0B, 0x0C};
            std::memcpy(payload.data() + 15, bt, 6);
            const std::uint32_t flash = 53000;
            std::memcpy(payload.data() + 26, &flash, 4);
            return 0x00;
        }
        default:
            return 0xBE;
    }
}

std::optional<nxt::Bytes> FakeNxtBrick::handle(const nxt::Bytes& q) {
    std::lock_guard lock(mutex_);
    if (unplugged_) return std::nullopt;
    ++handled_;
    advance();
    if (q.size() < 2) return std::nullopt;  // the firmware ignores a runt telegram
    const std::uint8_t type = q[0], op = q[1];
    const bool reply = type == 0x00 || type == 0x01;
    const std::optional<Armed> fault = takeFault(op);
    if (fault && fault->fault == Fault::Unplug) {
        unplugged_ = true;
        return std::nullopt;
    }
    if (fault && fault->fault == Fault::NoReply) return std::nullopt;
    if (op == nxt::GetOutputState && q.size() > 2 && q[2] <= 2) {
        if (!reply) return std::nullopt;
        if (fault && fault->fault == Fault::Status) return nxt::Bytes{0x02, op, fault->status};
        nxt::Bytes r = outputStateReply(q[2], 0);
        if (fault && fault->fault == Fault::WrongOpcode) r[1] = nxt::GetInputValues;
        return r;
    }
    nxt::Bytes payload;
    std::uint8_t status = op == nxt::GetOutputState ? 0xC0 : command(q, payload);
    if (!reply) return std::nullopt;
    if (fault && fault->fault == Fault::Status) status = fault->status;
    nxt::Bytes r{0x02, op, status};
    if (status == 0) r.insert(r.end(), payload.begin(), payload.end());
    if (fault && fault->fault == Fault::WrongOpcode) r[1] = static_cast<std::uint8_t>(op ^ 0x01);
    return r;
}

void FakeNxtTransport::write(const nxt::Bytes& telegram) {
    if (brick_.unplugged())
        throw nxt::TransportError(nxt::TransportError::Kind::Unplugged,
                                  "NXT: the emulated brick is unplugged");
    if (auto r = brick_.handle(telegram)) replies_.push_back(*r);
    if (brick_.unplugged())
        throw nxt::TransportError(nxt::TransportError::Kind::Unplugged,
                                  "NXT: the emulated brick was unplugged");
}

nxt::Bytes FakeNxtTransport::read(int timeoutMs) {
    if (!replies_.empty()) {
        nxt::Bytes r = replies_.front();
        replies_.pop_front();
        return r;
    }
    if (brick_.unplugged())
        throw nxt::TransportError(nxt::TransportError::Kind::Unplugged,
                                  "NXT: the emulated brick is unplugged");
    std::this_thread::sleep_for(std::chrono::milliseconds(timeoutMs));
    throw nxt::TransportError(nxt::TransportError::Kind::Timeout,
                              "NXT: no reply within " + std::to_string(timeoutMs) + " ms");
}

}  // namespace activetouch::emu
