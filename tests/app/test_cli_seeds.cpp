// seeds and compare from the command line: rates over whole runs, the same rows on any number
// of cores, shards merged into what one run writes, two experiments compared trial by trial and
// one trial shown as each ran it; bad ranges and unpairable experiments refused.
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>

#include "CliFixture.h"

class TestCliSeeds : public CliFixture {
    Q_OBJECT

private slots:
    void shardsMergeIntoWhatOneRunWrites() {
        // seeds 1-30 of the paper in three shards, merged: the same rates.json, rates.csv and
        // seed outcomes as one run over every seed (figures drawn from the same rates).
        const QString paper = sourceFile("experiments/paper.json");
        QStringList shards;
        for (int k = 1; k <= 3; ++k) {
            shards << dir_.filePath(QString("shard%1").arg(k));
            const Outcome o =
                runCli({"seeds", paper, "--from", "1", "--to", "30", "--shard",
                        QString("%1/3").arg(k), "--out", shards.last(), "--no-figures"});
            QVERIFY2(o.exitCode == 0, qPrintable(o.err));
            QCOMPARE(linesIn(shards.last() + "/rates.csv"), 1 + 10);
        }
        const QString merged = dir_.filePath("merged"), whole = dir_.filePath("whole");
        const Outcome m =
            runCli({"merge", shards[0], shards[1], shards[2], "--out", merged, "--no-figures"});
        QVERIFY2(m.exitCode == 0, qPrintable(m.err));
        QVERIFY(
            runCli({"seeds", paper, "--from", "1", "--to", "30", "--out", whole, "--no-figures"})
                .exitCode == 0);
        for (const char* f : {"rates.json", "rates.csv", "seed_outcomes.json"}) {
            QFile a(merged + "/" + f), b(whole + "/" + f);
            QVERIFY(a.open(QIODevice::ReadOnly) && b.open(QIODevice::ReadOnly));
            QVERIFY2(a.readAll() == b.readAll(), f);
        }
        // Overlapping and missing shards are refused, naming the seeds and the folders.
        const Outcome twice = runCli(
            {"merge", shards[0], shards[1], shards[1], shards[2], "--out", dir_.filePath("twice")});
        QCOMPARE(twice.exitCode, 2);
        QVERIFY2(twice.err.contains("seeds 11-20 are in both " + shards[1]), qPrintable(twice.err));
        const Outcome gap = runCli({"merge", shards[0], shards[2], "--out", dir_.filePath("gap")});
        QCOMPARE(gap.exitCode, 2);
        QVERIFY2(gap.err.contains("seeds 11-20 of 1-30 are in no shard given"),
                 qPrintable(gap.err));
        QVERIFY(!QFileInfo::exists(dir_.filePath("gap")));
        // Shards of other settings never merge.
        const QString other = dir_.filePath("other_shard");
        QVERIFY(runCli({"seeds", sourceFile("experiments/paper_kernel.json"), "--from", "1", "--to",
                        "30", "--shard", "2/3", "--out", other, "--no-figures"})
                    .exitCode == 0);
        const Outcome mixed =
            runCli({"merge", shards[0], other, shards[2], "--out", dir_.filePath("mixed")});
        QCOMPARE(mixed.exitCode, 2);
        QVERIFY2(mixed.err.contains(other) && mixed.err.contains("other settings"),
                 qPrintable(mixed.err));
        QCOMPARE(runCli({"seeds", paper, "--from", "1", "--to", "3", "--shard", "4/3"}).exitCode,
                 2);
    }

