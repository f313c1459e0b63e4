// What a scene fit reads before it estimates: the recording's shape, the masks of samples over
// nothing and pressed, dead taxels and the converter (see fitScene()).
#include "devices/simulated/fit/FitSteps.h"

namespace activetouch::scenefit {

void checkRecording(const SceneSpec& given, const std::vector<TapRecord>& recorded,
                    const SceneFitSettings& settings, int K) {
    if (recorded.size() < 20)
        throw InputError(settings.recording, "",
                         "a fit needs at least 20 recorded taps; the recording has " +
                             std::to_string(recorded.size()));
    for (const auto& r : recorded)
        if (r.tap.taxels != K || r.tap.sampleCount() != given.tap.samples)
            throw InputError(settings.recording, "",
                             "the recording's taps have " + std::to_string(r.tap.sampleCount()) +
                                 " samples of " + std::to_string(r.tap.taxels) +
                                 " taxels, but the scene's fingertip and tap (" +
                                 (given.source.empty() ? std::string("the experiment's scene")
                                                       : given.source + " at /tap/samples") +
                                 ") say " + std::to_string(given.tap.samples) + " of " +
                                 std::to_string(K) + "; give the scene the taps were taken with");
}

namespace {

/// The first sample at which the noise-free tap touches (its sample count where it never does).
int firstContactOf(const Tap& tap) {
    for (int t = 0; t < tap.sampleCount(); ++t)
        for (int k = 0; k < tap.taxels; ++k)
            if (tap.at(t, k) > 0.0) return t;
    return tap.sampleCount();
}

}  // namespace

Masks masksOf(const std::vector<TapRecord>& ideal, int K, double contactThreshold) {
    Masks masks;
    masks.quietMargin = 0.1 * contactThreshold;
    // Read so that a tapper whose stroke runs on another schedule than the simulated one (a real
    // rig's) is read the same: a taxel is pressed in a tap where the model presses it over
    // kPressed counts at some sample, and its pressure is the whole tap's.
    for (const auto& r : ideal) {
        double total = 0.0;
        std::vector<char> pressedTaxel(static_cast<std::size_t>(K), 0);
        for (int t = 0; t < r.tap.sampleCount(); ++t)
            for (int k = 0; k < K; ++k) {
                total += r.tap.at(t, k);
                if (r.tap.at(t, k) > kPressed) pressedTaxel[static_cast<std::size_t>(k)] = 1;
            }
        // Over nothing: a whole tap off the object, or the samples of the descent that end
        // kMargin samples before the model's first contact (a stroke on another schedule may
        // touch a little earlier).
        const int firstContact = firstContactOf(r.tap);
        std::vector<char> nothing(static_cast<std::size_t>(r.tap.sampleCount()), 0);
        for (int t = 0; t < r.tap.sampleCount(); ++t)
            nothing[static_cast<std::size_t>(t)] = total == 0.0 || t < firstContact - kMargin;
        std::vector<char> pressed(r.tap.samples.size(), 0);
        for (int t = 0; t < r.tap.sampleCount(); ++t)
            for (int k = 0; k < K; ++k)
                pressed[static_cast<std::size_t>(t * K + k)] =
                    pressedTaxel[static_cast<std::size_t>(k)];
        masks.nothing.push_back(std::move(nothing));
        masks.pressed.push_back(std::move(pressed));
    }
    return masks;
}

std::vector<char> readDeadTaxels(const std::vector<TapRecord>& recorded, const Masks& masks, int K,
                                 SceneFit& fit) {
    // Dead or stuck: where the model presses a taxel hard, it reads no more than over nothing
    // (under a twentieth of the median taxel's response).
    std::vector<char> skip(static_cast<std::size_t>(K), 0);
    std::vector<double> response(static_cast<std::size_t>(K), 0.0);
    std::vector<std::vector<double>> all(static_cast<std::size_t>(K));
    for (int k = 0; k < K; ++k) {
        double pressed = 0.0, idle = 0.0;
        long nPressed = 0, nIdle = 0;
        for (std::size_t i = 0; i < recorded.size(); ++i)
            for (int t = 0; t < recorded[i].tap.sampleCount(); ++t) {
                const double v = recorded[i].tap.at(t, k);
                all[static_cast<std::size_t>(k)].push_back(v);
                if (masks.nothing[i][static_cast<std::size_t>(t)]) {
                    idle += v;
                    ++nIdle;
                } else if (masks.pressed[i][static_cast<std::size_t>(t * K + k)]) {
                    pressed += v;
                    ++nPressed;
                }
            }
        response[static_cast<std::size_t>(k)] =
            nPressed >= 20 && nIdle > 0 ? pressed / nPressed - idle / nIdle : NAN;
    }
    std::vector<double> live;
    for (double r : response)
        if (std::isfinite(r)) live.push_back(r);
    std::sort(live.begin(), live.end());
    const double median = live.empty() ? 0.0 : live[live.size() / 2];
    for (int k = 0; k < K; ++k) {
        const double r = response[static_cast<std::size_t>(k)];
        if (!(std::isfinite(r) && median > 0 && r < 0.05 * median)) continue;
        fit.deadTaxels.push_back(k);
        skip[static_cast<std::size_t>(k)] = 1;
        auto& v = all[static_cast<std::size_t>(k)];
        std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
        fit.deadReading = v[v.size() / 2];  // its reading under the noise
    }
    return skip;
}

Converter readConverter(const std::vector<TapRecord>& recorded, const SceneSpec& base) {
    // Every reading a whole count. Its range: a converter that saturates piles its readings at
    // the top of its range (every reading that would lie above it), where a reading tail that
    // does not reach it thins out to a few at its highest value.
    Converter c;
    for (const auto& r : recorded)
        for (double v : r.tap.samples) {
            c.whole = c.whole && v == std::floor(v);
            c.top = std::max(c.top, v);
        }
    for (const auto& r : recorded)
        for (double v : r.tap.samples) {
            c.atTop += v == c.top;
            c.belowTop += v < c.top && v >= c.top - 1.0;
        }
    c.saturates = c.whole && c.atTop >= kPileReadings && c.atTop >= kPileRatio * c.belowTop;
    for (const auto& e : base.effects)
        if (e.name == "adc_quantisation" && e.parameters.contains("max_counts"))
            c.maxCounts = e.parameters["max_counts"].get<double>();
    c.maxCounts = c.saturates ? c.top : std::max(c.maxCounts, c.top);
    return c;
}

EffectSpec blinkEffectOf(const Blinking& blinking) {
    EffectSpec e;
    e.name = "intermittent_taxel";
    e.parameters = Json{{"taxels", blinking.taxels},
                        {"off_fraction", blinking.offFraction},
                        {"mean_off_s", blinking.meanOff_s},
                        {"reading_counts", blinking.reading}};
    return e;
}

}  // namespace activetouch::scenefit
