// The simulated rig: the ideal scene is reproducible bit for bit; each effect runs only when the
// scene lists it and changes exactly what it models.
#include <QtTest>
#include <cmath>
#include <numeric>

#include "core/scene/Scene.h"
#include "devices/simulated/SimulatedWorld.h"

using namespace activetouch;

namespace {

SceneSpec idealScene() {
    Json j = Json::parse(R"({
      "object": {"shape": "rectangle", "width_mm": 48, "height_mm": 58, "offset_mm": [150, 150], "top_height_mm": 10},
      "tap": {"retract_height_mm": 12, "descent_speed_mm_s": 25, "stroke_mm": 5, "contact_threshold_counts": 250},
      "seed": 3
    })");
    return parseScene(j, "test scene", "", ".");
}

SceneSpec withEffect(const std::string& effectJson) {
    SceneSpec s = idealScene();
    Json e = Json::parse(effectJson);
    EffectSpec spec{e["name"].get<std::string>(), e, "/effects/0"};
    spec.parameters.erase("name");
    s.effects.push_back(spec);
    return s;
}

std::shared_ptr<const FingertipContactModel> model() {
    static auto m = std::make_shared<const FingertipContactModel>(
        loadFingertip("icub_fingertip_2010", ".", "test", ""));
    return m;
}

// A row of taps across the lower edge, plane to air, then back on the plane.
std::vector<TapRecord> tapAcrossEdge(SimulatedRig& rig) {
    std::vector<TapRecord> taps;
    Rig r = rig.rig();
    for (double off = -8.5; off <= 8.5; off += 1.0) taps.push_back(r.tapAt({150, 121 - off}));
    taps.push_back(r.tapAt({150, 150}));
    taps.push_back(r.tapAt({150, 150}));
    return taps;
}

double maxAbsDifference(const Tap& a, const Tap& b) {
    double m = 0;
    for (std::size_t i = 0; i < a.samples.size(); ++i)
        m = std::max(m, std::abs(a.samples[i] - b.samples[i]));
    return m;
}

}  // namespace

class TestSimulatedRig : public QObject {
    Q_OBJECT
    std::vector<TapRecord> ideal_;

private slots:
    void initTestCase() {
        SimulatedRig rig(idealScene(), model());
        ideal_ = tapAcrossEdge(rig);
    }

    void idealSceneIsBitIdenticalRunToRun() {
        SimulatedRig again(idealScene(), model());
        const auto taps = tapAcrossEdge(again);
        for (std::size_t i = 0; i < taps.size(); ++i) {
            QVERIFY(taps[i].tap.samples == ideal_[i].tap.samples);
            QCOMPARE(taps[i].startTime_s, ideal_[i].startTime_s);
        }
        // The ideal model has no randomness: another seed gives the same taps.
        SceneSpec other = idealScene();
        other.seed = 12345;
        SimulatedRig reseeded(other, model());
        const auto taps2 = tapAcrossEdge(reseeded);
        for (std::size_t i = 0; i < taps2.size(); ++i)
            QVERIFY(taps2[i].tap.samples == ideal_[i].tap.samples);
    }

    void idealTapsHaveThePaperShape() {
        // On the plane the reflex stops the tap; far in the air the stroke limit does and nothing
        // touches; the tap fits the window (starts and ends retracted).
        QVERIFY(ideal_.front().ending == TapEnding::ContactReflex);
        QVERIFY(ideal_[17].ending == TapEnding::StrokeLimit);
        QCOMPARE(*std::max_element(ideal_[17].tap.samples.begin(), ideal_[17].tap.samples.end()),
                 0.0);
        const Tap& plane = ideal_.front().tap;
        for (int k = 0; k < 12; ++k) {
            QCOMPARE(plane.at(0, k), 0.0);
            QCOMPARE(plane.at(49, k), 0.0);
        }
        const double total = std::accumulate(plane.frame(25), plane.frame(25) + 12, 0.0);
        QVERIFY2(std::abs(total - 250.0) < 0.01,
                 qPrintable(QString::number(total, 'g', 12)));  // held at the contact threshold
    }