    void comparisonShardsMergeIntoWhatOneComparisonWrites() {
        // compare --shard k/3 on three machines, merged: the files of one compare over 1-6.
        const QString a = sourceFile("experiments/paper.json");
        const QString b = sourceFile("experiments/paper_kernel.json");
        QStringList shards;
        for (int k = 1; k <= 3; ++k) {
            shards << dir_.filePath(QString("cmp_shard%1").arg(k));
            const Outcome o =
                runCli({"compare", a, b, "--from", "1", "--to", "6", "--shard",
                        QString("%1/3").arg(k), "--out", shards.back(), "--no-figures"});
            QVERIFY2(o.exitCode == 0, qPrintable(o.err));
        }
        const QString merged = dir_.filePath("cmp_merged"), whole = dir_.filePath("cmp_whole");
        const Outcome m = runCli({"merge", shards[2], shards[0], shards[1], "--out", merged});
        QVERIFY2(m.exitCode == 0, qPrintable(m.err));
        QVERIFY(QFile::exists(merged + "/figures/compare.png"));
        QVERIFY(
            runCli({"compare", a, b, "--from", "1", "--to", "6", "--out", whole, "--no-figures"})
                .exitCode == 0);
        for (const char* file : {"compare.csv", "compare_so_far.csv", "compare.json"})
            QVERIFY2(linesOf(merged + "/" + file) == linesOf(whole + "/" + file), file);
        // A missing shard, one given twice, or a seeds shard among them is refused by name.
        const Outcome gap = runCli({"merge", shards[0], shards[2], "--out", dir_.filePath("g")});
        QCOMPARE(gap.exitCode, 2);
        QVERIFY2(gap.err.contains("seeds 3-4 of 1-6 are in no shard given"), qPrintable(gap.err));
        const Outcome twice = runCli(
            {"merge", shards[0], shards[1], shards[1], shards[2], "--out", dir_.filePath("t")});
        QCOMPARE(twice.exitCode, 2);
        QVERIFY2(twice.err.contains("seeds 3-4 are in both " + shards[1]), qPrintable(twice.err));
    }

