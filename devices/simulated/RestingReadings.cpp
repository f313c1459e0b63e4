#include "devices/simulated/RestingReadings.h"

#include <memory>

#include "devices/simulated/SimulatedWorld.h"

namespace activetouch {

RestingReadings restingReadings(const SceneSpec& scene, int taps) {
    auto model = std::make_shared<const FingertipContactModel>(scene.fingertip);
    SimulatedWorld world(scene, model);
    const Polygon& object = world.object();
    // Beside the object, where the stage can go: 30 mm past the side with the most room.
    const Vec2 lo = object.boundingBoxMin(), hi = object.boundingBoxMax();
    const double clear = 30.0;
    Vec2 at{lo.x - clear, 0.5 * (lo.y + hi.y)};
    if (at.x < 0.0) at = {hi.x + clear, at.y};
    world.moveStage(at);
    const int k = model->taxelCount();
    RestingReadings out;
    out.taxels.resize(static_cast<std::size_t>(k));
    for (int i = 0; i < taps; ++i) {
        const TapRecord r = world.tap();
        out.samplesPerTap = r.tap.sampleCount();
        for (int t = 0; t < r.tap.sampleCount(); ++t)
            for (int j = 0; j < k; ++j) out.taxels[std::size_t(j)].push_back(r.tap.at(t, j));
    }
    return out;
}

std::vector<std::vector<double>> edgeReadings(const SceneSpec& scene, int rounds) {
    auto model = std::make_shared<const FingertipContactModel>(scene.fingertip);
    SimulatedWorld world(scene, model);
    const Polygon& object = world.object();
    // The edge whose outward normal points most nearly down, at its middle.
    std::size_t lowest = 0;
    for (std::size_t e = 0; e < object.size(); ++e)
        if (object.outwardNormal(e).y < object.outwardNormal(lowest).y) lowest = e;
    const Vec2 middle = 0.5 * (object.vertex(lowest) + object.vertex(lowest + 1));
    const Vec2 normal = object.outwardNormal(lowest);
    std::vector<std::vector<double>> out(static_cast<std::size_t>(model->taxelCount()));
    for (int round = 0; round < rounds; ++round)
        for (double d = -6.0; d <= 6.0 + 1e-9; d += 0.5) {
            world.moveStage(middle + d * normal);
            const TapRecord r = world.tap();
            for (int t = 0; t < r.tap.sampleCount(); ++t)
                for (int k = 0; k < model->taxelCount(); ++k)
                    out[std::size_t(k)].push_back(r.tap.at(t, k));
        }
    return out;
}

}  // namespace activetouch
