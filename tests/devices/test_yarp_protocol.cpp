// The YARP codecs: name-server replies, text and binary data (both tag versions, with and without
// an envelope, 'd' and 'D'), a fingertip out of the hand vector, and skinManager compensation.
#include <sys/stat.h>

#include <QElapsedTimer>
#include <QtTest>
#include <cstring>

#include "devices/yarp/YarpConf.h"
#include "devices/yarp/YarpProtocol.h"

using namespace activetouch::yarp;
Q_DECLARE_METATYPE(std::vector<std::int32_t>)

namespace {
std::string fromHex(const char* hex) {
    return QByteArray::fromHex(hex).toStdString();
}

/// Every event `bytes` gives, fed in chunks of `chunk` bytes.
std::vector<StreamDecoder::Event> decodeInChunks(const std::string& bytes, std::size_t chunk) {
    StreamDecoder d(true);
    std::vector<StreamDecoder::Event> events;
    for (std::size_t at = 0; at < bytes.size(); at += chunk)
        for (auto& e : d.feed(bytes.data() + at, std::min(chunk, bytes.size() - at)))
            events.push_back(e);
    return events;
}

std::vector<std::uint8_t> binaryVector(std::int32_t tag, const std::vector<double>& values,
                                       bool asFloat) {
    std::vector<std::uint8_t> p(8);
    const auto n = static_cast<std::int32_t>(values.size());
    std::memcpy(p.data(), &tag, 4);
    std::memcpy(p.data() + 4, &n, 4);
    for (double v : values) {
        const std::size_t at = p.size();
        if (asFloat) {
            const float f = static_cast<float>(v);
            p.resize(at + 4);
            std::memcpy(p.data() + at, &f, 4);
        } else {
            p.resize(at + 8);
            std::memcpy(p.data() + at, &v, 8);
        }
    }
    return p;
}
}  // namespace

class TestYarpProtocol : public QObject {
    Q_OBJECT
private slots:
    void nameServer() {
        QCOMPARE(QString::fromStdString(nameServerGreeting()), QString("CONNACK extern\n"));
        QCOMPARE(QString::fromStdString(nameServerQuery("/icub/skin/right_hand_comp")),
                 QString("d\nquery /icub/skin/right_hand_comp\n"));
        const auto r = parseRegistration(
            {"registration name /icub/skin/right_hand_comp ip 10.0.0.2 port 10012 type tcp\n",
             "*** end of message\n"});
        QVERIFY(r.has_value());
        QCOMPARE(QString::fromStdString(r->host), QString("10.0.0.2"));
        QCOMPARE(r->tcpPort, 10012);
        QCOMPARE(QString::fromStdString(r->carrier), QString("tcp"));
        QVERIFY(!parseRegistration({"*** end of message"}).has_value());  // unknown port
        QVERIFY_THROWS_EXCEPTION(
            YarpError, parseRegistration({"registration name /x ip 1.2.3.4"}));  // cut short
        QVERIFY_THROWS_EXCEPTION(
            YarpError, parseRegistration({"registration name /x ip 1.2.3.4 port 99999 type tcp",
                                          "*** end of message"}));
    }

    void textCarrier_data() {
        QTest::addColumn<QString>("header");
        QTest::addColumn<bool>("isHeader");
        QTest::newRow("d") << "d" << true;
        QTest::newRow("do") << "do\r\n" << true;
        QTest::newRow("D with envelope") << "D 1523 1700000000.25" << true;
        QTest::newRow("do with envelope") << "do 12 3.4" << true;
        QTest::newRow("data line") << "235 234 236" << false;
        QTest::newRow("dog") << "dog" << false;
        QTest::newRow("empty") << "" << false;
    }
    void textCarrier() {
        QFETCH(QString, header);
        QFETCH(bool, isHeader);
        QCOMPARE(isMessageHeader(header.toStdString()), isHeader);
    }