    void seedsReportsRatesOverWholeRuns() {
        // Three whole runs: a row per seed, totals with 95 % intervals, and each seed's outcome
        // the same as that seed's own run.
        const QString out = dir_.filePath("rates");
        const Outcome o = runCli({"seeds", sourceFile("experiments/paper.json"), "--from", "2",
                                  "--to", "4", "--out", out});
        QCOMPARE(o.exitCode, 0);
        QVERIFY2(o.out.contains("active trials completed"), qPrintable(o.out));
        QFile csv(out + "/rates.csv");
        QVERIFY(csv.open(QIODevice::ReadOnly));
        const QStringList rows = QString(csv.readAll()).trimmed().split('\n');
        QCOMPARE(rows.size(), 4);  // header + seeds 2, 3, 4
        QVERIFY(rows[0].endsWith(
            ",paper_result_smoothed,active_failures,misnamed_paths,passive_not_lost_at_a_corner,"
            "run_failure,trials_not_run"));
        QVERIFY(
            rows[0].startsWith("seed,passive_trials,passive_lost,passive_lost_at_a_corner,"
                               "active_trials,"));
        int completed = 0, whole = 0;
        for (int i = 1; i < rows.size(); ++i) {
            const QStringList c = rows[i].split(',');
            QCOMPARE(c[0].toInt(), i + 1);
            QVERIFY(c[3].toInt() <= c[2].toInt());  // lost at a corner, of the lost
            QCOMPARE(c[4].toInt(), 8);
            completed += c[5].toInt();
            // The paper's result whole: all passive lost at a corner, all active completed and
            // recognised.
            QCOMPARE(c[6], c[5]);  // recognition looks at every completed active path
            const bool paper = c[3] == c[1] && c[5] == c[4] && c[7] == c[6];
            QVERIFY2(QRegularExpression("^\\d+-\\d+$").match(c[14]).hasMatch(), qPrintable(c[14]));
            QCOMPARE(c[15], QString::number(int(paper)));
            const bool smoothed = c[3] == c[1] && c[5] == c[4] && c[8] == c[6];
            QCOMPARE(c[16], QString::number(int(smoothed)));
            whole += paper;
        }
        QFile js(out + "/rates.json");
        QVERIFY(js.open(QIODevice::ReadOnly));
        const QJsonObject r = QJsonDocument::fromJson(js.readAll()).object();
        QCOMPARE(r["runs"].toInt(), 3);
        const QJsonObject active = r["active_completed"].toObject();
        QCOMPARE(active["total"].toInt(), 24);
        QCOMPARE(active["count"].toInt(), completed);
        const QJsonArray ci = active["ci95"].toArray();
        QVERIFY(ci[0].toDouble() <= active["rate"].toDouble());
        QVERIFY(ci[1].toDouble() >= active["rate"].toDouble());
        QVERIFY(ci[1].toDouble() - ci[0].toDouble() > 0.05);  // 24 trials cannot pin a rate down
        QCOMPARE(r["passive_lost"].toObject()["total"].toInt(), 6);
        QCOMPARE(r["paper_result"].toObject()["count"].toInt(), whole);
        QCOMPARE(r["paper_result"].toObject()["total"].toInt(), 3);
        QCOMPARE(r["paper_result_short_by"].toObject()["runs"].toInt(), 3 - whole);
        // Recognition over the runs: each completed active path in one cell, traced x named.
        const QJsonObject confusion = r["recognition_confusion"].toObject();
        QCOMPARE(confusion["labels"].toArray().size(), 4);
        for (const char* rule : {"paper_rule", "smoothed"}) {
            int paths = 0;
            for (const auto& row : confusion[rule].toArray())
                for (const auto& n : row.toArray()) paths += n.toInt();
            QCOMPARE(paths, completed);
        }
        QVERIFY2(o.out.contains("runs with the paper's result whole"), qPrintable(o.out));
        // The figure: each seed's outcome and the rates so far, as a paper would print it.
        for (const char* ext : {"png", "pdf", "svg"})
            QVERIFY2(QFileInfo(out + "/figures/seed_rates." + ext).size() > 0, ext);
        QFile png(out + "/figures/seed_rates.png");
        QVERIFY(png.open(QIODevice::ReadOnly));
        const QByteArray head = png.read(24);
        QVERIFY(head.startsWith("\x89PNG"));
        const auto byte = [&](int i) { return quint32(quint8(head[i])); };
        // A double-column figure (178 mm) at 300 dpi.
        QCOMPARE(byte(16) << 24 | byte(17) << 16 | byte(18) << 8 | byte(19), 2102u);  // width

        const QString single = dir_.filePath("seed3");
        QCOMPARE(runCli({"run", sourceFile("experiments/paper.json"), "--out", single, "--seed",
                         "3", "--no-figures"})
                     .exitCode,
                 0);
        QFile summary(single + "/summary.json");
        QVERIFY(summary.open(QIODevice::ReadOnly));
        int singleCompleted = 0;
        const QJsonArray following =
            QJsonDocument::fromJson(summary.readAll()).object()["following"].toArray();
        for (const auto& t : following)
            singleCompleted +=
                t.toObject()["mode"].toString() == "active" && t.toObject()["completed"].toBool();
        QCOMPARE(rows[2].split(',')[5].toInt(), singleCompleted);
    }