    void unlistedEffectsAreNeverConstructed() {
        std::map<std::string, int> before;
        for (const auto& d : effectCatalogue()) before[d.name] = Effect::constructedCount(d.name);
        {
            SimulatedRig ideal(idealScene(), model());
            QVERIFY(ideal.world().activeEffects().empty());
            SimulatedRig noisy(withEffect(R"({"name": "taxel_noise", "sigma_counts": 2})"),
                               model());
            QCOMPARE(noisy.world().activeEffects(), std::vector<std::string>{"taxel_noise"});
            tapAcrossEdge(noisy);
        }
        for (const auto& d : effectCatalogue())
            QCOMPARE(Effect::constructedCount(d.name) - before[d.name],
                     d.name == "taxel_noise" ? 1 : 0);
    }

    void eachEffectChangesWhatItModels_data() {
        QTest::addColumn<QString>("effect");
        for (const auto& d : effectCatalogue()) {
            Json e{{"name", d.name}};
            for (const auto& p : d.parameters) e[p.key] = p.typical;
            if (d.name == "adc_quantisation") e["max_counts"] = 60;  // low enough to saturate
            if (d.name == "dead_taxel") e["taxels"] = {9};
            if (d.name == "intermittent_taxel") {
                e["taxels"] = {9};
                e["off_fraction"] = 0.3;
            }
            if (d.name == "saturation_recovery") e["saturation_counts"] = 20;  // reached here
            if (d.name == "stage_error") e["sigma_mm"] = 0.3;
            if (d.name == "contact_latency") e["latency_s"] = 0.04;
            if (d.name == "viscoelastic_memory") {
                e["fraction"] = 0.3;
                e["time_constant_s"] = 2.0;
            }
            QTest::newRow(d.name.c_str()) << QString::fromStdString(e.dump());
        }
    }
    void eachEffectChangesWhatItModels() {
        QFETCH(QString, effect);
        const std::string name = Json::parse(effect.toStdString())["name"];
        if (name == "link_dropout") {
            // Listed at its typical 0 it never fires; at 1 every tap fails as a device error.
            SimulatedRig quiet(withEffect(effect.toStdString()), model());
            QCOMPARE(tapAcrossEdge(quiet).size(), ideal_.size());
            SimulatedRig dropping(
                withEffect(R"({"name": "link_dropout", "probability_per_tap": 1})"), model());
            try {
                tapAcrossEdge(dropping);
                QFAIL("a stream that always drops took a tap");
            } catch (const RigError& e) {
                QVERIFY2(QString(e.what()).contains("stream dropped"), e.what());
            }
            return;
        }
        SimulatedRig rig(withEffect(effect.toStdString()), model());
        const auto taps = tapAcrossEdge(rig);
        double changed = 0;
        for (std::size_t i = 0; i < taps.size(); ++i)
            changed = std::max(changed, maxAbsDifference(taps[i].tap, ideal_[i].tap));
        QVERIFY2(changed > 0, "the effect left every tap as the ideal model made it");

        const Tap& plane = taps.front().tap;
        const Tap& idealPlane = ideal_.front().tap;
        if (name == "taxel_noise") {
            // Noise shows on every taxel, even where nothing touches, and never goes negative.
            double airSum = 0;
            for (double v : taps[17].tap.samples) {
                QVERIFY(v >= 0);
                airSum += v;
            }
            QVERIFY(airSum > 0);
        } else if (name == "baseline_drift") {
            for (const auto& t : taps)
                for (double v : t.tap.samples) QVERIFY(v >= 0);
        } else if (name == "adc_quantisation") {
            bool saturated = false;
            for (const auto& t : taps)
                for (double v : t.tap.samples) {
                    QCOMPARE(v, std::round(v));
                    QVERIFY(v >= 0 && v <= 60);
                    saturated = saturated || v == 60;
                }
            QVERIFY(saturated);
        } else if (name == "contact_latency") {
            // The tip keeps pressing 40 ms x 25 mm/s = 1 mm past the threshold crossing.
            QVERIFY(std::abs(taps.front().stopDepth_mm - ideal_.front().stopDepth_mm - 1.0) < 1e-9);
            QVERIFY(std::accumulate(plane.frame(25), plane.frame(25) + 12, 0.0) > 250.0);
        } else if (name == "stage_error") {
            // Taps differ because the tip landed elsewhere; the pressure pattern is still ideal
            // physics.
            QVERIFY(rig.world().actualPose() != rig.world().commandedPose());
            QCOMPARE(rig.world().commandedPose(), (Vec2{150, 150}));
            QVERIFY(distance(rig.world().actualPose(), rig.world().commandedPose()) < 2.0);
        } else if (name == "viscoelastic_memory") {
            // The second of two plane taps starts with a residual from the first.
            const Tap& second = taps.back().tap;
            QVERIFY(second.at(0, 9) > 0.0);
            QCOMPARE(ideal_.back().tap.at(0, 9), 0.0);
            QVERIFY(plane.at(49, 9) > 0.0);  // the pad has not recovered by the end of the window
        } else if (name == "crosstalk") {
            // A taxel the ideal plane tap barely touches reads a share of its neighbours.
            int raised = 0;
            for (int k = 0; k < 12; ++k) raised += plane.at(25, k) > idealPlane.at(25, k) + 1e-9;
            QVERIFY(raised >= 6);
        } else if (name == "dead_taxel") {
            for (const auto& t : taps)
                for (int s = 0; s < t.tap.sampleCount(); ++s) QCOMPARE(t.tap.at(s, 9), 0.0);
            for (int k = 0; k < 12; ++k)
                if (k != 9) QCOMPARE(plane.at(25, k), idealPlane.at(25, k));
        } else if (name == "taxel_gain") {
            // Every taxel reads its ideal pressure times a gain of its own, the same in every
            // tap, and the gains differ.
            std::vector<double> gain(12, 0.0);
            for (std::size_t i = 0; i < taps.size(); ++i)
                for (int s = 0; s < taps[i].tap.sampleCount(); ++s)
                    for (int k = 0; k < 12; ++k) {
                        const double ideal = ideal_[i].tap.at(s, k);
                        if (ideal < 1.0) continue;
                        const double g = taps[i].tap.at(s, k) / ideal;
                        if (gain[static_cast<std::size_t>(k)] == 0.0)
                            gain[static_cast<std::size_t>(k)] = g;
                        QVERIFY(std::abs(g - gain[static_cast<std::size_t>(k)]) < 1e-9);
                    }
            const auto [lo, hi] = std::minmax_element(gain.begin(), gain.end());
            QVERIFY(*lo > 0.0 && *hi > *lo * 1.05);
            // The fingertip's gains do not depend on the run's seed: another seed, same gains.
            SceneSpec other = withEffect(effect.toStdString());
            other.seed += 1000;
            SimulatedRig again(other, model());
            QVERIFY(tapAcrossEdge(again)[0].tap.samples == plane.samples);
        } else if (name == "saturation_recovery") {
            // Nothing reads above the level; once the press eases, a saturated taxel comes down
            // along the recovery, not with the pressure.
            bool saturated = false, lingering = false;
            for (std::size_t i = 0; i < taps.size(); ++i)
                for (int s = 0; s < taps[i].tap.sampleCount(); ++s)
                    for (int k = 0; k < 12; ++k) {
                        const double v = taps[i].tap.at(s, k);
                        QVERIFY(v <= 20.0);
                        saturated = saturated || v == 20.0;
                        lingering = lingering || (v < 20.0 && v > ideal_[i].tap.at(s, k) + 1.0);
                    }
            QVERIFY(saturated && lingering);
        } else if (name == "intermittent_taxel") {
            // Taxel 9 drops to 0 now and then where it is pressed; the others are untouched.
            int dropped = 0, pressed = 0;
            for (std::size_t i = 0; i < taps.size(); ++i)
                for (int s = 0; s < taps[i].tap.sampleCount(); ++s) {
                    for (int k = 0; k < 12; ++k)
                        if (k != 9) QCOMPARE(taps[i].tap.at(s, k), ideal_[i].tap.at(s, k));
                    if (ideal_[i].tap.at(s, 9) > 1.0) {
                        ++pressed;
                        dropped += taps[i].tap.at(s, 9) == 0.0;
                    }
                }
            qInfo("taxel 9 off in %d of %d pressed samples (long-run share 0.3)", dropped, pressed);
            QVERIFY(dropped > 0 && dropped < pressed);
        } else {
            QFAIL(qPrintable("no behaviour check for effect " + QString::fromStdString(name)));
        }
    }