    void dataLinesAndFingertips() {
        std::string line;
        for (int i = 0; i < 192; ++i) line += std::to_string(i) + ".5 ";
        const auto hand = parseDataLine(line);
        QCOMPARE(int(hand.size()), 192);
        const auto thumb = fingertipTaxels(hand, Finger::Thumb);
        QCOMPARE(int(thumb.size()), 12);
        QCOMPARE(thumb.front(), 48.5);
        QCOMPARE(fingertipTaxels(hand, Finger::Index).back(), 11.5);
        QVERIFY_THROWS_EXCEPTION(YarpError, parseDataLine("1 2 three"));
        QVERIFY_THROWS_EXCEPTION(YarpError, parseDataLine("1 nan 3"));
        QVERIFY_THROWS_EXCEPTION(YarpError, fingertipTaxels(std::vector<double>(191, 0.0),
                                                            Finger::Index));  // wrong size
    }

    void binaryVectorsOfBothTags() {
        const std::vector<double> values{1.5, -2.25, 235.0};
        QVERIFY(parseBinaryVector(binaryVector(0x10A, values, false)) ==
                values);  // YARP <= 3.12 doubles
        QVERIFY(parseBinaryVector(binaryVector(0x114, values, false)) == values);  // YARP 4 doubles
        QVERIFY(parseBinaryVector(binaryVector(0x10A, values, true)) ==
                values);  // YARP 4 float32 under 0x10A
        QVERIFY_THROWS_EXCEPTION(YarpError, parseBinaryVector(binaryVector(0x999, values, false)));
        auto truncated = binaryVector(0x114, values, false);
        truncated.pop_back();
        QVERIFY_THROWS_EXCEPTION(YarpError, parseBinaryVector(truncated));
        QVERIFY_THROWS_EXCEPTION(YarpError, parseBinaryVector({1, 2, 3}));
    }

    void skinCompensation() {
        SkinCompensation comp(3);
        QVERIFY_THROWS_EXCEPTION(YarpError, comp.compensate({235, 235, 235}));
        for (int i = 0; i < 50; ++i) comp.calibrate({235.0 + (i % 3) - 1, 236.0, 234.0});
        QVERIFY(comp.threshold()[0] >= 1.0);
        // Resting reads 0; a press (raw falls) reads its depth; nothing goes below 0 or above 255.
        const auto rest = comp.compensate({235, 236, 234});
        for (double v : rest) QVERIFY(v >= 0 && v < 1.5);
        const auto press = comp.compensate({135, 236, 0});
        QVERIFY(std::abs(press[0] - 100) < 2);
        QVERIFY(press[2] <= 255.0);
        QVERIFY_THROWS_EXCEPTION(YarpError, comp.compensate({1, 2}));
        // A held press slowly eats into itself (touch gain 0.05), as skinManager does.
        double first = 0, last = 0;
        for (int i = 0; i < 500; ++i) {
            const double v = comp.compensate({135, 236, 234})[0];
            if (i == 0) first = v;
            last = v;
        }
        QVERIFY(last < first);
    }

    void theStreamDecoderFramesWhateverArrives() {
        // A whole message split anywhere gives the same values; what cannot be read is a Bad
        // event and skipped, what cannot be framed a Fatal one that ends the stream.
        std::string text = "do\n";
        for (int i = 0; i < 192; ++i) text += std::to_string(i % 9) + (i < 191 ? " " : "\n");
        for (std::size_t chunk : {std::size_t{1}, std::size_t{7}, text.size()}) {
            StreamDecoder d(false);
            std::vector<StreamDecoder::Event> events;
            for (std::size_t at = 0; at < text.size(); at += chunk)
                for (auto& e : d.feed(text.data() + at, std::min(chunk, text.size() - at)))
                    events.push_back(e);
            QCOMPARE(events.size(), std::size_t{1});
            QCOMPARE(events[0].kind, StreamDecoder::Event::Values);
            QCOMPARE(events[0].values.size(), std::size_t{192});
            QCOMPARE(d.buffered(), std::size_t{0});
        }
        StreamDecoder bad(false);
        const std::string garbage = "hello\nd\n1 x 3\n";
        const auto events = bad.feed(garbage.data(), garbage.size());
        QCOMPARE(events.size(), std::size_t{2});
        QCOMPARE(events[0].kind, StreamDecoder::Event::Bad);
        QCOMPARE(events[1].kind, StreamDecoder::Event::Bad);
        QVERIFY(!bad.dead());

        StreamDecoder endless(false);
        const std::string line(StreamDecoder::kMaxTextLineBytes + 10, '5');
        const auto fatal = endless.feed(line.data(), line.size());
        QCOMPARE(fatal.size(), std::size_t{1});
        QCOMPARE(fatal[0].kind, StreamDecoder::Event::Fatal);
        QVERIFY(endless.dead());
        QCOMPARE(endless.feed("d\n", 2).size(), std::size_t{0});  // nothing after the end
    }

