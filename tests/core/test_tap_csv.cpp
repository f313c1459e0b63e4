// Tap files: what is written reads back exactly, a file cut short by a stopped run keeps its
// finished taps and says what was cut, a write that fails (a full disk) stops the writer naming
// the file and keeps the taps written before, and a broken file is refused with its line.
#include <QTemporaryDir>
#include <QtTest>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "core/common/InputError.h"
#include "core/records/FollowingRecording.h"
#include "core/records/TapCsv.h"
#include "support/FileSizeLimit.h"

using namespace activetouch;
using test::FileSizeLimit;

namespace {
/// `write` fails naming `path` and the system's `reason`.
void expectWriteRefused(const std::function<void()>& write, const std::string& path,
                        const QString& reason) {
    try {
        write();
        QFAIL("the failed write went unreported");
    } catch (const WriteError& e) {
        const QString m = e.what();
        QVERIFY2(m.contains(QString::fromStdString(path)), qPrintable(m));
        QVERIFY2(m.contains("cannot write the file (" + reason + ")"), qPrintable(m));
        QVERIFY2(m.contains("what was written before stays in the file"), qPrintable(m));
    }
}

/// `read` refuses the broken file (bad.csv) naming it, `line` and `problem`.
void expectRefusedAt(const std::function<void()>& read, int line, const QString& problem) {
    try {
        read();
        QFAIL("the broken file was accepted");
    } catch (const InputError& e) {
        const QString m = e.what();
        QVERIFY2(m.contains("bad.csv"), qPrintable(m));
        QVERIFY2(m.contains(QString("line %1").arg(line)), qPrintable(m));
        QVERIFY2(m.contains(problem), qPrintable(m));
    }
}
}  // namespace

class TestTapCsv : public QObject {
    Q_OBJECT
    QTemporaryDir dir_;
    ClassSet classes_;

    std::vector<CollectedTap> someTaps() {
        std::vector<CollectedTap> taps;
        for (int i = 0; i < 3; ++i) {
            CollectedTap c;
            c.dataSet = 1 + i;
            c.cls = 5 * i + 3;
            c.trueOffset_mm = -1.25 + i;
            c.record.pose = {100.125 + i, 50.5};
            c.record.startTime_s = 2.5 * i;
            c.record.ending = i == 1 ? TapEnding::StrokeLimit : TapEnding::ContactReflex;
            c.record.stopDepth_mm = 0.3125 + 0.25 * i;
            c.record.tap = Tap(50, 12);
            for (int s = 0; s < 50; ++s)
                for (int k = 0; k < 12; ++k)
                    c.record.tap.at(s, k) = std::fmod(0.1 * s * (k + 1) + i, 255.0);
            taps.push_back(c);
        }
        return taps;
    }

    std::string writeTaps() {
        const std::string path = dir_.filePath("taps.csv").toStdString();
        TapCsvWriter w(path, 12);
        for (const auto& t : someTaps()) w.append(t, classes_);
        return path;
    }

    std::string corrupt(const std::string& path, int lineNumber, const std::string& replacement) {
        std::ifstream in(path);
        std::stringstream out;
        std::string line;
        for (int n = 1; std::getline(in, line); ++n)
            out << (n == lineNumber ? replacement : line) << '\n';
        const std::string bad = dir_.filePath("bad.csv").toStdString();
        std::ofstream(bad) << out.str();
        return bad;
    }

    /// A copy of the file at `path` as a run stopped while writing leaves it: its first `lines`
    /// lines and `more` characters of the next.
    std::string cutAfter(const std::string& path, std::size_t lines, std::size_t more,
                         const char* name) {
        std::ifstream in(path);
        const std::string whole((std::istreambuf_iterator<char>(in)), {});
        std::size_t at = 0;
        for (std::size_t n = 0; n < lines; ++n) at = whole.find('\n', at) + 1;
        const std::string cut = dir_.filePath(name).toStdString();
        std::ofstream(cut) << whole.substr(0, at + more);
        return cut;
    }

