#pragma once
// The fingertip's taxel stream (iCub skin, compensated, 0 = no contact) or its simulation.
namespace activetouch {

class TactileSensor {
public:
    virtual ~TactileSensor() = default;

    /// Number of taxels in a frame (12 for an iCub fingertip).
    virtual int taxelCount() const = 0;

    /// Copies the most recent frame (counts, taxelCount values) into `out`. Never blocks.
    virtual void latestFrame(double* out) const = 0;
};

}  // namespace activetouch