    void theBinaryHandshakeIsTheCapturedBytes() {
        // Captured from a real YARP 4 port (docs/protocols.md §3).
        QCOMPARE(
            QByteArray::fromStdString(binaryConnectionHeader("/activetouch/reader")).toHex(' '),
            (QByteArray::fromHex("5941641e00005250 14000000") +
             QByteArray("/activetouch/reader", 20))
                .toHex(' '));
        QCOMPARE(parseHeaderReply(fromHex("5941122700005250")), 10002);
        QCOMPARE(QByteArray::fromStdString(headerReply(10002)).toHex(),
                 QByteArray("5941122700005250"));
        QVERIFY_THROWS_EXCEPTION(YarpError, parseHeaderReply("YA\x12\x27\0\0RX"));
        QVERIFY_THROWS_EXCEPTION(YarpError, parseHeaderReply("YA\x12"));
        QCOMPARE(QByteArray::fromStdString(reverseRequest()).toHex(' '),
                 QByteArray::fromHex("59410a0000005250 0101 ffffffffffffffff 08000000 00000000"
                                     " 00000000 7e720001")
                     .toHex(' '));
        QCOMPARE(
            QByteArray::fromStdString(portCommandWithText("D 338 1795648690.92107")),
            QByteArray::fromHex("170000007e000001") + QByteArray("D 338 1795648690.92107", 23));
    }

    void binaryFramesInEveryLayoutAreRead_data() {
        QTest::addColumn<bool>("bottle");
        QTest::addColumn<QString>("envelope");
        QTest::addColumn<QByteArray>("start");
        // The starts of real frames: skinManager's Vector [8, 8, 1536], a Bottle [8, 1544].
        QTest::newRow("Vector")
            << false << QString()
            << QByteArray::fromHex(
                   "59410a0000005250 0301 ffffffffffffffff 08000000 08000000 00060000 00000000"
                   " 00000000 7e440001 14010000 c0000000");
        QTest::newRow("Bottle")
            << true << QString()
            << QByteArray::fromHex(
                   "59410a0000005250 0201 ffffffffffffffff 08000000 08060000 00000000"
                   " 00000000 7e440001 14010000 c0000000");
        // With a Stamp the envelope shares the port command's block: [31, 8, 1536].
        QTest::newRow("Vector with a Stamp")
            << false << "338 1795648690.92107"
            << QByteArray::fromHex(
                   "59410a0000005250 0301 ffffffffffffffff 1f000000 08000000"
                   " 00060000 00000000 170000007e000001") +
                   QByteArray("D 338 1795648690.92107", 23) +
                   QByteArray::fromHex("14010000c0000000");
        QTest::newRow("Bottle with a Stamp")
            << true << "338 1795648690.92107"
            << QByteArray::fromHex(
                   "59410a0000005250 0201 ffffffffffffffff 1f000000 08060000"
                   " 00000000 170000007e000001") +
                   QByteArray("D 338 1795648690.92107", 23) +
                   QByteArray::fromHex("14010000c0000000");
    }
    void binaryFramesInEveryLayoutAreRead() {
        QFETCH(bool, bottle);
        QFETCH(QString, envelope);
        QFETCH(QByteArray, start);
        std::vector<double> hand(192);
        for (std::size_t i = 0; i < hand.size(); ++i) hand[i] = 0.5 * static_cast<double>(i) - 7;
        BinaryFrame f;
        f.layout = bottle ? BinaryLayout::Bottle : BinaryLayout::Vector;
        f.envelope = envelope.toStdString();
        const std::string m = binaryDataMessage(hand, f);
        // The frame as a port sends it: the captured start, then the doubles.
        QCOMPARE(QByteArray::fromStdString(m.substr(0, static_cast<std::size_t>(start.size())))
                     .toHex(' '),
                 start.toHex(' '));
        QCOMPARE(m.size(), static_cast<std::size_t>(start.size()) + 192 * 8);
        QVERIFY(std::memcmp(m.data() + start.size(), hand.data(), 192 * 8) == 0);
        // Read back whole, byte by byte, and two frames in one read.
        for (std::size_t chunk : {m.size(), std::size_t{1}, std::size_t{13}}) {
            const auto events = decodeInChunks(m + m, chunk);
            QCOMPARE(events.size(), std::size_t{2});
            for (const auto& e : events) {
                QCOMPARE(e.kind, StreamDecoder::Event::Values);
                QVERIFY(e.values == hand);
                QCOMPARE(QString::fromStdString(e.envelope), envelope);
            }
        }
    }

