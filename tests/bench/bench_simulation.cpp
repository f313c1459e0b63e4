// Microseconds to simulate one tap on the paper rectangle, across the lower edge: the ideal
// scene, with every effect listed, and with each effect alone (what each costs); and what one of
// the noise's and drift's Gaussian values costs, drawn in blocks of a tap's 600 and one at a
// time. Budgets (docs/benchmarks.md): ideal <= 10 us, all effects <= 50 us; the rest have none.
#include <cstdio>
#include <vector>

#include "bench/BenchHarness.h"
#include "core/common/Random.h"
#include "core/scene/Scene.h"
#include "devices/simulated/SimulatedWorld.h"

using namespace activetouch;

namespace {
double microsecondsPerTap(SceneSpec scene, std::shared_ptr<const FingertipContactModel> model) {
    SimulatedRig rig(scene, model);
    Rig r = rig.rig();
    int i = 0;
    double sink = 0;
    const double us = bench::medianMicroseconds(
        [&] {
            const double off = -8.5 + (i++ % 18);
            sink += r.tapAt({150, 121 - off}).tap.samples[600];
        },
        4000);
    return sink == -1 ? 0 : us;
}
}  // namespace

int main() {
    SceneSpec scene =
        loadScene(std::string(ACTIVETOUCH_SOURCE_DIR) + "/experiments/scenes/paper_rectangle.json");
    auto model = std::make_shared<const FingertipContactModel>(scene.fingertip);
    SceneSpec ideal = scene;
    ideal.effects.clear();
    bench::report("simulate one tap, ideal scene", microsecondsPerTap(ideal, model), "us", 10.0);
    SceneSpec all = ideal;
    for (const auto& d : effectCatalogue()) {
        Json p = Json::object();
        for (const auto& param : d.parameters) p[param.key] = param.typical;
        if (d.takesTaxelList) p["taxels"] = {3};
        all.effects.push_back({d.name, p, "/effects"});
    }
    bench::report("simulate one tap, every effect on", microsecondsPerTap(all, model), "us", 50.0);
    for (const EffectSpec& e : all.effects) {
        SceneSpec alone = ideal;
        alone.effects = {e};
        const std::string what = "simulate one tap, ideal + " + e.name;
        std::printf("%-52s %10.3f us\n", what.c_str(), microsecondsPerTap(alone, model));
    }
    RandomStream rng(1);
    std::vector<double> values(600);
    double sink = 0;
    const double block = bench::medianMicroseconds(
        [&] {
            rng.normals(values.data(), values.size());
            sink += values[7];
        },
        2000);
    const double single = bench::medianMicroseconds(
        [&] {
            for (double& v : values) v = rng.normal();
            sink += values[7];
        },
        2000);
    std::printf("%-52s %10.3f ns\n", "draw a Gaussian value, in blocks of 600",
                sink == -1 ? 0 : 1000 * block / 600);
    std::printf("%-52s %10.3f ns\n", "draw a Gaussian value, one normal() at a time",
                1000 * single / 600);
    return 0;
}
