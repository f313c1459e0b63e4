#include "devices/emulators/EmulatedBench.h"

#include <algorithm>
#include <cmath>

namespace activetouch::emu {
namespace {

FakeNxtSettings brickSettings(const BenchSettings& s) {
    FakeNxtSettings b;
    b.timeScale = s.timeScale;
    return b;
}

FakeRcxSettings rcxSettings(const SceneSpec& scene, const BenchSettings& s) {
    FakeRcxSettings r;
    r.dialect = s.dialect;
    r.timeScale = s.timeScale;
    r.travel = scene.stage.travel_mm;
    return r;
}

FakeYarpSettings yarpSettings(const BenchSettings& s) {
    FakeYarpSettings y = s.yarp;
    y.rate_hz = 50.0 * s.timeScale;
    return y;
}

}  // namespace

EmulatedBench::EmulatedBench(const SceneSpec& scene,
                             std::shared_ptr<const FingertipContactModel> model,
                             BenchSettings settings)
    : scene_(scene),
      object_(scene.object.outline()),
      model_(std::move(model)),
      s_(settings),
      brick_(brickSettings(settings)),
      rcx_(rcxSettings(scene, settings)),
      yarp_(yarpSettings(settings), [this] { return fingertip(); }),
      noise_(RandomStream::derived(scene.seed, "bench:taxel_noise")),
      stageRandom_(RandomStream::derived(scene.seed, "bench:stage_error")) {
    for (const EffectSpec& e : scene.effects) {
        if (e.name == "taxel_noise") noiseSigma_ = e.parameters.at("sigma_counts").get<double>();
        if (e.name == "adc_quantisation") adcMax_ = e.parameters.at("max_counts").get<double>();
        if (e.name == "stage_error") stageSigma_ = e.parameters.at("sigma_mm").get<double>();
    }
}

std::vector<std::string> EmulatedBench::effects() const {
    std::vector<std::string> names;
    if (noiseSigma_ > 0.0) names.push_back("taxel_noise");
    if (adcMax_) names.push_back("adc_quantisation");
    if (stageSigma_ > 0.0) names.push_back("stage_error");
    return names;
}

EmulatedBench::~EmulatedBench() {
    yarp_.stop();
    rcx_.stop();
}

void EmulatedBench::start() {
    rcx_.start();
    yarp_.start();
}

std::vector<double> EmulatedBench::fingertip() {
    std::vector<double> out(static_cast<std::size_t>(model_->taxelCount()), 0.0);
    const double clearance = scene_.tap.retractHeight_mm - scene_.object.height_mm;
    const double depth = brick_.rotationDegrees(0) / s_.degreesPerMm - clearance;
    std::lock_guard lock(frameMutex_);
    if (depth <= 0.0 && deepest_ > 0.0) {  // a press has ended
        pressDepths_.push_back(deepest_);
        deepest_ = 0.0;
    }
    if (depth > 0.0) {
        deepest_ = std::max(deepest_, depth);
        // Each place the stage comes to, it misses by its own error (drawn when it arrives).
        const Vec2 reported = rcx_.position();
        if (!target_ || distance(reported, *target_) > 1e-9) {
            target_ = reported;
            miss_ = stageSigma_ > 0.0 ? Vec2{stageSigma_ * stageRandom_.normal(),
                                             stageSigma_ * stageRandom_.normal()}
                                      : Vec2{};
        }
        const Vec2 pose = reported + miss_;
        if (!contact_ || distance(pose, contactPose_) > 1e-6) {
            contact_.emplace(model_->contactAt(object_, pose));
            contactPose_ = pose;
        }
        contact_->taxelPressures(depth, out.data());
    }
    // The frame effects, in the simulated rig's order: noise, then the converter.
    if (noiseSigma_ > 0.0)
        for (double& v : out) v = std::max(0.0, v + noiseSigma_ * noise_.normal());
    if (adcMax_)
        for (double& v : out) v = std::clamp(std::round(v), 0.0, *adcMax_);
    return out;
}

std::vector<double> EmulatedBench::pressDepths() {
    std::lock_guard lock(frameMutex_);
    return pressDepths_;
}

nxt::NxtTapperSettings EmulatedBench::tapperSettings() const {
    nxt::NxtTapperSettings t;
    t.degreesPerMm = s_.degreesPerMm;
    t.timeScale = s_.timeScale;
    return t;
}

rcx::YamahaStageSettings EmulatedBench::stageSettings() const {
    rcx::YamahaStageSettings st;
    st.serial.portName = rcx_.portName();
    st.dialect = s_.dialect;
    st.timeScale = s_.timeScale;
    st.softMax = scene_.stage.travel_mm;
    st.speedPercent =
        std::clamp(static_cast<int>(scene_.stage.speed_mm_s / st.fullSpeed_mm_s * 100.0), 1, 100);
    return st;
}

yarp::YarpFingertipSettings EmulatedBench::fingertipSettings() const {
    yarp::YarpFingertipSettings y;
    y.nameServerHost = "127.0.0.1";
    y.nameServerPort = yarp_.nameServerPort();
    y.port = s_.yarp.portName;
    y.finger = static_cast<yarp::Finger>(s_.yarp.fingerOffset);
    return y;
}

}  // namespace activetouch::emu
