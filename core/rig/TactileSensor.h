#pragma once
// The fingertip's taxel stream (iCub skin, compensated, 0 = no contact) or its simulation.
#include <cstdint>

namespace activetouch {

class TactileSensor {
public:
    virtual ~TactileSensor() = default;

    /// Number of taxels in a frame (12 for an iCub fingertip).
    virtual int taxelCount() const = 0;

    /// Copies the most recent frame (counts, taxelCount values) into `out`. Never blocks.
    virtual void latestFrame(double* out) const = 0;

    /// For streams: waits at most `timeoutMs` for a frame newer than the one numbered `after`
    /// (0: any frame), copies it into `out` and returns its number; 0 if none came in time.
    /// Throws RigError if the stream has failed. A sensor without a stream returns its latest
    /// frame at once.
    virtual std::uint64_t waitFrame(std::uint64_t after, int timeoutMs, double* out) {
        (void)timeoutMs;
        latestFrame(out);
        return after + 1;
    }
};

}  // namespace activetouch
