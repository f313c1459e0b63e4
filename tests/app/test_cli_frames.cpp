// Real skin recordings in a frames-table layout: the iCub grasp dataset's kept excerpt read with
// its layout, every number checked against the file's own text; lines that do not fit the layout
// refused by line; per-taxel statistics that find a dead taxel and a taxel's noise.
#include <QRegularExpression>
#include <algorithm>

#include "CliFixture.h"

namespace {

/// The pressures a grasp file holds, read from its text here: after the first line, 7 lines a
/// frame, lines 3-7 the five fingers' 12 readings, inverted from 255.
std::vector<std::vector<double>> framesOfText(const QString& path) {
    QFile f(path);
    f.open(QIODevice::ReadOnly);
    const QStringList lines = QString::fromUtf8(f.readAll()).split('\n', Qt::SkipEmptyParts);
    std::vector<std::vector<double>> frames;
    for (int i = 1; i + 7 <= lines.size(); i += 7) {
        std::vector<double> frame;
        for (int l = 2; l < 7; ++l)
            for (const QString& w : lines[i + l].split(' ', Qt::SkipEmptyParts))
                frame.push_back(255.0 - w.toDouble());
        frames.push_back(frame);
    }
    return frames;
}

}  // namespace

class TestCliFrames : public CliFixture {
    Q_OBJECT

private slots:
    void theGraspExcerptIsReadNumberForNumber() {
        const QString layout = sourceFile("experiments/layouts/icub_grasp_2012.json");
        QStringList files;
        for (const char* name : {"book_1", "none_1", "blue_bear_1"})
            files << sourceFile(QString("experiments/recordings/icub_grasp_2012/%1.txt").arg(name));
        const QString out = dir_.filePath("frames");
        const Outcome o =
            runCli(QStringList{"import-frames", layout} + files + QStringList{"--out", out});
        QVERIFY2(o.exitCode == 0, qPrintable(o.err));
        // Every row: file, frame, (no time), finger, 12 pressures, as the text says.
        const QStringList rows = linesOf(out + "/frames.csv");
        QCOMPARE(rows.front(), QString("file,frame,time_s,finger,taxel_0,taxel_1,taxel_2,taxel_3,"
                                       "taxel_4,taxel_5,taxel_6,taxel_7,taxel_8,taxel_9,"
                                       "taxel_10,taxel_11"));
        const QStringList fingers{"thumb", "index", "middle", "ring", "little"};
        int row = 1, total = 0;
        for (const QString& file : files) {
            const auto frames = framesOfText(file);
            QVERIFY(!frames.empty());
            total += int(frames.size());
            for (std::size_t t = 0; t < frames.size(); ++t)
                for (int g = 0; g < 5; ++g, ++row) {
                    const QStringList cells = rows[row].split(',');
                    QCOMPARE(cells[0], QFileInfo(file).fileName());
                    QCOMPARE(cells[1].toInt(), int(t));
                    QCOMPARE(cells[3], fingers[g]);
                    for (int k = 0; k < 12; ++k)
                        QCOMPARE(cells[4 + k].toDouble(), frames[t][std::size_t(12 * g + k)]);
                }
        }
        QCOMPARE(row, int(rows.size()));
        QVERIFY2(
            o.out.startsWith(QString("%1 frames of 60 taxels (5 fingers) from 3 files").arg(total)),
            qPrintable(o.out));
        const QJsonObject doc = readJson(out + "/frames.json");
        QCOMPARE(doc["files"].toArray().size(), 3);
        QCOMPARE(doc["files"].toArray()[0].toObject()["sha256"].toString().size(), 64);
        // Written again only when asked.
        QCOMPARE(runCli(QStringList{"import-frames", layout, files[0], "--out", out}).exitCode, 2);
        QCOMPARE(runCli(QStringList{"import-frames", layout, files[0], "--out", out, "--replace"})
                     .exitCode,
                 0);
    }

    void linesThatDoNotFitTheLayoutAreRefusedByLine_data() {
        QTest::addColumn<QString>("text");
        QTest::addColumn<QString>("expected");
        const QString frame =
            "1 2 3\n14 15 11 14 11\n" + QString("243 ").repeated(12).trimmed() + "\n";
        const QString rest = (QString("243 ").repeated(12).trimmed() + "\n").repeated(4);
        QTest::newRow("a short finger line")
            << "-10000\n" + frame + QString("243 ").repeated(11) + "\n" + rest.section('\n', 1)
            << "line 5: the index finger's taxels are columns 1..12 of the frame's line 4, but it "
               "has 11";
        QTest::newRow("a word") << "-10000\n" + frame + "243 x\n" + rest.section('\n', 1)
                                << "line 5: column 2 ('x') is not a number";
        QTest::newRow("past full scale")
            << "-10000\n" + frame + "300 " + QString("243 ").repeated(11) + "\n" +
                   rest.section('\n', 1)
            << "line 5: the index finger's taxel 0 reads 300, outside 0..255";
        QTest::newRow("a frame cut short")
            << "-10000\n" + frame + rest + frame << "line 9: the last frame has 3 of its 7 lines";
        QTest::newRow("nothing") << "-10000\n"
                                 << "holds no frame after its 1 header line(s)";
    }
    void linesThatDoNotFitTheLayoutAreRefusedByLine() {
        QFETCH(QString, text);
        QFETCH(QString, expected);
        const QString file = write("grasp.txt", text);
        const QString out = dir_.filePath("refused");
        const Outcome o =
            runCli({"import-frames", sourceFile("experiments/layouts/icub_grasp_2012.json"), file,
                    "--out", out});
        QCOMPARE(o.exitCode, 2);
        QVERIFY2(o.err.contains(file) && o.err.contains(expected), qPrintable(o.err));
        QVERIFY(!QFileInfo::exists(out + "/frames.csv"));
    }