    void compareRunsTwoExperimentsTrialByTrial() {
        // The paper against its kernel variant on seeds 3 and 4: a row per paired trial, the
        // rates of each side and the disagreements, in the order the paper runs its trials.
        const QString out = dir_.filePath("compare");
        const Outcome o = runCli({"compare", sourceFile("experiments/paper.json"),
                                  sourceFile("experiments/paper_kernel.json"), "--from", "3",
                                  "--to", "4", "--out", out});
        QCOMPARE(o.exitCode, 0);
        QVERIFY2(o.out.contains("A = paper, B = paper_kernel, 2 seeds, trial by trial:"),
                 qPrintable(o.out));
        QVERIFY2(o.out.contains("active trials completed") && o.out.contains("McNemar p"),
                 qPrintable(o.out));
        const QStringList rows = linesOf(out + "/compare.csv");
        QCOMPARE(rows.size(), 1 + 2 * 10);
        QCOMPARE(rows[0], QString("seed,mode,label,trial,outcome_a,outcome_b,named_a,named_b"));
        QVERIFY2(rows[1].startsWith("3,passive,\"rectangle\",1,"), qPrintable(rows[1]));
        QVERIFY2(rows[3].startsWith("3,active,\"rectangle\",1,completed,"), qPrintable(rows[3]));
        const QJsonObject c = readJson(out + "/compare.json");
        QCOMPARE(c["seeds"].toInt(), 2);
        const QJsonObject active = c["active_completed"].toObject();
        QCOMPARE(active["pairs"].toInt(), 16);
        QCOMPARE(active["both"].toInt() + active["only_a"].toInt() + active["only_b"].toInt() +
                     active["neither"].toInt(),
                 16);
        QVERIFY(active["mcnemar_p"].toDouble() > 0.0 && active["mcnemar_p"].toDouble() <= 1.0);
        // Each side's count is what that experiment's own seeds run gives.
        const QString seedsOut = dir_.filePath("compare_seeds");
        QCOMPARE(runCli({"seeds", sourceFile("experiments/paper_kernel.json"), "--from", "3",
                         "--to", "4", "--out", seedsOut, "--no-figures"})
                     .exitCode,
                 0);
        const QJsonObject kernel = readJson(seedsOut + "/rates.json");
        QCOMPARE(active["b"].toObject()["count"].toInt(),
                 kernel["active_completed"].toObject()["count"].toInt());
        for (const char* format : {"png", "pdf", "svg"})
            QVERIFY(QFileInfo(out + "/figures/compare." + format).size() > 0);
        // How each part stood after each seed; after the last, as compare.json has it.
        const QStringList soFar = linesOf(out + "/compare_so_far.csv");
        QCOMPARE(soFar.size(), 1 + 2 * 4);
        QCOMPARE(soFar[0], QString("seeds_compared,seed,part,pairs,a,b,only_a,only_b,"
                                   "difference_b_minus_a,ci95_low,ci95_high,mcnemar_p"));
        QVERIFY2(soFar[1].startsWith("1,3,active_completed,8,"), qPrintable(soFar[1]));
        for (int i = 5; i < 9; ++i) {
            const QStringList f = soFar[i].split(',');
            QCOMPARE(f[0], QString("2"));
            QCOMPARE(f[1], QString("4"));
            const QJsonObject part = c[f[2]].toObject();
            QVERIFY2(!part.isEmpty(), qPrintable(f[2]));
            QCOMPARE(f[3].toInt(), part["pairs"].toInt());
            QCOMPARE(f[6].toInt(), part["only_a"].toInt());
            QCOMPARE(f[7].toInt(), part["only_b"].toInt());
            QVERIFY(qAbs(f[8].toDouble() - part["difference_b_minus_a"].toDouble()) < 1e-5);
        }
    }