    void binaryMessagesThatAreNotDataAreNamed() {
        // A port closing sends ~q: the stream ends with that said.
        auto events = decodeInChunks(binaryMessage({portCommandWithText("q")}), 5);
        QCOMPARE(events.size(), std::size_t{1});
        QCOMPARE(events[0].kind, StreamDecoder::Event::Fatal);
        QVERIFY(events[0].problem.find("closed its port") != std::string::npos);
        // Another command is skipped and named; the next frame still reads.
        const std::string frame = binaryDataMessage(std::vector<double>(192, 1.0), {});
        events = decodeInChunks(binaryMessage({portCommand('a')}) + frame, 7);
        QCOMPARE(events.size(), std::size_t{2});
        QCOMPARE(events[0].kind, StreamDecoder::Event::Bad);
        QVERIFY(events[0].problem.find("'~a'") != std::string::npos);
        QCOMPARE(events[1].kind, StreamDecoder::Event::Values);
        // Lost framing (no FF padding, a torn start): skipped to the next index, which reads.
        std::string unpadded = frame;
        unpadded[12] = 0;
        events = decodeInChunks(unpadded + "junk" + frame, 64);
        QCOMPARE(events.back().kind, StreamDecoder::Event::Values);
        QCOMPARE(events.front().kind, StreamDecoder::Event::Bad);
        // An envelope whose length overruns its block, a command text without NUL.
        std::string overrun = binaryMessage({portCommandWithText("D 1 2")});
        overrun[18 + 8] = 50;  // the command's text length
        events = decodeInChunks(overrun, 3);
        QCOMPARE(events.size(), std::size_t{1});
        QCOMPARE(events[0].kind, StreamDecoder::Event::Bad);
        std::string noNul = binaryMessage({portCommandWithText("D 1 2")});
        noNul.back() = 'x';
        events = decodeInChunks(noNul, 3);
        QVERIFY(events.size() == 1 && events[0].problem.find("NUL") != std::string::npos);
    }

