#pragma once
// The LEGO NXT tapper (docs/protocols.md §1): motor A lowers the fingertip at a regulated speed
// with the stroke as tacho limit; the fingertip's total pressure crossing the contact threshold is
// the reflex that brakes it; after the contact time the motor returns to the retract angle (tacho
// 0, set when the tapper connects). The tap records the fingertip stream's frames from the start of
// the stroke. On any fault the motor is braked and, if the brick still answers, sent back.
#include <atomic>
#include <chrono>
#include <functional>
#include <mutex>
#include <optional>
#include <string>

#include "core/rig/Rig.h"
#include "core/scene/Scene.h"
#include "devices/nxt/NxtBrick.h"

namespace activetouch::nxt {

struct NxtTapperSettings {
    std::uint8_t motorPort = 0;  ///< 0, 1, 2 = A, B, C
    /// Motor degrees per mm of fingertip travel: the tapper's gearing (unverified: measure it on
    /// the rig and set it).
    double degreesPerMm = 20.0;
    /// Motor speed at power 100 under speed regulation, degrees per second (unverified).
    double fullPowerDegreesPerSecond = 900.0;
    int returnPower = 60;
    int pollPeriodMs = 10;        ///< GETOUTPUTSTATE while the motor moves
    int retractToleranceDeg = 8;  ///< how close to the retract angle counts as retracted
    int frameTimeoutMs = 500;     ///< a fingertip stream quiet this long has stalled
    double timeScale = 1.0;       ///< robot seconds per wall second (emulated benches)
};

class NxtTapper final : public Tapper {
public:
    /// `clock` times the taps. The brick, sensor and clock must outlive the tapper.
    NxtTapper(NxtBrick& brick, TactileSensor& sensor, const RobotClock& clock, const TapSpec& tap,
              NxtTapperSettings settings = {});

    /// Keep-alive, motor position reset (the current angle becomes the retract angle), battery.
    /// Returns the battery voltage, mV. Throws RigError.
    std::uint16_t connect();

    TapRecord tap() override;

    /// Brakes the motor and, if the brick answers, returns it to the retract angle within about a
    /// second. Never throws; says what it managed.
    std::string safeStop() noexcept;

    void setContactThreshold(double counts) { tap_.contactThreshold = counts; }
    /// The object's top lies `clearance_mm` below the retract angle (the retract height less the
    /// object's height): each tap's stop depth is then read below the top, as the simulated rig
    /// gives it. Without it, from the frame where contact began (a tenth of the threshold).
    void setSurface(double clearance_mm) { clearance_mm_ = clearance_mm; }
    const TapSpec& tapSpec() const { return tap_; }
    /// Motor state for panels ("retracted", "descending", ...); read from any thread.
    std::string state() const;
    /// Stops a tap in progress at the next frame (the tap then throws RigError) and refuses every
    /// later one: for closing, from any thread.
    void abort() { abort_ = true; }
    /// abort(), then waits at most `bound` for a tap in progress to leave tap() (it stops at its
    /// next frame and brakes and returns the motor). True once no tap is running: the tapper and
    /// what it uses may then be destroyed.
    bool abortAndWait(std::chrono::milliseconds bound);

private:
    enum class Phase { Retracted, Descending, Holding, Returning };
    void brake(bool withReply);
    std::chrono::milliseconds pollPeriod() const;
    void setPhase(Phase p) { phase_ = p; }
    struct Stroke;  ///< one tap's progress (NxtTapper.cpp)
    /// tap()'s steps: the brick kept awake, the next frame read into the tap (and the reflex
    /// checked), the motor polled, the descent stopped, the hold and return moved on.
    void keepAwake();
    void readFrame(Stroke& s, TapRecord& record, std::vector<double>& frame);
    void pollMotor(Stroke& s, TapRecord& record);
    void stopDescent(Stroke& s, TapRecord& record, TapEnding ending);
    void holdAndReturn(Stroke& s);
    NxtBrick& brick_;
    TactileSensor& sensor_;
    const RobotClock& clock_;
    TapSpec tap_;
    NxtTapperSettings s_;
    std::atomic<Phase> phase_{Phase::Retracted};
    std::atomic<bool> abort_{false};
    std::timed_mutex inTap_;  ///< held while a tap runs
    std::optional<double> clearance_mm_;
    double lastKeepAlive_s_ = 0.0;
    std::uint32_t sleepMs_ = 0;
};

}  // namespace activetouch::nxt