    /// Two trials of a following recording: three taps, then two.
    std::string writeFollowing() {
        const std::string path = dir_.filePath("following.csv").toStdString();
        FollowingRecording w(path, 12);
        for (int trial = 1; trial <= 2; ++trial)
            for (int i = 0; i < 4 - trial; ++i) {
                FollowedTap t;
                t.record = someTaps()[static_cast<std::size_t>(i % 3)].record;
                t.percept.region = Region::Edge;
                t.percept.orientationDeg = 270;
                t.percept.position = 9;
                t.decision = {RuleId::FollowInRange, {2.0, 0.0}, {}};
                t.contact = true;
                w.append("rectangle", FollowingMode::Active, trial, i, t);
            }
        return path;
    }

private slots:
    void roundTripIsExact() {
        const auto original = someTaps();
        const auto read = readTapCsv(writeTaps(), classes_);
        QCOMPARE(read.size(), original.size());
        for (std::size_t i = 0; i < read.size(); ++i) {
            QCOMPARE(read[i].cls, original[i].cls);
            QCOMPARE(read[i].dataSet, original[i].dataSet);
            QCOMPARE(read[i].trueOffset_mm, original[i].trueOffset_mm);
            QCOMPARE(read[i].record.pose.x, original[i].record.pose.x);
            QVERIFY(read[i].record.ending == original[i].record.ending);
            QCOMPARE(read[i].record.stopDepth_mm, original[i].record.stopDepth_mm);
            QVERIFY(read[i].record.tap.samples == original[i].record.tap.samples);
        }
    }

    void recordingsWithoutStopDepthsStillRead() {
        // A recording in the layout without the stop_depth_mm column reads with every stop depth
        // 0 (not recorded) and everything else as written.
        std::ifstream in(writeTaps());
        std::stringstream out;
        std::string line;
        while (std::getline(in, line)) {
            auto fields = QString::fromStdString(line).split(',');
            fields.removeAt(9);
            out << fields.join(',').toStdString() << '\n';
        }
        const std::string earlier = dir_.filePath("earlier.csv").toStdString();
        std::ofstream(earlier) << out.str();
        const auto original = someTaps();
        const auto read = readTapCsv(earlier, classes_);
        QCOMPARE(read.size(), original.size());
        for (std::size_t i = 0; i < read.size(); ++i) {
            QCOMPARE(read[i].record.stopDepth_mm, 0.0);
            QCOMPARE(read[i].record.pose.x, original[i].record.pose.x);
            QVERIFY(read[i].record.tap.samples == original[i].record.tap.samples);
        }
    }