    void effectRandomnessIsSeededAndIndependent() {
        // Same seed, same noise; another seed, other noise; adding another effect does not change
        // the noise draws.
        const auto noise = R"({"name": "taxel_noise", "sigma_counts": 2})";
        SimulatedRig a(withEffect(noise), model()), b(withEffect(noise), model());
        QVERIFY(tapAcrossEdge(a)[3].tap.samples == tapAcrossEdge(b)[3].tap.samples);
        SceneSpec other = withEffect(noise);
        other.seed = 4;
        SimulatedRig c(other, model());
        QVERIFY(tapAcrossEdge(c)[3].tap.samples != tapAcrossEdge(a)[3].tap.samples);
    }

    void badEffectEntriesAreNamed_data() {
        QTest::addColumn<QString>("effect");
        QTest::addColumn<QString>("problem");
        QTest::newRow("unknown effect") << R"({"name": "gravity_waves"})"
                                        << "unknown effect 'gravity_waves'";
        QTest::newRow("missing parameter") << R"({"name": "taxel_noise"})"
                                           << "missing required number 'sigma_counts'";
        QTest::newRow("out of range") << R"({"name": "taxel_noise", "sigma_counts": 500})"
                                      << "outside the allowed range";
        QTest::newRow("unknown parameter")
            << R"({"name": "taxel_noise", "sigma_counts": 1, "colour": 3})"
            << "unknown key 'colour'";
        QTest::newRow("taxel that does not exist")
            << R"({"name": "dead_taxel", "taxels": [12], "reading_counts": 0})"
            << "does not exist";
        QTest::newRow("gains for too few taxels") << R"({"name": "taxel_gain", "gains": [1, 1, 1]})"
                                                  << "give one gain per taxel: 12, not 3";
        QTest::newRow("a gain out of range")
            << R"({"name": "taxel_gain", "gains": [1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 0]})"
            << "gains/11: expected a number between 0.05 and 20";
        QTest::newRow("gains beside a spread")
            << R"({"name": "taxel_gain", "spread": 0.2, "gains": [1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1]})"
            << "leave 'spread' out";
    }
    void badEffectEntriesAreNamed() {
        QFETCH(QString, effect);
        QFETCH(QString, problem);
        const SceneSpec s = withEffect(effect.toStdString());
        for (int attempt = 0; attempt < 2; ++attempt) {
            try {
                if (attempt == 0)
                    validateEffects(s);
                else
                    SimulatedRig rig(s, model());
                QFAIL("the effect was accepted");
            } catch (const InputError& e) {
                QVERIFY2(QString(e.what()).contains("test scene"), e.what());
                QVERIFY2(QString(e.what()).contains("/effects/0"), e.what());
                QVERIFY2(QString(e.what()).contains(problem), e.what());
            }
        }
    }

    void stageRefusesMovesOutsideItsTravel() {
        SimulatedRig rig(idealScene(), model());
        QVERIFY_THROWS_EXCEPTION(RigError, rig.rig().stage.moveTo({-1, 10}));
        QVERIFY_THROWS_EXCEPTION(RigError, rig.rig().stage.moveTo({10, 301}));
        try {
            rig.rig().stage.moveTo({-0.25, 150});
            QFAIL("a move outside the travel was accepted");
        } catch (const RigError& e) {
            QCOMPARE(QString(e.what()),
                     QString("simulated stage: target (-0.25, 150) mm is outside "
                             "the travel (0..650, 0..300 mm)"));
        }
    }
};

QTEST_APPLESS_MAIN(TestSimulatedRig)
#include "test_simulated_rig.moc"
