#include "devices/nxt/NxtTapper.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <thread>
#include <vector>

namespace activetouch::nxt {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
}

}  // namespace

NxtTapper::NxtTapper(NxtBrick& brick, TactileSensor& sensor, const RobotClock& clock,
                     const TapSpec& tap, NxtTapperSettings settings)
    : brick_(brick), sensor_(sensor), clock_(clock), tap_(tap), s_(settings) {
    if (!(s_.degreesPerMm > 0) || !(s_.fullPowerDegreesPerSecond > 0) || !(s_.timeScale > 0) ||
        s_.returnPower < 1 || s_.returnPower > 100 || s_.motorPort > 2)
        throw RigError(
            "NXT tapper: settings out of range (degrees per mm and full-power speed must be "
            "positive, return power 1..100, motor port A, B or C)");
}

std::chrono::milliseconds NxtTapper::pollPeriod() const {
    return std::chrono::milliseconds(
        std::max(1, static_cast<int>(std::lround(s_.pollPeriodMs / s_.timeScale))));
}

std::string NxtTapper::state() const {
    switch (phase_.load()) {
        case Phase::Retracted:
            return "retracted";
        case Phase::Descending:
            return "descending";
        case Phase::Holding:
            return "holding on contact";
        case Phase::Returning:
            return "returning";
    }
    return "?";
}

std::uint16_t NxtTapper::connect() {
    sleepMs_ = brick_.keepAlive();
    lastKeepAlive_s_ = clock_.now_s();
    brake(true);
    brick_.call(resetMotorPosition(s_.motorPort, false, true));
    brick_.call(resetMotorPosition(s_.motorPort, true, true));
    setPhase(Phase::Retracted);
    return brick_.batteryMillivolts();
}

void NxtTapper::brake(bool withReply) {
    brick_.call(setOutputState(s_.motorPort, 0, MotorOn | Brake | Regulated, RegulationSpeed, 0,
                               RunRunning, 0, withReply));
}

std::string NxtTapper::safeStop() noexcept {
    try {
        brake(false);
    } catch (const std::exception& e) {
        setPhase(Phase::Retracted);
        return std::string("the motor could not be braked (") + e.what() +
               "); it stops at its tacho limit";
    }
    try {
        const auto started = Clock::now();
        int tacho = brick_.outputState(s_.motorPort).rotationCount;
        if (tacho > s_.retractToleranceDeg) {
            setPhase(Phase::Returning);
            brick_.call(setOutputState(s_.motorPort, -s_.returnPower, MotorOn | Brake | Regulated,
                                       RegulationSpeed, 0, RunRunning,
                                       static_cast<std::uint32_t>(tacho), true));
            while (tacho > s_.retractToleranceDeg && secondsSince(started) < 1.0) {
                std::this_thread::sleep_for(pollPeriod());
                tacho = brick_.outputState(s_.motorPort).rotationCount;
            }
            brake(true);
        }
        setPhase(Phase::Retracted);
        return tacho > s_.retractToleranceDeg
                   ? "the motor was braked " + std::to_string(tacho) +
                         " degrees short of the retract angle"
                   : "the motor was braked and returned to the retract angle";
    } catch (const std::exception&) {
        setPhase(Phase::Retracted);
        return "the motor was braked (the brick did not answer the return)";
    }
}

bool NxtTapper::abortAndWait(std::chrono::milliseconds bound) {
    abort();
    const std::unique_lock idle(inTap_, bound);
    return idle.owns_lock();
}

struct NxtTapper::Stroke {
    std::uint32_t limitDeg = 0;
    double hold_s = 0.0;
    std::uint64_t seq = 0;  ///< the last frame read
    int samples = 0, tacho = 0, stopTacho = 0;
    std::optional<int> contactTacho;
    Clock::time_point holdUntil{}, lastPoll = Clock::now();
};

void NxtTapper::keepAwake() {
    if (sleepMs_ > 0 &&
        (clock_.now_s() - lastKeepAlive_s_) * 1000.0 / s_.timeScale > sleepMs_ / 2.0) {
        sleepMs_ = brick_.keepAlive();
        lastKeepAlive_s_ = clock_.now_s();
    }
}

void NxtTapper::stopDescent(Stroke& s, TapRecord& record, TapEnding ending) {
    if (ending == TapEnding::ContactReflex) brake(true);
    s.tacho = brick_.outputState(s_.motorPort).rotationCount;
    s.lastPoll = Clock::now();
    s.stopTacho = s.tacho;
    record.ending = ending;
    s.holdUntil = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                     std::chrono::duration<double>(s.hold_s));
    setPhase(Phase::Holding);
}

