#include "devices/simulated/SimulatedWorld.h"

#include <algorithm>
#include <cmath>

#include "core/common/NumberText.h"

namespace activetouch {
namespace {

const EffectDescription& describedEffect(const SceneSpec& scene, const EffectSpec& spec) {
    const EffectDescription* d = findEffect(spec.name);
    if (!d) {
        std::string known;
        for (const auto& e : effectCatalogue()) known += (known.empty() ? "" : ", ") + e.name;
        throw InputError(scene.source, spec.place + "/name",
                         "unknown effect '" + spec.name + "'; the simulated rig knows: " + known);
    }
    return *d;
}

// The effect's parameters, every key known.
JsonFields effectFields(const SceneSpec& scene, const EffectSpec& spec,
                        const EffectDescription& d) {
    JsonFields f(spec.parameters, scene.source, spec.place);
    std::vector<std::string> keys;
    for (const auto& p : d.parameters) keys.push_back(p.key);
    if (d.takesTaxelList) keys.push_back("taxels");
    if (d.takesGainList) keys.push_back("gains");
    keys.push_back("name");
    f.rejectUnknownKeys(keys);
    return f;
}

std::unique_ptr<Effect> buildEffect(const SceneSpec& scene, const EffectSpec& spec,
                                    const FingertipContactModel& model) {
    const EffectDescription& d = describedEffect(scene, spec);
    return d.make(effectFields(scene, spec, d), model,
                  RandomStream::derived(scene.seed, "effect:" + spec.name));
}

}  // namespace

void validateEffects(const SceneSpec& scene) {
    // Everything an effect reads from a scene, checked without building the contact model: the
    // only thing of the fingertip an effect's parameters depend on is its number of taxels.
    const int taxels = static_cast<int>(scene.fingertip.taxels.size());
    for (const auto& spec : scene.effects) {
        const EffectDescription& d = describedEffect(scene, spec);
        const JsonFields f = effectFields(scene, spec, d);
        if (d.takesGainList && f.has("gains")) {
            effectGainList(f, taxels);
            continue;
        }
        for (const auto& p : d.parameters) f.number(p.key, p.lo, p.hi);
        if (d.takesTaxelList) effectTaxelList(f, taxels);
    }
}

SimulatedWorld::SimulatedWorld(const SceneSpec& scene,
                               std::shared_ptr<const FingertipContactModel> model)
    : scene_(scene), object_(scene.object.outline()), model_(std::move(model)) {
    for (const auto& spec : scene_.effects) {
        auto effect = buildEffect(scene_, spec, *model_);
        switch (effect->acts()) {
            case Effect::Acts::Pose:
                poseEffects_.push_back(std::move(effect));
                break;
            case Effect::Acts::Mechanics:
                mechanicsEffects_.push_back(std::move(effect));
                break;
            case Effect::Acts::Signal:
                signalEffects_.push_back(std::move(effect));
                break;
        }
    }
    std::stable_sort(
        signalEffects_.begin(), signalEffects_.end(),
        [](const auto& a, const auto& b) { return a->signalOrder() < b->signalOrder(); });
    lastFrame_.assign(static_cast<std::size_t>(model_->taxelCount()), 0.0);
}

std::vector<std::string> SimulatedWorld::activeEffects() const {
    std::vector<std::string> names;
    for (const auto* list : {&poseEffects_, &mechanicsEffects_, &signalEffects_})
        for (const auto& e : *list) names.push_back(e->name());
    return names;
}

void SimulatedWorld::moveStage(Vec2 target) {
    clock_s_ += distance(commanded_, target) / scene_.stage.speed_mm_s;
    commanded_ = target;
    actual_ = target;
    for (auto& e : poseEffects_) actual_ = e->perturbPose(actual_);
}

void SimulatedWorld::placeFingertip(Vec2 reported) {
    commanded_ = reported;
    actual_ = reported;
    for (auto& e : poseEffects_) actual_ = e->perturbPose(actual_);
}

void SimulatedWorld::latestFrame(double* out) const {
    std::copy(lastFrame_.begin(), lastFrame_.end(), out);
}

TapRecord SimulatedWorld::tap() {
    const TapSpec& ts = scene_.tap;
    const int K = model_->taxelCount();
    const double v = ts.descentSpeed_mm_s;
    const double clearance = ts.retractHeight_mm - scene_.object.height_mm;
    const double strokeDepth = scene_.strokeLimitDepth();

    double latency = 0.0;
    for (const auto& e : mechanicsEffects_) latency += e->reflexLatency_s();

    // The reflex: the stroke stops once the total pressure crosses the threshold (plus latency),
    // or at the stroke limit, whichever comes first.
    auto contact = model_->contactAt(object_, actual_);
    TapRecord record;
    record.pose = commanded_;
    record.startTime_s = clock_s_;
    double stopDepth = strokeDepth;
    record.ending = TapEnding::StrokeLimit;
    if (auto crossing = contact.depthReaching(ts.contactThreshold, strokeDepth)) {
        stopDepth = std::min(*crossing + v * latency, strokeDepth);
        record.ending = TapEnding::ContactReflex;
    }
    if (forcedStop_mm_) {
        stopDepth = std::clamp(*forcedStop_mm_, 0.0, strokeDepth);
        forcedStop_mm_.reset();
    }
    record.stopDepth_mm = stopDepth;
    const double stopTime = (clearance + stopDepth) / v;
    const double release = stopTime + ts.contactTime_s;

    // The depth of every sample; the pressures at the distinct depths come from one ascending
    // sweep over the contact patch.
    record.tap = Tap(ts.samples, K);
    const double period = 1.0 / ts.sampleRate_hz;
    sampleDepths_.resize(static_cast<std::size_t>(ts.samples));
    distinctDepths_.clear();
    for (int i = 0; i < ts.samples; ++i) {
        const double t = i * period;
        double depth;
        if (t < stopTime)
            depth = v * t - clearance;
        else if (t <= release)
            depth = stopDepth;
        else
            depth = stopDepth - v * (t - release);
        sampleDepths_[static_cast<std::size_t>(i)] = depth;
        if (depth > 0.0) distinctDepths_.push_back(depth);
    }
    distinctDepths_.push_back(stopDepth);
    std::sort(distinctDepths_.begin(), distinctDepths_.end());
    distinctDepths_.erase(std::unique(distinctDepths_.begin(), distinctDepths_.end()),
                          distinctDepths_.end());
    depthPressures_.resize(distinctDepths_.size() * static_cast<std::size_t>(K));
    contact.taxelPressuresAtDepths(distinctDepths_.data(), distinctDepths_.size(),
                                   depthPressures_.data());
    auto pressuresAt = [&](double depth) {
        const auto at = std::lower_bound(distinctDepths_.begin(), distinctDepths_.end(), depth) -
                        distinctDepths_.begin();
        return depthPressures_.data() + static_cast<std::size_t>(at) * static_cast<std::size_t>(K);
    };
    const double* holdPressures = pressuresAt(stopDepth);
    std::vector<double> hold(holdPressures, holdPressures + K);
    for (int i = 0; i < ts.samples; ++i) {
        const double depth = sampleDepths_[static_cast<std::size_t>(i)];
        if (depth <= 0.0) continue;
        const double* p = pressuresAt(depth);
        std::copy(p, p + K, record.tap.samples.data() + static_cast<std::size_t>(i * K));
    }

    SignalContext context{clock_s_, period, release, hold.data()};
    for (auto& e : signalEffects_) e->shapeSignal(record.tap, context);

    record.cycleTime_s = ts.window_s() + ts.settle_s;
    clock_s_ += record.cycleTime_s;
    std::copy(record.tap.frame(ts.samples - 1), record.tap.frame(ts.samples - 1) + K,
              lastFrame_.begin());
    ++taps_;
    return record;
}

void SimulatedStage::moveTo(Vec2 target) {
    const Vec2 travel = world_.scene().stage.travel_mm;
    if (!(target.x >= 0 && target.y >= 0 && target.x <= travel.x && target.y <= travel.y))
        throw RigError("simulated stage: target (" + numberText(target.x) + ", " +
                       numberText(target.y) + ") mm is outside the travel (0.." +
                       numberText(travel.x) + ", 0.." + numberText(travel.y) + " mm)");
    world_.moveStage(target);
}

namespace {

class SimulatedRigFactory final : public SimulatedRigs {
public:
    void checkEffects(const SceneSpec& scene) const override { validateEffects(scene); }
    std::unique_ptr<SceneRig> build(
        const SceneSpec& scene, std::shared_ptr<const FingertipContactModel> model) const override {
        return std::make_unique<SimulatedRig>(scene, std::move(model));
    }
};

}  // namespace

const SimulatedRigs& simulatedRigs() {
    static const SimulatedRigFactory factory;
    return factory;
}

}  // namespace activetouch
