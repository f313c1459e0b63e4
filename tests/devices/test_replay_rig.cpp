// A recorded trial replayed as a rig: a tap is served only where the recorded run tapped, in the
// recorded order; anything else ends the replay with a sentence saying where it parted.
#include <QtTest>

#include "core/run/ReplayRig.h"

using namespace activetouch;

namespace {

RecordedTrial threeTaps() {
    RecordedTrial t;
    t.label = "cross";
    t.mode = FollowingMode::Active;
    t.trial = 2;
    for (int i = 0; i < 3; ++i) {
        TapRecord r;
        r.pose = {150.0 + 2.0 * i, 120.0};
        r.startTime_s = 10.0 + 2.5 * i;
        r.ending = TapEnding::ContactReflex;
        r.tap = Tap(50, 12);
        for (int s = 0; s < 50; ++s)
            for (int k = 0; k < 12; ++k) r.tap.at(s, k) = i * 100 + s + k;
        t.taps.push_back(r);
        t.decisions.push_back({"lower edge", 9, "follow"});
    }
    return t;
}

}  // namespace

class TestReplayRig : public QObject {
    Q_OBJECT

private slots:
    void servesTheRecordedTapsWhereTheyWereTaken() {
        const RecordedTrial recorded = threeTaps();
        ReplayRig replay(recorded, "results/paper");
        Rig rig = replay.rig();
        QCOMPARE(rig.sensor.taxelCount(), 12);
        QCOMPARE(rig.clock.now_s(), 10.0);  // the first tap's start
        for (int i = 0; i < 3; ++i) {
            const TapRecord r = rig.tapAt(recorded.taps[static_cast<std::size_t>(i)].pose);
            QVERIFY(r.tap.samples == recorded.taps[static_cast<std::size_t>(i)].tap.samples);
            QCOMPARE(r.startTime_s, 10.0 + 2.5 * i);
            QCOMPARE(replay.served(), i + 1);
        }
        // The last frame of the last tap served; the clock ends a mean cycle after it.
        double frame[12];
        rig.sensor.latestFrame(frame);
        QCOMPARE(frame[0], 249.0);
        QCOMPARE(frame[11], 260.0);
        QCOMPARE(rig.clock.now_s(), 15.0 + 2.5);
        QCOMPARE(rig.stage.position().x, 154.0);
    }

    void aTapElsewhereLeavesTheRecording() {
        const RecordedTrial recorded = threeTaps();
        ReplayRig replay(recorded, "results/paper");
        Rig rig = replay.rig();
        rig.tapAt({150.0, 120.0});
        try {
            rig.tapAt({152.0, 121.0});  // the recorded run went to (152, 120)
            QFAIL("a tap away from the recorded pose was served");
        } catch (const RecordingLeft& e) {
            const QString m = e.what();
            QVERIFY2(m.contains("the recorded active cross trial 2 (results/paper) took tap 1 at "
                                "(152.00, 120.00) mm") &&
                         m.contains("asked for it at (152.00, 121.00) mm, 1.00 mm away"),
                     e.what());
        }
        QCOMPARE(replay.served(), 1);  // nothing was served for the refused tap
        // Within the tolerance it is the same pose.
        rig.tapAt({152.0 + 0.5 * ReplayRig::kPoseTolerance_mm, 120.0});
        QCOMPARE(replay.served(), 2);
    }

    void aStartElsewhereAndATapAfterTheEndAreRefused() {
        const RecordedTrial recorded = threeTaps();
        {
            ReplayRig replay(recorded, "r");
            Rig rig = replay.rig();
            QVERIFY_THROWS_EXCEPTION(RecordingLeft, rig.tapAt({149.0, 120.0}));
            try {
                rig.tapAt({149.0, 120.0});
            } catch (const RecordingLeft& e) {
                QVERIFY2(QString(e.what()).contains("starts at (150.00, 120.00) mm; the replay "
                                                    "started at (149.00, 120.00) mm"),
                         e.what());
            }
        }
        ReplayRig replay(recorded, "r");
        Rig rig = replay.rig();
        for (const TapRecord& r : recorded.taps) rig.tapAt(r.pose);
        try {
            rig.tapAt({156.0, 120.0});
            QFAIL("a tap after the recording's last was served");
        } catch (const RecordingLeft& e) {
            QVERIFY2(QString(e.what()).contains("ends after tap 2; the replay went on to tap 3"),
                     e.what());
        }
        // A RecordingLeft is a rig error: a run that does not know replays stops on it as on
        // any device failure.
        static_assert(std::is_base_of_v<RigError, RecordingLeft>);
    }

    void anEmptyTrialServesNothing() {
        RecordedTrial empty;
        empty.label = "l";
        ReplayRig replay(empty, "r");
        Rig rig = replay.rig();
        QCOMPARE(rig.clock.now_s(), 0.0);
        double frame[12] = {1};
        rig.sensor.latestFrame(frame);
        QCOMPARE(frame[0], 0.0);
        QVERIFY_THROWS_EXCEPTION(RecordingLeft, rig.tapAt({0.0, 0.0}));
    }
};

QTEST_GUILESS_MAIN(TestReplayRig)
#include "test_replay_rig.moc"