void NxtTapper::readFrame(Stroke& s, TapRecord& record, std::vector<double>& frame) {
    const std::uint64_t next = sensor_.waitFrame(s.seq, s_.frameTimeoutMs, frame.data());
    if (next == 0)
        throw RigError("fingertip: no frame for " + std::to_string(s_.frameTimeoutMs) +
                       " ms during a tap; the stream has stalled");
    s.seq = next;
    const auto K = static_cast<std::ptrdiff_t>(frame.size());
    std::copy(frame.begin(), frame.end(), record.tap.samples.begin() + s.samples * K);
    ++s.samples;
    double total = 0.0;
    for (double v : frame) total += v;
    if (phase_ != Phase::Descending) return;
    // Contact onset, for the stop depth: a tenth of the threshold is well above what the skin's
    // noise sums to over the untouched taxels.
    if (!s.contactTacho && total >= 0.1 * tap_.contactThreshold) {
        s.tacho = brick_.outputState(s_.motorPort).rotationCount;
        s.lastPoll = Clock::now();
        s.contactTacho = s.tacho;
    }
    if (total >= tap_.contactThreshold) stopDescent(s, record, TapEnding::ContactReflex);
}

void NxtTapper::pollMotor(Stroke& s, TapRecord& record) {
    if (Clock::now() - s.lastPoll < pollPeriod()) return;
    const OutputState st = brick_.outputState(s_.motorPort);
    s.tacho = st.rotationCount;
    s.lastPoll = Clock::now();
    if (phase_ == Phase::Descending &&
        (st.runState == RunIdle || s.tacho >= static_cast<int>(s.limitDeg) - 1))
        stopDescent(s, record, TapEnding::StrokeLimit);
}

void NxtTapper::holdAndReturn(Stroke& s) {
    if (phase_ == Phase::Holding && Clock::now() >= s.holdUntil) {
        if (s.tacho > s_.retractToleranceDeg)
            brick_.call(setOutputState(s_.motorPort, -s_.returnPower, MotorOn | Brake | Regulated,
                                       RegulationSpeed, 0, RunRunning,
                                       static_cast<std::uint32_t>(s.tacho), true));
        setPhase(Phase::Returning);
    }
    if (phase_ == Phase::Returning && s.tacho <= s_.retractToleranceDeg) {
        brake(true);
        setPhase(Phase::Retracted);
    }
}

TapRecord NxtTapper::tap() {
    const std::lock_guard running(inTap_);
    if (abort_) throw RigError("NXT tapper: stopped (the application is closing); no further taps");
    const int K = sensor_.taxelCount();
    const int T = tap_.samples;
    TapRecord record;
    record.startTime_s = clock_.now_s();
    record.tap = Tap(T, K);
    record.ending = TapEnding::StrokeLimit;
    std::vector<double> frame(static_cast<std::size_t>(K));
    Stroke s;
    s.limitDeg = static_cast<std::uint32_t>(std::lround(tap_.stroke_mm * s_.degreesPerMm));
    s.hold_s = tap_.contactTime_s / s_.timeScale;
    const int power =
        std::clamp(static_cast<int>(std::lround(tap_.descentSpeed_mm_s * s_.degreesPerMm /
                                                s_.fullPowerDegreesPerSecond * 100.0)),
                   1, 100);
    // Worst case: a full stroke down and back at the commanded speeds, the hold and the window,
    // three times over and two seconds to spare. Nothing waits longer.
    const double deadline_s =
        3.0 *
            (2.0 * tap_.stroke_mm / tap_.descentSpeed_mm_s + tap_.contactTime_s + tap_.window_s()) /
            s_.timeScale +
        2.0;
    try {
        keepAwake();
        s.seq = sensor_.waitFrame(0, s_.frameTimeoutMs, frame.data());
        if (s.seq == 0)
            throw RigError("fingertip: no frame for " + std::to_string(s_.frameTimeoutMs) +
                           " ms before the tap; the stream has stalled (the tapper did not move)");
        const auto started = Clock::now();
        brick_.call(setOutputState(s_.motorPort, power, MotorOn | Brake | Regulated,
                                   RegulationSpeed, 0, RunRunning, s.limitDeg, true));
        setPhase(Phase::Descending);
        s.lastPoll = Clock::now();
        while (s.samples < T || phase_ != Phase::Retracted) {
            if (abort_) throw RigError("NXT tapper: the tap was stopped");
            if (secondsSince(started) > deadline_s)
                throw RigError("NXT tapper: the tap did not finish within " +
                               std::to_string(deadline_s) + " s");
            if (s.samples < T)
                readFrame(s, record, frame);
            else
                std::this_thread::sleep_for(pollPeriod());
            if (phase_ == Phase::Retracted) continue;
            pollMotor(s, record);
            holdAndReturn(s);
        }
        if (clearance_mm_)
            record.stopDepth_mm = std::max(0.0, s.stopTacho / s_.degreesPerMm - *clearance_mm_);
        else
            record.stopDepth_mm =
                s.contactTacho ? std::max(0, s.stopTacho - *s.contactTacho) / s_.degreesPerMm : 0.0;
    } catch (const RigError& e) {
        const std::string after = safeStop();
        throw RigError(std::string(e.what()) + "; " + after);
    }
    record.cycleTime_s = clock_.now_s() - record.startTime_s;
    return record;
}

}  // namespace activetouch::nxt