    void listsOfOtherNumbersAreRead() {
        // A Bottle of int32 (0x101), and a mixed list (0x100) of an int32, a float64, an int8.
        std::string ints = fromHex("01010000 03000000 05000000 faffffff 00010000");
        QVERIFY(parseBinaryVector(ints.data(), ints.size()) == (std::vector<double>{5, -6, 256}));
        std::string mixed = fromHex("00010000 03000000 01000000 07000000 14000000") +
                            std::string("\0\0\0\0\0\0\xf8\x3f", 8) + fromHex("20000000 fe");
        QVERIFY(parseBinaryVector(mixed.data(), mixed.size()) == (std::vector<double>{7, 1.5, -2}));
        std::string text = fromHex("00010000 01000000 04000000 02000000 6869");
        QVERIFY_THROWS_EXCEPTION(YarpError, parseBinaryVector(text.data(), text.size()));
        std::string hugeCount = fromHex("00010000 ffffff7f 01000000");
        QVERIFY_THROWS_EXCEPTION(YarpError, parseBinaryVector(hugeCount.data(), hugeCount.size()));
        std::string strings = fromHex("04010000 01000000 00000000");
        QVERIFY_THROWS_EXCEPTION(YarpError, parseBinaryVector(strings.data(), strings.size()));
    }

    void theNameServerComesFromTheYarpConfFile() {
        QTemporaryDir home;
        const QByteArray dir = (home.path() + "/conf").toUtf8();
        QDir().mkpath(dir);
        qputenv("YARP_CONFIG_HOME", dir);
        qunsetenv("YARP_NAMESPACE");
        auto write = [&](const char* name, const char* text) {
            QFile f(QString(dir) + "/" + name);
            QVERIFY(f.open(QIODevice::WriteOnly));
            f.write(text);
        };
        // No conf file: loopback, and said so.
        NameServerAddress a = resolveNameServer("", 0);
        QCOMPARE(a.host, std::string("127.0.0.1"));
        QCOMPARE(a.port, 10000);
        QVERIFY(a.source.find("loopback: no YARP conf file at " + dir.toStdString() +
                              "/yarp.conf") != std::string::npos);
        // What `yarp conf 10.0.1.7 10111` writes.
        write("yarp.conf", "10.0.1.7 10111 yarp\n");
        a = resolveNameServer("", 0);
        QCOMPARE(a.host, std::string("10.0.1.7"));
        QCOMPARE(a.port, 10111);
        QCOMPARE(a.source, dir.toStdString() + "/yarp.conf");
        // The rig's own address wins; a host alone keeps the file's port.
        QCOMPARE(resolveNameServer("192.168.1.2", 10002).source, std::string("set for the rig"));
        a = resolveNameServer("192.168.1.2", 0);
        QVERIFY(a.host == "192.168.1.2" && a.port == 10111);
        // The [name] group form, and a namespace's own file.
        write("yarp.conf", "[name]\nhost 10.0.0.9\nport 10005\n");
        QCOMPARE(resolveNameServer("", 0).port, 10005);
        write("yarp_namespace.conf", "/lab2\n");
        write("_lab2.conf", "10.2.2.2 10222\n");
        QCOMPARE(yarpConfFile(), dir.toStdString() + "/_lab2.conf");
        QCOMPARE(resolveNameServer("", 0).host, std::string("10.2.2.2"));
        qputenv("YARP_NAMESPACE", "/root");
        QCOMPARE(yarpConfFile(), dir.toStdString() + "/yarp.conf");
        // A conf file that cannot be read is refused by name, not passed over for loopback.
        write("yarp.conf", "10.0.1.7 port\n");
        try {
            resolveNameServer("", 0);
            QFAIL("a bad conf file was passed over");
        } catch (const YarpError& e) {
            QVERIFY2(QString(e.what()).contains(dir + "/yarp.conf") &&
                         QString(e.what()).contains("'port'"),
                     e.what());
        }
        write("yarp.conf", "justahost\n");
        QVERIFY_THROWS_EXCEPTION(YarpError, resolveNameServer("", 0));
        write("yarp.conf", "[other]\nhost x\n");
        QVERIFY_THROWS_EXCEPTION(YarpError, resolveNameServer("", 0));
        qunsetenv("YARP_CONFIG_HOME");
        qunsetenv("YARP_NAMESPACE");
    }

