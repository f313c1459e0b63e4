#pragma once
// A rig for testing the perception-action loop apart from the physics: its tapper produces a tap
// that a small classifier reads as exactly the class an oracle names for the current pose. The
// default oracle is ideal perception of a true outline: the nearest edge's orientation and the
// tip's position across it, plane and air beyond the window.
#include <cmath>
#include <functional>
#include <stdexcept>

#include "core/classify/HistogramClassifier.h"
#include "core/control/ContourFollower.h"

namespace activetouch::test {

/// One tap per class that only that class explains: taxel 0 reads the class index.
inline Tap tapForClass(int cls) {
    Tap t(kSamplesPerTap, kFingertipTaxels);
    for (int s = 0; s < t.sampleCount(); ++s) t.at(s, 0) = static_cast<double>(cls);
    return t;
}

struct OracleWorld {
    ClassSet classes;
    HistogramClassifier classifier;
    std::function<int(Vec2)> oracle;  ///< pose -> class
    Vec2 pose;
    double clock = 0.0;
    int moves = 0;
    int failAfterMoves = -1;  ///< the stage fails on this move (-1: never)

    explicit OracleWorld(const ClassSet& cs) : classes(cs) {
        std::vector<Tap> taps;
        for (int c = 0; c < cs.classCount(); ++c) taps.push_back(tapForClass(c));
        std::vector<LabelledTap> labelled;
        for (int c = 0; c < cs.classCount(); ++c)
            labelled.push_back({&taps[static_cast<std::size_t>(c)], c});
        classifier = HistogramClassifier::train(labelled, cs.classCount(), {cs.classCount(), 0.01});
    }

    /// Ideal perception of `outline`: the nearest edge's orientation (among the trained ones) and
    /// the position class of the signed distance; the class region decides plane/edge/air.
    void perceiveIdeally(const Polygon& outline) {
        oracle = [this, outline](Vec2 p) {
            const auto nearest = outline.nearestOutlinePoint(p);
            const Vec2 n = outline.outwardNormal(nearest.edge);
            double best = -2;
            int o = 0;
            for (std::size_t i = 0; i < classes.orientationsDeg.size(); ++i) {
                const double d = dot(n, directionFromDegrees(classes.orientationsDeg[i]));
                if (d > best) {
                    best = d;
                    o = static_cast<int>(i);
                }
            }
            const double offset = outline.contains(p) ? -nearest.distance : nearest.distance;
            const int position =
                std::clamp(static_cast<int>(std::lround(classes.positionAtOffset(offset))), 1,
                           classes.positions);
            return classes.classOf(o, position);
        };
    }
};

class OracleStage final : public Stage {
public:
    explicit OracleStage(OracleWorld& w) : w_(w) {}
    void moveTo(Vec2 target) override {
        if (w_.failAfterMoves >= 0 && w_.moves >= w_.failAfterMoves)
            throw RigError("oracle stage: the serial port vanished");
        ++w_.moves;
        w_.clock += distance(w_.pose, target) / 50.0;
        w_.pose = target;
    }
    Vec2 position() const override { return w_.pose; }

private:
    OracleWorld& w_;
};

class OracleTapper final : public Tapper {
public:
    explicit OracleTapper(OracleWorld& w) : w_(w) {}
    TapRecord tap() override {
        TapRecord r;
        r.tap = tapForClass(w_.oracle(w_.pose));
        r.pose = w_.pose;
        r.startTime_s = w_.clock;
        r.cycleTime_s = 2.5;
        r.ending = TapEnding::ContactReflex;
        w_.clock += 2.5;
        return r;
    }

private:
    OracleWorld& w_;
};

class OracleSensor final : public TactileSensor {
public:
    int taxelCount() const override { return kFingertipTaxels; }
    void latestFrame(double* out) const override { std::fill(out, out + kFingertipTaxels, 0.0); }
};

class OracleClock final : public RobotClock {
public:
    explicit OracleClock(const OracleWorld& w) : w_(w) {}
    double now_s() const override { return w_.clock; }

private:
    const OracleWorld& w_;
};

struct OracleRig {
    OracleWorld world;
    OracleStage stage{world};
    OracleTapper tapper{world};
    OracleSensor sensor;
    OracleClock clock{world};
    explicit OracleRig(const ClassSet& cs) : world(cs) {}
    Rig rig() { return Rig{stage, tapper, sensor, clock}; }
};

/// The paper's classes (or `orientations`) with a simple region map: positions 1-4 plane, 15-18
/// air.
inline ClassSet paperClassesWithRegions(std::vector<double> orientations = {270, 0, 90, 180}) {
    ClassSet cs;
    cs.orientationsDeg = std::move(orientations);
    cs.regions.assign(static_cast<std::size_t>(cs.classCount()), Region::Edge);
    for (int o = 0; o < static_cast<int>(cs.orientationsDeg.size()); ++o)
        for (int p = 1; p <= 18; ++p)
            cs.regions[static_cast<std::size_t>(cs.classOf(o, p))] =
                p <= 4 ? Region::Plane : (p >= 15 ? Region::Air : Region::Edge);
    return cs;
}

}  // namespace activetouch::test