    void compareShowsOneTrialAsEachExperimentRanIt() {
        // The first trial of seed 3 the two ended differently, named by its compare.csv row.
        const QString out = dir_.filePath("compare_show");
        const QStringList common = {"compare", sourceFile("experiments/paper.json"),
                                    sourceFile("experiments/paper_kernel.json"), "--out", out};
        QCOMPARE(runCli(common + QStringList{"--from", "3", "--to", "3", "--no-figures"}).exitCode,
                 0);
        QStringList differing;
        for (const QString& row : linesOf(out + "/compare.csv").mid(1)) {
            const QStringList f = row.split(',');
            if (f[4] != f[5] || f[6] != f[7]) {
                differing = f;
                break;
            }
        }
        QVERIFY2(!differing.isEmpty(), "seed 3 has a trial the two ended differently");
        const QString ref = differing.mid(0, 4).join(',');  // as the row has it, label quoted
        const Outcome o = runCli(common + QStringList{"--show", ref});
        QCOMPARE(o.exitCode, 0);
        const QString label = differing[2].mid(1, differing[2].size() - 2);
        QVERIFY2(o.out.contains(QString("seed 3, %1 trial %2 of %3, as each experiment ran it")
                                    .arg(differing[1], differing[3], label)),
                 qPrintable(o.out));
        // It says how each ended as compare.csv does.
        const auto ended = [](const QString& outcome, const QString& named) {
            return named.isEmpty() ? outcome : outcome + ", named " + named;
        };
        QVERIFY2(o.out.contains(QString("a %1; b %2")
                                    .arg(ended(differing[4], differing[6]),
                                         ended(differing[5], differing[7]))),
                 qPrintable(o.out));
        // Its table holds A's trial tap for tap as A's own run of that seed recorded it.
        const QString stem =
            QString("trial_pair_seed3_%1_%2_%3").arg(differing[1], label, differing[3]);
        const QStringList pair = linesOf(out + "/" + stem + ".csv");
        QVERIFY(pair.size() > 2);
        QVERIFY(pair[0].startsWith("side,experiment,tap,x_mm,y_mm,"));
        const QString runOut = dir_.filePath("compare_show_run");
        QCOMPARE(runCli({"run", sourceFile("experiments/paper.json"), "--seed", "3", "--out",
                         runOut, "--no-figures"})
                     .exitCode,
                 0);
        QStringList fromRun, fromPair, sides;
        const QString trialPrefix = QString("%1,%2,%3,").arg(label, differing[1], differing[3]);
        for (const QString& row : linesOf(runOut + "/data/following_paths.csv"))
            if (row.startsWith(trialPrefix)) fromRun << row.mid(trialPrefix.size());
        for (const QString& row : pair.mid(1)) {
            const QStringList f = row.split(',');
            if (!sides.contains(f[0])) sides << f[0];
            if (f[0] == "a") {
                QCOMPARE(f[1], QString("\"paper\""));
                fromPair << f.mid(2).join(',');
            } else {
                QCOMPARE(f[1], QString("\"paper_kernel\""));
            }
        }
        QCOMPARE(sides, QStringList({"a", "b"}));
        QVERIFY(!fromRun.isEmpty());
        QCOMPARE(fromPair, fromRun);
        for (const char* format : {"png", "pdf", "svg"})
            QVERIFY(QFileInfo(out + "/figures/" + stem + "." + format).size() > 0);

        // A trial either lacks, a malformed name and a seed range beside it are refused.
        const Outcome missing = runCli(common + QStringList{"--show", "3,active,cross,3"});
        QCOMPARE(missing.exitCode, 2);
        QVERIFY2(missing.err.contains("experiments/paper.json") &&
                     missing.err.contains("'paper' has no active trial 3 of 'cross'"),
                 qPrintable(missing.err));
        QVERIFY(!QFile::exists(out + "/trial_pair_seed3_active_cross_3.csv"));
        const Outcome malformed = runCli(common + QStringList{"--show", "3,active,cross"});
        QCOMPARE(malformed.exitCode, 2);
        QVERIFY2(malformed.err.contains("give seed,mode,label,trial"), qPrintable(malformed.err));
        const Outcome both =
            runCli(common + QStringList{"--show", "3,active,cross,2", "--from", "1", "--to", "2"});
        QCOMPARE(both.exitCode, 2);
        QVERIFY2(both.err.contains("leave out --from, --to and --jobs"), qPrintable(both.err));
        const Outcome jobs =
            runCli(common + QStringList{"--show", "3,active,cross,2", "--jobs", "2"});
        QCOMPARE(jobs.exitCode, 2);
    }

