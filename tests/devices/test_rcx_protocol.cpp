// The Yamaha RCX line codec: commands as the controller expects them, and both reply dialects.
#include <QtTest>

#include "devices/yamaha/RcxProtocol.h"

using namespace activetouch::rcx;

class TestRcxProtocol : public QObject {
    Q_OBJECT
private slots:
    void commands() {
        QCOMPARE(QString::fromStdString(servoOn()), QString("@SERVO ON\r\n"));
        QCOMPARE(QString::fromStdString(origin()), QString("@ORIGIN\r\n"));
        QCOMPARE(QString::fromStdString(askPosition()), QString("@?WHRXY\r\n"));
        QCOMPARE(QString::fromStdString(moveTo(123.4, 56.7, 2)),
                 QString("@MOVE P, 123.400 56.700 0 0 0 0, S=2\r\n"));
        QCOMPARE(QString::fromStdString(stop()), QString("\x03"));
        QVERIFY_THROWS_EXCEPTION(ProtocolError, moveTo(1, 2, 0));
        QVERIFY_THROWS_EXCEPTION(ProtocolError, moveTo(1, 2, 101));
        QVERIFY_THROWS_EXCEPTION(ProtocolError, command(std::string(80, 'A')));
        QVERIFY_THROWS_EXCEPTION(ProtocolError, command("SERVO ON\r\n@ORIGIN"));
    }

    void replies_data() {
        QTest::addColumn<QString>("line");
        QTest::addColumn<int>("dialect");
        QTest::addColumn<int>("kind");
        QTest::addColumn<QString>("code");
        const int r22 = int(Dialect::Rcx22x), r340 = int(Dialect::Rcx340);
        QTest::newRow("OK") << "OK\r\n" << r22 << int(Reply::Kind::Ok) << "";
        QTest::newRow("ok lower case") << "ok" << r22 << int(Reply::Kind::Ok) << "";
        QTest::newRow("NG=code") << "NG=12\r\n" << r22 << int(Reply::Kind::Error) << "12";
        QTest::newRow("NG code: message")
            << "NG 12: Origin incomplete" << r22 << int(Reply::Kind::Error) << "12";
        QTest::newRow("NG alone") << "NG" << r22 << int(Reply::Kind::Error) << "";
        QTest::newRow("mm.nnn:message")
            << "14.200:Standby on" << r22 << int(Reply::Kind::Error) << "14.200";
        QTest::newRow("[POS]") << "[POS] 123.40 56.70 0.00 0.00 0.00 0.00" << r22
                               << int(Reply::Kind::Position) << "";
        QTest::newRow("RUN") << "RUN" << r340 << int(Reply::Kind::Running) << "";
        QTest::newRow("END") << "END\r\n" << r340 << int(Reply::Kind::Ended) << "";
        QTest::newRow("RCX340 position")
            << "123.40 56.70 0.00 0.00 0.00 0.00" << r340 << int(Reply::Kind::Position) << "";
        QTest::newRow("welcome") << "Welcome to RCX340" << r340 << int(Reply::Kind::Welcome) << "";
        QTest::newRow("garbage") << "\x7f#?%" << r22 << int(Reply::Kind::Other) << "";
        QTest::newRow("half a number") << "[POS] 12.3abc" << r22 << int(Reply::Kind::Other) << "";
    }
    void replies() {
        QFETCH(QString, line);
        QFETCH(int, dialect);
        QFETCH(int, kind);
        QFETCH(QString, code);
        const Reply r = parseReply(line.toStdString(), Dialect(dialect));
        QCOMPARE(int(r.kind), kind);
        QCOMPARE(QString::fromStdString(r.code), code);
        if (r.kind == Reply::Kind::Position) {
            QCOMPARE(int(r.values.size()), 6);
            QCOMPARE(r.values[0], 123.4);
            QCOMPARE(r.values[1], 56.7);
        }
    }

    void errorsReadAsSentences() {
        const Reply r = parseReply("NG 12: Origin incomplete", Dialect::Rcx22x);
        QCOMPARE(QString::fromStdString(describeError(r, moveTo(1, 2, 5))),
                 QString("the controller refused '@MOVE P, 1.000 2.000 0 0 0 0, S=5' with error "
                         "12: Origin incomplete"));
    }
};

QTEST_APPLESS_MAIN(TestRcxProtocol)
#include "test_rcx_protocol.moc"