    void brokenFilesNameTheLineAndProblem_data() {
        QTest::addColumn<int>("line");
        QTest::addColumn<QString>("replacement");
        QTest::addColumn<QString>("problem");
        QTest::newRow("wrong columns") << 1 << "set,class,x,y"
                                       << "unexpected columns";
        QTest::newRow("too few fields") << 3 << "1,3,270,4,-1.25"
                                        << "has 5 fields";
        QTest::newRow("not a number")
            << 3 << "1,3,270,4,-1.25,100.125,50.5,0,reflex,0.3125,1,a,0,0,0,0,0,0,0,0,0,0,0"
            << "'a' is not a number";
        QTest::newRow("NaN")
            << 3 << "1,3,270,4,-1.25,100.125,50.5,0,reflex,0.3125,1,nan,0,0,0,0,0,0,0,0,0,0,0"
            << "not a finite number";
        QTest::newRow("above 255")
            << 3 << "1,3,270,4,-1.25,100.125,50.5,0,reflex,0.3125,1,300,0,0,0,0,0,0,0,0,0,0,0"
            << "outside the fingertip's 0..255";
        QTest::newRow("negative")
            << 3 << "1,3,270,4,-1.25,100.125,50.5,0,reflex,0.3125,1,-2,0,0,0,0,0,0,0,0,0,0,0"
            << "outside the fingertip's 0..255";
        QTest::newRow("class out of range")
            << 2 << "1,999,270,4,-1.25,100,50,0,reflex,0.3125,0,0,0,0,0,0,0,0,0,0,0,0,0"
            << "class 999 is outside";
        QTest::newRow("sample out of order")
            << 4 << "1,3,270,4,-1.25,100,50,0,reflex,0.3125,7,0,0,0,0,0,0,0,0,0,0,0,0"
            << "does not continue the tap";
        QTest::newRow("bad ending")
            << 2 << "1,3,270,4,-1.25,100,50,0,bounced,0.3125,0,0,0,0,0,0,0,0,0,0,0,0,0"
            << "neither reflex nor stroke_limit";
        QTest::newRow("other classes")
            << 2 << "1,3,0,4,-1.25,100,50,0,reflex,0.3125,0,0,0,0,0,0,0,0,0,0,0,0,0"
            << "recorded with other classes";
        QTest::newRow("set beyond any count")
            << 2 << "99999999999,3,270,4,-1.25,100,50,0,reflex,0.3125,0,0,0,0,0,0,0,0,0,0,0,0,0"
            << "'99999999999' is not a whole number";
        QTest::newRow("position between classes")
            << 2 << "1,3,270,4.5,-1.25,100,50,0,reflex,0.3125,0,0,0,0,0,0,0,0,0,0,0,0,0"
            << "'4.5' is not a whole number";
        QTest::newRow("fractional sample")
            << 3 << "1,3,270,4,-1.25,100,50,0,reflex,0.3125,1.5,0,0,0,0,0,0,0,0,0,0,0,0"
            << "'1.5' is not a whole number";
        QTest::newRow("negative stop depth")
            << 2 << "1,3,270,4,-1.25,100,50,0,reflex,-0.5,0,0,0,0,0,0,0,0,0,0,0,0,0"
            << "is not an indentation";
        QTest::newRow("a short line inside") << 30 << "1,3,270"
                                             << "only the file's last line may be cut short";
    }
    void brokenFilesNameTheLineAndProblem() {
        QFETCH(int, line);
        QFETCH(QString, replacement);
        QFETCH(QString, problem);
        const std::string bad = corrupt(writeTaps(), line, replacement.toStdString());
        expectRefusedAt([&] { readTapCsv(bad, classes_); }, line, problem);
    }

    void tapRecordingCutShortKeepsItsFinishedTaps() {
        // A run stopped while writing its third tap, in the middle of a line: the two finished
        // taps are read and the cut is said; asked for whole taps only, the file is refused.
        const std::string path = writeTaps();
        const std::string cut = cutAfter(path, 1 + 2 * 50 + 20, 30, "cut.csv");
        std::string said;
        const auto taps = readTapCsv(cut, classes_, &said);
        QCOMPARE(int(taps.size()), 2);
        QCOMPARE(taps.back().record.tap.sampleCount(), 50);
        QVERIFY2(QString::fromStdString(said).contains("the last tap (set 3, class 13) has 20 of "
                                                       "50 samples"),
                 said.c_str());
        QVERIFY2(QString::fromStdString(said).contains("is cut off"), said.c_str());
        QVERIFY_THROWS_EXCEPTION(InputError, readTapCsv(cut, classes_));
        std::string none;
        QCOMPARE(int(readTapCsv(path, classes_, &none).size()), 3);
        QVERIFY(none.empty());
    }

    void tapsWithUnequalSamplesAreRefused() {
        // The first tap lost its last sample row: the taps no longer match.
        const std::string bad = corrupt(writeTaps(), 51, "");
        expectRefusedAt([&] { readTapCsv(bad, classes_); }, 101, "the first tap 49");
    }

    void followingRecordingsAreCheckedWhole() {
        const auto c = checkFollowingRecording(writeFollowing());
        QCOMPARE(c.taps, 5);
        QCOMPARE(c.trials, 2);
        QCOMPARE(c.samplesPerTap, 50);
        QVERIFY(c.cutOff.empty());
    }