    void aConfFileThatIsNoRegularFileIsRefusedAtOnce() {
        // A pipe would block the open forever and /dev/zero never end: each is refused by name,
        // at once and without reading it, as the conf file and as the namespace's file.
        QTemporaryDir home;
        const QString dir = home.path();
        qputenv("YARP_CONFIG_HOME", dir.toUtf8());
        qunsetenv("YARP_NAMESPACE");
        const QString conf = dir + "/yarp.conf";
        auto refused = [&](const char* what) {
            QElapsedTimer t;
            t.start();
            try {
                resolveNameServer("", 0);
                QFAIL(qPrintable(QString("a conf file that is %1 was passed over").arg(what)));
            } catch (const YarpError& e) {
                QVERIFY2(QString(e.what()).contains(conf) && QString(e.what()).contains(what),
                         e.what());
            }
            QVERIFY2(t.elapsed() < 2000, what);
        };
        QVERIFY(::mkfifo(QFile::encodeName(conf).constData(), 0600) == 0);
        refused("not a regular file");
        QFile::remove(conf);
        QVERIFY(QFile::link("/dev/zero", conf));
        refused("not a regular file");
        QFile::remove(conf);
        QVERIFY(QDir().mkpath(conf));
        refused("folder");
        QDir(conf).removeRecursively();
        {
            QFile big(conf);
            QVERIFY(big.open(QIODevice::WriteOnly));
            big.write(QByteArray(100 << 10, '#'));
        }
        refused("larger than 64 KiB");
        QFile::remove(conf);
        QVERIFY(QFile::link(dir + "/nowhere", conf));
        refused("no such file");
        QFile::remove(conf);
        // The namespace's file is read the same way.
        const QString space = dir + "/yarp_namespace.conf";
        QVERIFY(::mkfifo(QFile::encodeName(space).constData(), 0600) == 0);
        try {
            resolveNameServer("", 0);
            QFAIL("a namespace file that is a pipe was passed over");
        } catch (const YarpError& e) {
            QVERIFY2(QString(e.what()).contains(space), e.what());
        }
        qunsetenv("YARP_CONFIG_HOME");
    }

    void theStreamDecoderChecksEveryBlockLength_data() {
        QTest::addColumn<std::vector<std::int32_t>>("lengths");
        QTest::addColumn<bool>("fatal");
        QTest::newRow("negative") << std::vector<std::int32_t>{-1000, 100} << true;
        QTest::newRow("INT32_MAX") << std::vector<std::int32_t>{8, 2147483647} << true;
        QTest::newRow("over a megabyte together")
            << std::vector<std::int32_t>{700000, 700000} << true;
        QTest::newRow("a torn vector") << std::vector<std::int32_t>{8, 4, 13} << false;
    }
    void theStreamDecoderChecksEveryBlockLength() {
        QFETCH(std::vector<std::int32_t>, lengths);
        QFETCH(bool, fatal);
        std::string m = fromHex("59410a0000005250");
        auto put = [&](std::int32_t v) { m.append(reinterpret_cast<const char*>(&v), 4); };
        m.push_back(static_cast<char>(lengths.size()));
        m.push_back('\1');
        m.append(8, '\xFF');
        for (auto l : lengths) put(l);
        put(0);
        if (!fatal) {
            m += portCommand('D');  // the first block
            for (std::size_t b = 1; b < lengths.size(); ++b)
                m.append(static_cast<std::size_t>(lengths[b]), '\x01');
        }
        StreamDecoder d(true);
        const auto events = d.feed(m.data(), m.size());
        QCOMPARE(events.size(), std::size_t{1});
        QCOMPARE(events[0].kind, fatal ? StreamDecoder::Event::Fatal : StreamDecoder::Event::Bad);
        QCOMPARE(d.dead(), fatal);
        QVERIFY(d.buffered() < 64);  // nothing of a claimed length is waited for
    }
};

QTEST_APPLESS_MAIN(TestYarpProtocol)
#include "test_yarp_protocol.moc"
