// Every file a command reads, given as something that is no file a user meant: a pipe nobody
// writes to (which would block an open forever), /dev/zero (which never ends) and a one-line
// gigabyte (which a reader that takes whole lines would hold whole). Each is refused at once,
// naming it, within 2 s and 64 MiB, and an output folder claimed before it is left consistent
// (docs/limits.md, "Reading outside input").
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTcpServer>
#include <QTemporaryDir>
#include <QtTest>
#include <chrono>
#include <thread>

#include "support/Paths.h"

using activetouch::test::sourceFile;

using Environment = QMap<QString, QString>;
Q_DECLARE_METATYPE(Environment)

namespace {

struct Measured {
    int exitCode = -1;  ///< -1: a signal, or still running at the deadline (then killed)
    QString err;
    double seconds = 0;
    long maxRss_kib = 0;
};

/// Runs the CLI with `args` (and `env` added), as fork and exec, so that its own peak memory is
/// read from wait4; one still running after `limit_s` is killed. `onStart` runs in this process
/// once the child is started, with its pid.
Measured measure(const QStringList& args, const QMap<QString, QString>& env = {},
                 double limit_s = 20, const std::function<void(pid_t)>& onStart = nullptr) {
    QTemporaryFile err;
    err.open();
    const QByteArray cli = qgetenv("ACTIVETOUCH_CLI");
    std::vector<QByteArray> held{cli};
    for (const QString& a : args) held.push_back(a.toLocal8Bit());
    std::vector<char*> argv;
    for (QByteArray& a : held) argv.push_back(a.data());
    argv.push_back(nullptr);
    const int errFd = err.handle();
    const pid_t pid = ::fork();
    if (pid == 0) {
        for (auto it = env.begin(); it != env.end(); ++it)
            ::setenv(it.key().toLocal8Bit().constData(), it.value().toLocal8Bit().constData(), 1);
        ::dup2(errFd, 2);
        const int devNull = ::open("/dev/null", O_WRONLY);
        ::dup2(devNull, 1);
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    if (onStart) onStart(pid);
    QElapsedTimer t;
    t.start();
    int status = 0;
    rusage usage{};
    while (::wait4(pid, &status, WNOHANG, &usage) == 0) {
        if (t.elapsed() > limit_s * 1000) {
            ::kill(pid, SIGKILL);
            ::wait4(pid, &status, 0, &usage);
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    Measured m;
    m.seconds = t.elapsed() / 1000.0;
    m.maxRss_kib = usage.ru_maxrss;
    m.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    QFile e(err.fileName());
    e.open(QIODevice::ReadOnly);
    m.err = e.readAll();
    return m;
}

constexpr long kMemoryBound_kib = 64 * 1024;

}  // namespace

class TestFileArguments : public QObject {
    Q_OBJECT
    QTemporaryDir dir_;
    QString paper_, run_, map_, log_, onRig_;

    QString path(const QString& name) const { return dir_.filePath(name); }

    QString write(const QString& name, const QByteArray& text) {
        QFile f(path(name));
        if (!f.open(QIODevice::WriteOnly)) qFatal("cannot write %s", qPrintable(f.fileName()));
        f.write(text);
        return f.fileName();
    }

    /// `name` made as `kind`: a pipe, a link to /dev/zero, or a sparse one-line gigabyte.
    QString hostile(const QString& kind, const QString& name) {
        const QString p = path(kind + "_" + name);
        QFile::remove(p);
        if (kind == "fifo") {
            if (::mkfifo(QFile::encodeName(p).constData(), 0600) != 0) qFatal("mkfifo");
        } else if (kind == "zero") {
            if (!QFile::link("/dev/zero", p)) qFatal("link");
        } else {
            QFile f(p);
            if (!f.open(QIODevice::WriteOnly) || !f.resize(1000000000)) qFatal("resize");
        }
        return p;
    }

    /// A rig file whose fingertip asks the name server at 127.0.0.1:`port`.
    QString rigWithNameServerAt(const QString& name, quint16 port) {
        return write(name, QString(R"({"tapper": {"device": "nxt"}, "fingertip": {
            "device": "yarp", "name_server": "127.0.0.1", "name_server_port": %1}})")
                               .arg(port)
                               .toUtf8());
    }

    /// A folder whose run.json or seed_outcomes.json (`file`) is `hostile`.
    QString shardFolderWith(const QString& file, const QString& hostileFile) {
        const QString folder = path("shard_" + QFileInfo(hostileFile).fileName());
        QDir().mkpath(folder);
        QFile::remove(folder + "/" + file);
        QFile::link(hostileFile, folder + "/" + file);
        return folder;
    }

    /// A YARP conf folder whose yarp.conf is `hostileFile`.
    QString confHomeWith(const QString& hostileFile) {
        const QString home = path("yarp_" + QFileInfo(hostileFile).fileName());
        QDir().mkpath(home);
        QFile::remove(home + "/yarp.conf");
        QFile::link(hostileFile, home + "/yarp.conf");
        return home;
    }

    /// Every command and file argument, with `bad` in that argument's place.
    QList<QPair<QStringList, QMap<QString, QString>>> everyArgument(const QString& kind) {
        const QString out = path("out_" + kind);
        QList<QPair<QStringList, QMap<QString, QString>>> cases;
        auto add = [&](const QStringList& args, const QMap<QString, QString>& env = {}) {
            cases.append({args, env});
        };
        add({"check", hostile(kind, "experiment.json")});
        add({"check", hostile(kind, "taps.csv")});
        add({"run", hostile(kind, "run.json"), "--out", out + "_run", "--no-figures"});
        add({"run", paper_, "--rig", hostile(kind, "rig.json"), "--out", out + "_rig"});
        add({"seeds", hostile(kind, "seeds.json"), "--from", "1", "--to", "2", "--out",
             out + "_seeds", "--no-figures"});
        add({"compare", paper_, hostile(kind, "b.json"), "--from", "1", "--to", "2", "--out",
             out + "_cmp", "--no-figures"});
        add({"analyse", paper_, hostile(kind, "analyse.csv"), "--out", out + "_an",
             "--no-figures"});
        const QString replay = path("replay_" + kind);
        QDir().mkpath(replay + "/data");
        for (const char* name : {"taps.csv", "following_taps.csv"}) {
            QFile::remove(replay + "/data/" + name);
            QFile::link(hostile(kind, "replay_" + QString(name)), replay + "/data/" + name);
        }
        add({"replay", paper_, replay, "--out", out + "_rep", "--no-figures"});
        add({"import", paper_, hostile(kind, "data.log"), "--taxel-map", map_, "--out",
             out + "_i1"});
        add({"import", paper_, log_, "--taxel-map", hostile(kind, "map.txt"), "--out",
             out + "_i2"});
        add({"import", paper_, log_, "--taxel-map", map_, "--poses", hostile(kind, "poses.log"),
             "--out", out + "_i3"});
        add({"dump", paper_, hostile(kind, "dump.csv"), "--taxel-map", map_, "--out", out + "_d"});
        add({"calibrate", paper_, hostile(kind, "calibrate.csv"), "--out", out + "_c.json"});
        add({"calibrate", paper_, run_, "--scene", hostile(kind, "scene.json"), "--out",
             out + "_s.json"});
        add({"merge", shardFolderWith("seed_outcomes.json", hostile(kind, "outcomes.json")),
             "--out", out + "_m1"});
        const QString withManifest = shardFolderWith("run.json", hostile(kind, "manifest.json"));
        write(QDir(dir_.path()).relativeFilePath(withManifest + "/seed_outcomes.json"), "{}");
        add({"merge", withManifest, "--out", out + "_m2"});
        // The YARP conf file, read when the fingertip connects: the run's folder is already
        // claimed then, and must be left finished.
        const QString yarpRig = write("yarp_rig.json", R"({"tapper": {"device": "nxt"},
            "fingertip": {"device": "yarp"}})");
        add({"run", onRig_, "--rig", yarpRig, "--out", out + "_yarp", "--no-figures"},
            {{"YARP_CONFIG_HOME", confHomeWith(hostile(kind, "yarp.conf"))},
             {"YARP_NAMESPACE", "/root"}});
        return cases;
    }