    void statisticsFindTheNoiseAndADeadTaxel() {
        // Two recordings of 60 frames: index taxel 0 alternates 243/244 (sample SD 0.504, a step
        // of 1), taxel 1 reads 255 throughout (dead), the thumb is pressed in half the frames.
        QString text[2];
        for (int r = 0; r < 2; ++r) {
            text[r] = "-10000\n";
            for (int t = 0; t < 60; ++t) {
                text[r] += "0 0 0 0 0 0 0 0 0\n0 0 0 0 0\n";
                text[r] += QString(t % 2 ? "150 " : "243 ").repeated(12).trimmed() + "\n";
                text[r] += QString(t % 2 ? "244 255 " : "243 255 ") +
                           QString("243 ").repeated(10).trimmed() + "\n";
                text[r] += (QString("243 ").repeated(12).trimmed() + "\n").repeated(3);
            }
        }
        const QString in = dir_.filePath("synthetic");
        QCOMPARE(runCli({"import-frames", sourceFile("experiments/layouts/icub_grasp_2012.json"),
                         write("a.txt", text[0]), write("b.txt", text[1]), "--out", in})
                     .exitCode,
                 0);
        const QString out = dir_.filePath("stats");
        const Outcome o = runCli({"fingertip-stats", in, "--out", out});
        QVERIFY2(o.exitCode == 0, qPrintable(o.err));
        QVERIFY2(QRegularExpression("\\nindex +0 +120 +11\\.50 \\(11\\.50-11\\.50\\) +0\\.504 "
                                    "\\(0\\.504-0\\.504\\) +1 ")
                     .match(o.out)
                     .hasMatch(),
                 qPrintable(o.out));
        QVERIFY2(QRegularExpression("\\nindex +1 .* dead\\n").match(o.out).hasMatch(),
                 qPrintable(o.out));
        const QJsonObject stats = readJson(out + "/fingertip_stats.json");
        const QJsonArray taxels = stats["taxels"].toArray();
        QCOMPARE(taxels.size(), 60);
        const QJsonObject thumb0 = taxels[0].toObject();
        QCOMPARE(thumb0["max_counts"].toDouble(), 105.0);
        QCOMPARE(thumb0["contact_frames"].toInt(), 60);
        QCOMPARE(taxels[13].toObject()["dead"].toBool(), true);
    }

    void aMeasuredSceneIsWrittenAndComparedWithTheRealFingertip() {
        // The kept excerpt: the index finger's resting noise becomes the scene's, and the scene's
        // simulated fingertip at rest lies closer to the real one than the paper scene's does.
        QStringList files;
        for (const char* name : {"book_1", "none_1", "blue_bear_1"})
            files << sourceFile(QString("experiments/recordings/icub_grasp_2012/%1.txt").arg(name));
        const QString in = dir_.filePath("excerpt");
        QCOMPARE(runCli(QStringList{"import-frames",
                                    sourceFile("experiments/layouts/icub_grasp_2012.json")} +
                        files + QStringList{"--out", in})
                     .exitCode,
                 0);
        const QString scene = dir_.filePath("measured.json");
        const QString paper = sourceFile("experiments/scenes/paper_rectangle.json");
        const Outcome o = runCli({"fingertip-stats", in, "--out", dir_.filePath("excerpt_stats"),
                                  "--scenes", paper, "--write-scene", scene});
        QVERIFY2(o.exitCode == 0, qPrintable(o.err));
        const QJsonObject written = readJson(scene);
        QVERIFY(written["provenance"].toString().contains("clear-nus/icub_grasp_dataset"));
        double sigma = -1.0;
        for (const auto& e : written["effects"].toArray())
            if (e.toObject()["name"].toString() == "taxel_noise")
                sigma = e.toObject()["sigma_counts"].toDouble();
        std::vector<double> measured;
        for (const auto& t :
             readJson(dir_.filePath("excerpt_stats/fingertip_stats.json"))["taxels"].toArray())
            if (t.toObject()["finger"].toString() == "index")
                measured.push_back(t.toObject()["sigma_counts"].toObject()["mean"].toDouble());
        QCOMPARE(int(measured.size()), 12);
        std::sort(measured.begin(), measured.end());
        QVERIFY2(std::abs(sigma - 0.5 * (measured[5] + measured[6])) < 1e-3,
                 qPrintable(QString::number(sigma)));
        QCOMPARE(runCli({"check", scene}).exitCode, 0);
        for (const char* format : {"png", "pdf", "svg"})
            QVERIFY(
                QFileInfo(dir_.filePath("excerpt_stats/figures/fingertip_stats.") + format).size() >
                0);
        // One line per scene compared, the measured one closer on most taxels.
        const QRegularExpression line(
            "resting KS distance, index finger vs (\\S+), per taxel:"
            "(( [0-9.]+){12}) \\(([0-9]+) of 12 within 0\\.1\\)");
        auto it = line.globalMatch(o.out);
        QStringList scenes;
        std::vector<int> within;
        while (it.hasNext()) {
            const auto m = it.next();
            scenes << m.captured(1);
            within.push_back(m.captured(4).toInt());
        }
        QCOMPARE(scenes, (QStringList{paper, scene}));
        QVERIFY2(within[1] >= 10 && within[1] > within[0], qPrintable(o.out));
        // A finger the recordings do not have is refused naming those they have.
        const Outcome bad = runCli({"fingertip-stats", in, "--finger", "pinky"});
        QCOMPARE(bad.exitCode, 2);
        QVERIFY2(bad.err.contains("no finger 'pinky'") && bad.err.contains("thumb, index"),
                 qPrintable(bad.err));
    }
};

QTEST_MAIN(TestCliFrames)
#include "test_cli_frames.moc"