    void followingRecordingReadsBackEveryTap() {
        // What a replay is served: each trial's taps in order with their pose, time, ending and
        // samples exactly as taken, and what the run perceived and decided at each.
        const auto taps = someTaps();
        FollowingRecordingContents c;
        const auto trials = readFollowingRecording(writeFollowing(), &c);
        QCOMPARE(c.taps, 5);
        QCOMPARE(int(trials.size()), 2);
        for (int trial = 1; trial <= 2; ++trial) {
            const RecordedTrial& r = trials[static_cast<std::size_t>(trial - 1)];
            QCOMPARE(r.label, std::string("rectangle"));
            QVERIFY(r.mode == FollowingMode::Active);
            QCOMPARE(r.trial, trial);
            QCOMPARE(int(r.taps.size()), 4 - trial);
            QCOMPARE(r.decisions.size(), r.taps.size());
            for (std::size_t i = 0; i < r.taps.size(); ++i) {
                const TapRecord& want = taps[i % 3].record;
                QCOMPARE(r.taps[i].pose.x, want.pose.x);
                QCOMPARE(r.taps[i].pose.y, want.pose.y);
                QCOMPARE(r.taps[i].startTime_s, want.startTime_s);
                QVERIFY(r.taps[i].ending == want.ending);
                QCOMPARE(r.taps[i].tap.taxels, 12);
                QVERIFY(r.taps[i].tap.samples == want.tap.samples);
                QCOMPARE(r.decisions[i].shapeClass, std::string("lower edge"));
                QCOMPARE(r.decisions[i].position, 9);
                QCOMPARE(r.decisions[i].rule, std::string(ruleFor(RuleId::FollowInRange).name));
            }
        }
        // Cut short in the first tap of a trial: that trial is not read at all.
        const std::string cut = cutAfter(writeFollowing(), 1 + 3 * 50 + 10, 0, "cut_first.csv");
        const auto kept = readFollowingRecording(cut);
        QCOMPARE(int(kept.size()), 1);
        QCOMPARE(int(kept.front().taps.size()), 3);
    }

    void followingRecordingCutShortKeepsItsFinishedTaps() {
        // A run stopped while writing leaves whole taps and a last one cut short, maybe in the
        // middle of a line: every finished tap is read and the cut is reported.
        // Lines before the cut: header, 3 taps, 20 rows of the fourth.
        const std::string cut = cutAfter(writeFollowing(), 1 + 3 * 50 + 20, 30, "cut.csv");
        const auto c = checkFollowingRecording(cut);
        QCOMPARE(c.taps, 3);
        QCOMPARE(c.trials, 1);
        QVERIFY2(QString::fromStdString(c.cutOff).contains("has 20 of 50 samples"),
                 c.cutOff.c_str());
        QVERIFY2(QString::fromStdString(c.cutOff).contains("is cut off"), c.cutOff.c_str());
    }

    void brokenFollowingRecordingsNameTheLineAndProblem_data() {
        QTest::addColumn<int>("line");
        QTest::addColumn<QString>("replacement");
        QTest::addColumn<QString>("problem");
        const QString row =
            "rectangle,active,1,0,100,50,0,reflex,1,lower edge,270,9,0,0,follow,"
            "2,0,0,0,%1,%2,0,0,0,0,0,0,0,0,0,0,0";
        QTest::newRow("wrong columns") << 1 << "shape,mode,x"
                                       << "unexpected columns";
        QTest::newRow("short line inside") << 30 << "rectangle,active,1"
                                           << "only the file's last line may be cut short";
        QTest::newRow("not a number") << 3 << row.arg(1).arg("a") << "'a' is not a number";
        QTest::newRow("NaN") << 3 << row.arg(1).arg("nan") << "not a finite number";
        QTest::newRow("above 255") << 3 << row.arg(1).arg(300) << "outside the fingertip's";
        QTest::newRow("sample out of order") << 3 << row.arg(5).arg(0) << "does not continue";
        QTest::newRow("bad mode") << 2 << QString(row.arg(0).arg(0)).replace(",active,", ",eager,")
                                  << "neither active";
        QTest::newRow("bad rule") << 2 << QString(row.arg(0).arg(0)).replace(",follow,", ",wander,")
                                  << "not a rule of the decision table";
        QTest::newRow("bad contact")
            << 2 << QString(row.arg(0).arg(0)).replace(",reflex,1,", ",reflex,2,")
            << "neither 0 nor 1";
        QTest::newRow("sample beyond any count")
            << 3 << row.arg("1e30").arg(0) << "'1e30' is not a whole number";
        QTest::newRow("fractional tap")
            << 2 << QString(row.arg(0).arg(0)).replace("active,1,0,", "active,1,0.5,")
            << "'0.5' is not a whole number";
        QTest::newRow("tap out of order")
            << 52 << QString(row.arg(0).arg(0)).replace("active,1,0,", "active,1,7,")
            << "a trial's taps run 0, 1, 2";
    }
    void brokenFollowingRecordingsNameTheLineAndProblem() {
        QFETCH(int, line);
        QFETCH(QString, replacement);
        QFETCH(QString, problem);
        const std::string bad = corrupt(writeFollowing(), line, replacement.toStdString());
        expectRefusedAt([&] { checkFollowingRecording(bad); }, line, problem);
    }

