#include "devices/emulators/EmulatedBench.h"

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
      yarp_(yarpSettings(settings), [this] { return fingertip(); }) {}

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
    if (depth <= 0.0) return out;
    const Vec2 pose = rcx_.position();
    if (!contact_ || distance(pose, contactPose_) > 1e-6) {
        contact_.emplace(model_->contactAt(object_, pose));
        contactPose_ = pose;
    }
    contact_->taxelPressures(depth, out.data());
    return out;
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
    y.nameServerPort = yarp_.nameServerPort();
    y.port = s_.yarp.portName;
    y.finger = static_cast<yarp::Finger>(s_.yarp.fingerOffset);
    y.binaryCarrier = false;
    return y;
}

}  // namespace activetouch::emu