    void compareRefusesWhatItCannotPair() {
        const QString out = dir_.filePath("compare_bad");
        const Outcome one =
            runCli({"compare", sourceFile("experiments/paper.json"), "--from", "1", "--to", "2"});
        QCOMPARE(one.exitCode, 2);
        QVERIFY2(one.err.contains("compare needs a second experiment"), qPrintable(one.err));
        const Outcome noRange = runCli({"compare", sourceFile("experiments/paper.json"),
                                        sourceFile("experiments/paper_kernel.json")});
        QCOMPARE(noRange.exitCode, 2);
        QVERIFY2(noRange.err.contains("--from and --to"), qPrintable(noRange.err));
        // An experiment whose trials the paper does not have: nothing to compare.
        const QString other =
            write("other_trials.json",
                  QString(R"({"extends": "%1", "name": "other_trials", "following": {"trials": [
                {"label": "mine", "mode": "active", "object": {"shape": "rectangle",
                "width_mm": 48, "height_mm": 58, "offset_mm": [150, 150]}}]}})")
                      .arg(sourceFile("experiments/paper.json")));
        const Outcome none = runCli({"compare", sourceFile("experiments/paper.json"), other,
                                     "--from", "1", "--to", "2", "--out", out});
        QCOMPARE(none.exitCode, 2);
        QVERIFY2(none.err.contains("no trial of 'other_trials' has a namesake in 'paper'"),
                 qPrintable(none.err));
        QVERIFY(!QFile::exists(out + "/compare.csv"));
    }

    void seedsRefusesABadRange() {
        const QString out = dir_.filePath("badrange");
        const Outcome back = runCli({"seeds", sourceFile("experiments/paper.json"), "--from", "3",
                                     "--to", "1", "--out", out});
        QCOMPARE(back.exitCode, 2);
        QVERIFY2(back.err.contains("--from 3 is after --to 1"), qPrintable(back.err));
        const Outcome missing =
            runCli({"seeds", sourceFile("experiments/paper.json"), "--from", "1", "--out", out});
        QCOMPARE(missing.exitCode, 2);
        QVERIFY2(missing.err.contains("--from and --to"), qPrintable(missing.err));
        const Outcome word = runCli({"seeds", sourceFile("experiments/paper.json"), "--from", "one",
                                     "--to", "2", "--out", out});
        QCOMPARE(word.exitCode, 2);
        const Outcome none = runCli({"seeds", sourceFile("experiments/paper.json"), "--from", "1",
                                     "--to", "2", "--jobs", "0", "--out", out});
        QCOMPARE(none.exitCode, 2);
        QVERIFY2(none.err.contains("--jobs 0 cannot run seeds"), qPrintable(none.err));
        QVERIFY(!QFile::exists(out + "/rates.csv"));
    }

    void seedsGiveTheSameRowsOnAnyNumberOfCores() {
        // One seed after another, or three at a time: the same rows, in seed order, and the same
        // report.
        QStringList reports;
        for (const char* jobs : {"1", "3"}) {
            const QString out = dir_.filePath(QString("rates_jobs%1").arg(jobs));
            const Outcome o = runCli({"seeds", sourceFile("experiments/paper.json"), "--from", "1",
                                      "--to", "5", "--jobs", jobs, "--out", out, "--no-figures"});
            QCOMPARE(o.exitCode, 0);
            reports << o.out.section("wall time", 0, 0);
        }
        QCOMPARE(reports[1], reports[0]);
        QCOMPARE(linesOf(dir_.filePath("rates_jobs3/rates.csv")),
                 linesOf(dir_.filePath("rates_jobs1/rates.csv")));
        QCOMPARE(linesOf(dir_.filePath("rates_jobs3/rates.csv")).size(), 6);
    }

    void seedsWithoutFiguresWritesOnlyTheTables() {
        const QString out = dir_.filePath("rates_nofig");
        const Outcome o = runCli({"seeds", sourceFile("experiments/paper.json"), "--from", "5",
                                  "--to", "5", "--out", out, "--no-figures"});
        QCOMPARE(o.exitCode, 0);
        QVERIFY(QFile::exists(out + "/rates.csv") && QFile::exists(out + "/rates.json"));
        QVERIFY(!QFile::exists(out + "/figures/seed_rates.png"));
    }

    void sweepsOverSeedsMergeAndPairWithThePaper() {
        // A small accuracy-versus-time experiment over seeds 1-4: the sweep tables over seeds,
        // their figures, and two shards merged into exactly what one run writes.
        QFile base(sourceFile("experiments/accuracy_vs_time.json"));
        QVERIFY(base.open(QIODevice::ReadOnly));
        QJsonObject spec = QJsonDocument::fromJson(base.readAll()).object();
        spec["name"] = "small_sweeps";
        spec["scene"] = sourceFile("experiments/scenes/paper_rectangle.json");
        spec["sweeps"] = QJsonDocument::fromJson(R"({
            "perception": {"belief_thresholds": [0.9, 0.99], "taps_per_class": 3,
                           "max_taps_per_decision": 6},
            "following": {"follow_steps_mm": [2, 3], "reposition_steps_mm": [1],
                          "belief_thresholds": [0], "modes": ["active"], "repeats": 1}})")
                             .object();
        const QString path = dir_.filePath("small_sweeps.json");
        QFile out(path);
        QVERIFY(out.open(QIODevice::WriteOnly));
        out.write(QJsonDocument(spec).toJson());
        out.close();
        const QString whole = dir_.filePath("sweeps_whole");
        const Outcome o = runCli({"seeds", path, "--from", "1", "--to", "4", "--out", whole});
        QVERIFY2(o.exitCode == 0, qPrintable(o.err));
        QVERIFY2(o.out.contains("accuracy-versus-time sweeps over 4 seeds"), qPrintable(o.out));
        QVERIFY(o.out.contains("beat the paper's setting in robot time at no loss of completion:"));
        // One row per threshold and the single tap; one per following setting.
        QCOMPARE(linesOf(whole + "/sweeps_perception.csv").size(), 1 + 3);
        QCOMPARE(linesOf(whole + "/sweeps_following.csv").size(), 1 + 2);
        QVERIFY(linesOf(whole + "/sweeps_perception.csv")[1].startsWith("single_tap,4,"));
        for (const char* figure : {"sweeps_perception.png", "sweeps_following_pareto.pdf"})
            QVERIFY2(QFile::exists(whole + "/figures/" + figure), figure);
        QFile rates(whole + "/rates.json");
        QVERIFY(rates.open(QIODevice::ReadOnly));
        const QJsonObject sweeps =
            QJsonDocument::fromJson(rates.readAll()).object()["sweeps"].toObject();
        QCOMPARE(sweeps["seeds"].toInt(), 4);
        const QJsonArray following = sweeps["following"].toArray();
        QVERIFY(following[0].toObject()["paper_setting"].toBool());
        QVERIFY(!following[0].toObject().contains("against_paper_setting"));
        QVERIFY(
            following[1].toObject()["against_paper_setting"].toObject().contains("beats_paper"));

        QStringList shards;
        for (int k = 1; k <= 2; ++k) {
            shards << dir_.filePath(QString("sweeps_shard%1").arg(k));
            QCOMPARE(runCli({"seeds", path, "--from", "1", "--to", "4", "--shard",
                             QString("%1/2").arg(k), "--out", shards.last(), "--no-figures"})
                         .exitCode,
                     0);
        }
        const QString merged = dir_.filePath("sweeps_merged");
        QCOMPARE(runCli({"merge", shards[0], shards[1], "--out", merged, "--no-figures"}).exitCode,
                 0);
        // (Sweep (c) times the classifier on this machine, so it is left out: its microseconds
        // differ from run to run.)
        for (const char* f :
             {"rates.json", "seed_outcomes.json", "sweeps_perception.csv", "sweeps_following.csv"})
            QVERIFY2(linesOf(merged + "/" + f) == linesOf(whole + "/" + f), f);
    }
};

QTEST_GUILESS_MAIN(TestCliSeeds)
#include "test_cli_seeds.moc"
