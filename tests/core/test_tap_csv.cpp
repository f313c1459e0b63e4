// Tap files: what is written reads back exactly, and a broken file is refused with its line.
#include <QTemporaryDir>
#include <QtTest>
#include <fstream>
#include <sstream>

#include "core/common/InputError.h"
#include "core/io/TapCsv.h"

using namespace activetouch;

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
            << 3 << "1,3,270,4,-1.25,100,50,0,reflex,1,a,0,0,0,0,0,0,0,0,0,0,0"
            << "'a' is not a number";
        QTest::newRow("NaN") << 3 << "1,3,270,4,-1.25,100,50,0,reflex,1,nan,0,0,0,0,0,0,0,0,0,0,0"
                             << "not a finite number";
        QTest::newRow("above 255")
            << 3 << "1,3,270,4,-1.25,100,50,0,reflex,1,300,0,0,0,0,0,0,0,0,0,0,0"
            << "outside the fingertip's 0..255";
        QTest::newRow("negative") << 3
                                  << "1,3,270,4,-1.25,100,50,0,reflex,1,-2,0,0,0,0,0,0,0,0,0,0,0"
                                  << "outside the fingertip's 0..255";
        QTest::newRow("class out of range")
            << 2 << "1,999,270,4,-1.25,100,50,0,reflex,0,0,0,0,0,0,0,0,0,0,0,0,0"
            << "class 999 is outside";
        QTest::newRow("sample out of order")
            << 4 << "1,3,270,4,-1.25,100,50,0,reflex,7,0,0,0,0,0,0,0,0,0,0,0,0"
            << "does not continue the tap";
        QTest::newRow("bad ending")
            << 2 << "1,3,270,4,-1.25,100,50,0,bounced,0,0,0,0,0,0,0,0,0,0,0,0,0"
            << "neither reflex nor stroke_limit";
    }
    void brokenFilesNameTheLineAndProblem() {
        QFETCH(int, line);
        QFETCH(QString, replacement);
        QFETCH(QString, problem);
        const std::string bad = corrupt(writeTaps(), line, replacement.toStdString());
        try {
            readTapCsv(bad, classes_);
            QFAIL("the broken file was accepted");
        } catch (const InputError& e) {
            const QString m = e.what();
            QVERIFY2(m.contains("bad.csv"), qPrintable(m));
            QVERIFY2(m.contains(QString("line %1").arg(line)), qPrintable(m));
            QVERIFY2(m.contains(problem), qPrintable(m));
        }
    }

    void emptyAndMissingFiles() {
        const std::string empty = dir_.filePath("empty.csv").toStdString();
        std::ofstream(empty).close();
        QVERIFY_THROWS_EXCEPTION(InputError, readTapCsv(empty, classes_));
        QVERIFY_THROWS_EXCEPTION(InputError,
                                 readTapCsv(dir_.filePath("missing.csv").toStdString(), classes_));
    }
};

QTEST_APPLESS_MAIN(TestTapCsv)
#include "test_tap_csv.moc"
