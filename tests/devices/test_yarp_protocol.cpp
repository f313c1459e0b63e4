// The YARP codecs: name-server replies, text and binary data (both tag versions, with and without
// an envelope, 'd' and 'D'), a fingertip out of the hand vector, and skinManager compensation.
#include <QtTest>
#include <cstring>

#include "devices/yarp/YarpProtocol.h"

using namespace activetouch::yarp;
Q_DECLARE_METATYPE(std::vector<std::int32_t>)

namespace {
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

    void theStreamDecoderChecksEveryBlockLength_data() {
        QTest::addColumn<std::vector<std::int32_t>>("lengths");
        QTest::addColumn<bool>("fatal");
        QTest::newRow("negative") << std::vector<std::int32_t>{-1000, 100} << true;
        QTest::newRow("INT32_MAX") << std::vector<std::int32_t>{8, 2147483647} << true;
        QTest::newRow("over a megabyte together")
            << std::vector<std::int32_t>{700000, 700000} << true;
        QTest::newRow("a torn vector") << std::vector<std::int32_t>{4, 13} << false;
    }
    void theStreamDecoderChecksEveryBlockLength() {
        QFETCH(std::vector<std::int32_t>, lengths);
        QFETCH(bool, fatal);
        std::string m = "YA";
        auto put = [&](std::int32_t v) { m.append(reinterpret_cast<const char*>(&v), 4); };
        put(0);
        m += "RP";
        put(static_cast<std::int32_t>(lengths.size()));
        for (auto l : lengths) put(l);
        put(0);
        if (!fatal)
            for (auto l : lengths) m.append(static_cast<std::size_t>(l), '\x01');
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
