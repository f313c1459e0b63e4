#include "app/cli/FingertipComparison.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/common/InputError.h"
#include "core/common/NumberText.h"
#include "core/scene/Scene.h"
#include "core/stats/Intervals.h"
#include "core/stats/SampleTests.h"
#include "devices/simulated/RestingReadings.h"

namespace activetouch::cli {

namespace {

/// Taps at rest per scene: 40 taps of the paper's 50 samples give 2,000 readings a taxel, enough
/// for a KS distance to within about 0.03.
constexpr int kRestingTaps = 40;

/// `readings` as fingertip-stats treats a real recording's resting frames: each tap's samples
/// above that tap's resting level (their mean, rounded to whole counts), clipped at 0.
std::vector<double> aboveEachTapsLevel(const std::vector<double>& readings, int samplesPerTap) {
    std::vector<double> out;
    const auto n = static_cast<std::size_t>(std::max(1, samplesPerTap));
    for (std::size_t start = 0; start < readings.size(); start += n) {
        const std::size_t end = std::min(readings.size(), start + n);
        double sum = 0.0;
        for (std::size_t i = start; i < end; ++i) sum += readings[i];
        const double level = std::round(sum / static_cast<double>(end - start));
        for (std::size_t i = start; i < end; ++i) out.push_back(std::max(0.0, readings[i] - level));
    }
    return out;
}

/// The quantiles at kPressedLevels of the values of `all` over kPressed_counts; empty if none.
std::vector<double> pressedQuantiles(const std::vector<std::vector<double>>& all) {
    std::vector<double> pressed;
    for (const auto& v : all)
        for (double x : v)
            if (x > kPressed_counts) pressed.push_back(x);
    std::vector<double> out;
    if (pressed.empty()) return out;
    std::sort(pressed.begin(), pressed.end());
    for (double level : kPressedLevels)
        out.push_back(pressed[std::size_t(level * double(pressed.size() - 1))]);
    return out;
}

}  // namespace

std::vector<double> realPressedQuantiles(const FingertipStatsReport& report,
                                         const std::string& finger) {
    std::vector<std::vector<double>> all;
    for (const TaxelStats* t : taxelsOf(report, finger)) all.push_back(t->contactAbove);
    return pressedQuantiles(all);
}

std::vector<const TaxelStats*> taxelsOf(const FingertipStatsReport& report,
                                        const std::string& finger) {
    std::vector<const TaxelStats*> out;
    std::string names;
    for (const TaxelStats& t : report.taxels)
        if (t.finger == finger) out.push_back(&t);
    for (const FingerStats& f : report.fingers) names += (names.empty() ? "" : ", ") + f.finger;
    if (out.empty())
        throw InputError("--finger", "",
                         "the recordings have no finger '" + finger + "'; their fingers: " + names);
    return out;
}

std::vector<SceneComparison> compareWithScenes(const FingertipStatsReport& report,
                                               const std::string& finger,
                                               const std::vector<std::string>& scenePaths) {
    const std::vector<const TaxelStats*> taxels = taxelsOf(report, finger);
    std::vector<SceneComparison> out;
    for (const std::string& path : scenePaths) {
        const SceneSpec scene = loadScene(path);
        const RestingReadings simulated = restingReadings(scene, kRestingTaps);
        if (simulated.taxels.size() != taxels.size())
            throw InputError(path, "/fingertip",
                             "its fingertip has " + std::to_string(simulated.taxels.size()) +
                                 " taxels and the " + finger + " finger " +
                                 std::to_string(taxels.size()) + ": compare like with like");
        SceneComparison c{path, 0.0, {}, pressedQuantiles(edgeReadings(scene, 2))};
        for (const EffectSpec& e : scene.effects)
            if (e.name == "taxel_noise") c.sigma = e.parameters.value("sigma_counts", 0.0);
        for (std::size_t k = 0; k < taxels.size(); ++k)
            c.ks.push_back(stats::ksDistance(
                taxels[k]->restAbove,
                aboveEachTapsLevel(simulated.taxels[k], simulated.samplesPerTap)));
        out.push_back(std::move(c));
    }
    return out;
}

namespace {

std::string quantileText(const std::vector<double>& q) {
    if (q.empty()) return "no reading pressed";
    std::string text;
    for (std::size_t i = 0; i < q.size(); ++i) {
        char cell[48];
        std::snprintf(cell, sizeof cell, "%s%g %%: %.4g", i ? ", " : "", kPressedLevels[i] * 100,
                      q[i]);
        text += cell;
    }
    return text + " counts";
}

}  // namespace

void printComparison(const std::vector<SceneComparison>& comparisons, const std::string& finger,
                     const std::vector<double>& realPressed) {
    std::printf("under contact (readings over %g counts above rest), the %s finger grasping: %s\n",
                kPressed_counts, finger.c_str(), quantileText(realPressed).c_str());
    for (const SceneComparison& c : comparisons)
        std::printf("  %s's fingertip tapping across its object's edge: %s\n", c.scene.c_str(),
                    quantileText(c.pressedQuantiles).c_str());
    for (const SceneComparison& c : comparisons) {
        int close = 0;
        std::string row;
        for (double d : c.ks) {
            close += d <= 0.1;
            char cell[16];
            std::snprintf(cell, sizeof cell, " %.3f", d);
            row += cell;
        }
        std::printf("resting KS distance, %s finger vs %s, per taxel:%s (%d of %zu within 0.1)\n",
                    finger.c_str(), c.scene.c_str(), row.c_str(), close, c.ks.size());
    }
}

namespace {

/// The median over `taxels` (dead and stuck ones left out) of `of`.
template <class Of>
double medianOver(const std::vector<const TaxelStats*>& taxels, Of of) {
    std::vector<double> values;
    for (const TaxelStats* t : taxels)
        if (!t->dead && !t->stuck) values.push_back(of(*t));
    return stats::medianOr(values, 0.0);
}

}  // namespace

Json measuredScene(const Json& baseScene, const FingertipStatsReport& report,
                   const std::string& finger, const std::string& provenance) {
    const std::vector<const TaxelStats*> taxels = taxelsOf(report, finger);
    int dead = 0, saturating = 0;
    for (const TaxelStats* t : taxels) {
        dead += t->dead || t->stuck;
        saturating += t->atFullScale > 0.0;
    }
    const double sigma =
        std::round(medianOver(taxels, [](const TaxelStats& t) { return t.sigma.mean; }) * 1000.0) /
        1000.0;
    const double drift =
        medianOver(taxels, [](const TaxelStats& t) { return std::abs(t.drift.mean); });
    const double step = medianOver(taxels, [](const TaxelStats& t) { return t.quantum; });
    // A resting level that moves less than half a converter step within a recording: no drift
    // to simulate.
    const bool drifts = drift >= 0.5 * step;
    Json scene = baseScene;
    Json effects = Json::array();
    bool noise = false;
    for (Json e : scene["effects"]) {
        if (e.value("name", "") == "baseline_drift" && !drifts) continue;
        if (e.value("name", "") == "taxel_noise") e["sigma_counts"] = sigma, noise = true;
        effects.push_back(e);
    }
    if (!noise) effects.push_back({{"name", "taxel_noise"}, {"sigma_counts", sigma}});
    scene["effects"] = effects;
    scene["description"] =
        "The paper's rig with the noise of a real iCub fingertip: taxel_noise's sigma is the "
        "median over the " +
        finger +
        " finger's taxels of the resting standard deviation "
        "measured by fingertip-stats (" +
        numberText(sigma) +
        " counts); readings come in whole "
        "counts (adc_quantisation, as measured); " +
        (drifts
             ? "the resting level drifts within a recording (median " + numberText(drift) +
                   " counts), but the recordings carry no time stamps, so the drift's rate is "
                   "the base scene's; "
             : "the resting level moves by a median " + numberText(std::round(drift * 100) / 100) +
                   " counts within a recording, under half a step, so baseline_drift is not "
                   "listed; ") +
        "no taxel was dead (" + std::to_string(dead) + ") or reached full scale (" +
        std::to_string(saturating) +
        "), so neither effect is listed. Everything else as the "
        "base scene.";
    scene["provenance"] = provenance;
    return scene;
}

}  // namespace activetouch::cli