    /// A folder a command claimed is finished (its run.json lists what it left) or was never
    /// made.
    void checkFolderConsistent(const QStringList& args) {
        const int at = args.indexOf("--out");
        if (at < 0) return;
        const QString out = args[at + 1];
        if (!QFileInfo(out).isDir()) return;
        QFile manifest(out + "/run.json");
        if (!manifest.exists()) {
            QVERIFY2(QDir(out).isEmpty(), qPrintable(out + " holds files but no run.json"));
            return;
        }
        QVERIFY(manifest.open(QIODevice::ReadOnly));
        const QJsonObject m = QJsonDocument::fromJson(manifest.readAll()).object();
        QVERIFY2(m["finished"].toBool(), qPrintable(out + "/run.json is not finished"));
        QVERIFY2(!QFile::exists(out + "/data/taps.csv"), "a tap was recorded");
    }

private slots:
    void initTestCase() {
        QVERIFY(dir_.isValid());
        paper_ = sourceFile("experiments/paper.json");
        run_ = path("paper_run");
        const Measured made = measure({"run", paper_, "--out", run_, "--no-figures"}, {}, 120);
        QVERIFY2(made.exitCode == 0, qPrintable(made.err));
        QString map = "values_per_frame 12\n";
        for (int k = 0; k < 12; ++k) map += QString("taxel %1 value %1\n").arg(k);
        map_ = write("map.txt", map.toUtf8());
        QByteArray log;
        for (int f = 0; f < 3; ++f) {
            log += QByteArray::number(f) + " " + QByteArray::number(f * 0.02) + " (";
            for (int k = 0; k < 12; ++k) log += (k ? " " : "") + QByteArray("0");
            log += ")\n";
        }
        log_ = write("data.log", log);
        // One trial on the rectangle: an experiment a rig with a real fingertip may run.
        onRig_ = write("on_the_rig.json", QString(R"({"extends": "%1", "name": "on_the_rig",
            "training": {"data_sets": 2}, "recognition": null, "following": {"trials": [
            {"mode": "active", "object": {"shape": "rectangle", "width_mm": 48, "height_mm": 58,
            "offset_mm": [150, 150], "top_height_mm": 10}}]}})")
                                              .arg(paper_)
                                              .toUtf8());
    }

    void everyFileArgumentRefusesAPipeAndAnEndlessFile_data() {
        QTest::addColumn<QStringList>("args");
        QTest::addColumn<Environment>("env");
        QTest::addColumn<QString>("named");
        for (const QString kind : {"fifo", "zero"})
            for (const auto& [args, env] : everyArgument(kind)) {
                QString named;
                for (const QString& a : args)
                    if (QFileInfo(a).fileName().startsWith(kind + "_")) named = a;
                if (named.isEmpty()) named = kind;  // inside a folder: the message names it
                QTest::newRow(qPrintable(kind + ": " + args.mid(0, 4).join(' ').right(90)))
                    << args << env << named;
            }
    }
    void everyFileArgumentRefusesAPipeAndAnEndlessFile() {
        QFETCH(QStringList, args);
        QFETCH(Environment, env);
        QFETCH(QString, named);
        const Measured m = measure(args, env);
        QVERIFY2(m.exitCode == 2 || m.exitCode == 1,
                 qPrintable(QString::number(m.exitCode) + m.err));
        QVERIFY2(m.seconds < 2.0, qPrintable(QString("took %1 s").arg(m.seconds)));
        QVERIFY2(m.maxRss_kib < kMemoryBound_kib,
                 qPrintable(QString("peaked at %1 MiB").arg(m.maxRss_kib / 1024)));
        QVERIFY2(m.err.contains("not a regular file") && m.err.contains(named),
                 qPrintable(m.err.left(1500)));
        checkFolderConsistent(args);
    }

    void aOneLineGigabyteIsRefusedWithinItsLineBound_data() {
        QTest::addColumn<QStringList>("args");
        const QString big = hostile("big", "one_line.csv");
        const QString bigLog = hostile("big", "one_line.log");
        QTest::newRow("check a recording") << QStringList{"check", big};
        QTest::newRow("analyse") << QStringList{"analyse", paper_,       big,
                                                "--out",   path("b_an"), "--no-figures"};
        QTest::newRow("calibrate")
            << QStringList{"calibrate", paper_, big, "--out", path("b_c.json")};
        QTest::newRow("dump") << QStringList{"dump", paper_,  big,        "--taxel-map",
                                             map_,   "--out", path("b_d")};
        QTest::newRow("import: skin log")
            << QStringList{"import", paper_, bigLog, "--taxel-map", map_, "--out", path("b_i1")};
        QTest::newRow("import: taxel map")
            << QStringList{"import", paper_, log_, "--taxel-map", bigLog, "--out", path("b_i2")};
        QTest::newRow("import: pose log") << QStringList{
            "import", paper_, log_, "--taxel-map", map_, "--poses", bigLog, "--out", path("b_i3")};
    }
    void aOneLineGigabyteIsRefusedWithinItsLineBound() {
        QFETCH(QStringList, args);
        const Measured m = measure(args);
        QCOMPARE(m.exitCode, 2);
        QVERIFY2(m.err.contains("line 1") && m.err.contains("longer than 64 KiB"),
                 qPrintable(m.err.left(1500)));
        QVERIFY2(m.maxRss_kib < kMemoryBound_kib,
                 qPrintable(QString("peaked at %1 MiB").arg(m.maxRss_kib / 1024)));
        checkFolderConsistent(args);
    }

    void ctrlCEndsAConnectWaitingOnASilentNameServerWithinASecond() {
        // A name server that takes the connection and never says a word: the fingertip would
        // wait out its timeouts; Ctrl-C ends the wait within a second, naming what it did.
        QTcpServer silent;
        QVERIFY(silent.listen(QHostAddress::LocalHost));
        const QString rig = rigWithNameServerAt("silent_rig.json", silent.serverPort());
        const QString out = path("silent");
        QElapsedTimer sinceInterrupt;
        const Measured m = measure({"run", onRig_, "--rig", rig, "--out", out, "--no-figures"}, {},
                                   20, [&](pid_t pid) {
                                       QVERIFY(silent.waitForNewConnection(10000));
                                       std::this_thread::sleep_for(std::chrono::milliseconds(200));
                                       ::kill(pid, SIGINT);
                                       sinceInterrupt.start();
                                   });
        const double afterInterrupt_s = sinceInterrupt.elapsed() / 1000.0;
        QCOMPARE(m.exitCode, 1);
        QVERIFY2(afterInterrupt_s < 1.0, qPrintable(QString("took %1 s").arg(afterInterrupt_s)));
        QVERIFY2(m.err.contains("stopped while connecting") && m.err.contains("was stopped"),
                 qPrintable(m.err));
        checkFolderConsistent({"--out", out});
    }

    void anUnwelcomingServerIsDescribedAsItBehaved() {
        // A server that closes at once and one that greets otherwise are told apart, and
        // neither is called a YARP name server that did not answer.
        QTcpServer server;
        QVERIFY(server.listen(QHostAddress::LocalHost));
        const QString rig = rigWithNameServerAt("closing_rig.json", server.serverPort());
        const auto closeAt = [&](const QByteArray& say) {
            return [&server, say](pid_t) {
                if (!server.waitForNewConnection(10000)) return;
                QTcpSocket* s = server.nextPendingConnection();
                if (!say.isEmpty()) {
                    s->write(say);
                    s->waitForBytesWritten(1000);
                }
                s->disconnectFromHost();
                s->waitForDisconnected(1000);
            };
        };
        const Measured closed =
            measure({"run", onRig_, "--rig", rig, "--out", path("closed"), "--no-figures"}, {}, 20,
                    closeAt({}));
        QCOMPARE(closed.exitCode, 1);
        QVERIFY2(closed.err.contains("closed it without a word"), qPrintable(closed.err));
        const Measured other =
            measure({"run", onRig_, "--rig", rig, "--out", path("other"), "--no-figures"}, {}, 20,
                    closeAt("SSH-2.0-OpenSSH_9.2\r\n"));
        QCOMPARE(other.exitCode, 1);
        QVERIFY2(other.err.contains("answered 'SSH-2.0-OpenSSH_9.2' instead of YARP's welcome"),
                 qPrintable(other.err));
        // Nobody listening: refused, said as such.
        const quint16 port = server.serverPort();
        server.close();
        Q_UNUSED(port);
        const Measured nobody =
            measure({"run", onRig_, "--rig", rig, "--out", path("nobody"), "--no-figures"});
        QCOMPARE(nobody.exitCode, 1);
        QVERIFY2(nobody.err.contains("cannot be reached") && nobody.err.contains("refused"),
                 qPrintable(nobody.err));
    }
};

QTEST_GUILESS_MAIN(TestFileArguments)
#include "test_file_arguments.moc"