    void aFollowingRecordingGivenAsTrainingTapsIsNamed() {
        const std::string copy = corrupt(writeFollowing(), 0, "");  // line 0: none replaced
        expectRefusedAt([&] { readTapCsv(copy, classes_); }, 1,
                        "this is a contour-following recording; the training taps are in the "
                        "run's data/taps.csv");
    }

    void aWriteThatFailsStopsTheWriterAndKeepsWhatWasWritten() {
        // A disk that fills while taps are recorded: the tap that does not fit is refused naming
        // the file and why, and every tap written before it reads back whole.
        const auto taps = someTaps();
        const std::string one = dir_.filePath("one_tap.csv").toStdString();
        { TapCsvWriter(one, 12).append(taps[0], classes_); }
        const auto oneTap = std::filesystem::file_size(one);
        const std::string path = dir_.filePath("full.csv").toStdString();
        {
            TapCsvWriter w(path, 12);
            w.append(taps[0], classes_);
            FileSizeLimit limit(oneTap + 1000);  // room for a few rows of the second tap
            expectWriteRefused([&] { w.append(taps[1], classes_); }, path, "File too large");
        }
        std::string cut;
        const auto kept = readTapCsv(path, classes_, &cut);
        QCOMPARE(int(kept.size()), 1);
        QVERIFY(kept.front().record.tap.samples == taps[0].record.tap.samples);
        QVERIFY2(!cut.empty(), "the tap cut short is reported");

        const std::string following = dir_.filePath("full_following.csv").toStdString();
        {
            FollowingRecording w(following, 12);
            FollowedTap t;
            t.record = taps[0].record;
            t.decision = {RuleId::FollowInRange, {2.0, 0.0}, {}};
            w.append("rectangle", FollowingMode::Active, 1, 0, t);
            FileSizeLimit limit(std::filesystem::file_size(following) + 1000);
            expectWriteRefused([&] { w.append("rectangle", FollowingMode::Active, 1, 1, t); },
                               following, "File too large");
        }
        const auto c = checkFollowingRecording(following);
        QCOMPARE(c.taps, 1);
        QVERIFY(!c.cutOff.empty());
    }

    void aFullDiskIsNamedBeforeTheFirstTap() {
        // /dev/full takes no byte: the header already fails, before any tap is taken.
        if (!QFileInfo::exists("/dev/full")) QSKIP("this system has no /dev/full");
        expectWriteRefused([] { TapCsvWriter("/dev/full", 12); }, "/dev/full",
                           "No space left on device");
        expectWriteRefused([] { FollowingRecording("/dev/full", 12); }, "/dev/full",
                           "No space left on device");
        OutputFile table("/dev/full");
        table.print("a,b\n");
        expectWriteRefused([&] { table.close(); }, "/dev/full", "No space left on device");
        table.close();  // once closed, nothing more to report
    }

    void emptyAndMissingFiles() {
        const std::string empty = dir_.filePath("empty.csv").toStdString();
        std::ofstream(empty).close();
        QVERIFY_THROWS_EXCEPTION(InputError, readTapCsv(empty, classes_));
        QVERIFY_THROWS_EXCEPTION(InputError,
                                 readTapCsv(dir_.filePath("missing.csv").toStdString(), classes_));
        QVERIFY_THROWS_EXCEPTION(InputError, checkFollowingRecording(empty));
        QVERIFY_THROWS_EXCEPTION(
            InputError, checkFollowingRecording(dir_.filePath("missing.csv").toStdString()));
    }
};

QTEST_APPLESS_MAIN(TestTapCsv)
#include "test_tap_csv.moc"
