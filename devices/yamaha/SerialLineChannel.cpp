#include "devices/yamaha/SerialLineChannel.h"

#include <QSerialPort>
#include <future>

namespace activetouch::rcx {

SerialLineChannel::SerialLineChannel() {
    thread_.startEventLoop();
    context_ = new QObject;
    context_->moveToThread(thread_.thread());
    QObject::connect(thread_.thread(), &QThread::finished, context_, &QObject::deleteLater);
}

SerialLineChannel::~SerialLineChannel() {
    close();
    thread_.stop();  // every slot in the port's thread returns at once or within its timeout
}

bool SerialLineChannel::isOpen() const {
    std::lock_guard lock(mutex_);
    return open_ && failure_.empty();
}

void SerialLineChannel::open(const SerialSettings& settings) {
    close();
    settings_ = settings;
    auto done = std::make_shared<std::promise<std::string>>();
    auto result = done->get_future();
    QMetaObject::invokeMethod(
        context_,
        [this, done] {
            auto* port = new QSerialPort(context_);
            port->setPortName(QString::fromStdString(settings_.portName));
            bool ok = port->open(QIODevice::ReadWrite);
            const auto parity = settings_.parity == 'E'   ? QSerialPort::EvenParity
                                : settings_.parity == 'O' ? QSerialPort::OddParity
                                                          : QSerialPort::NoParity;
            ok = ok && port->setBaudRate(settings_.baud) &&
                 port->setDataBits(static_cast<QSerialPort::DataBits>(settings_.dataBits)) &&
                 port->setParity(parity) &&
                 port->setStopBits(settings_.stopBits == 2 ? QSerialPort::TwoStop
                                                           : QSerialPort::OneStop) &&
                 port->setFlowControl(settings_.hardwareFlowControl ? QSerialPort::HardwareControl
                                                                    : QSerialPort::NoFlowControl);
            if (!ok) {
                const std::string why = port->errorString().toStdString();
                delete port;
                done->set_value("serial port " + settings_.portName + " cannot be opened (" + why +
                                "); check the name and that you may use it (group dialout)");
                return;
            }
            QObject::connect(port, &QSerialPort::readyRead, context_,
                             [this, port] { received(port->readAll()); });
            QObject::connect(port, &QSerialPort::errorOccurred, context_,
                             [this, port](QSerialPort::SerialPortError e) {
                                 if (e == QSerialPort::ResourceError ||
                                     e == QSerialPort::PermissionError ||
                                     e == QSerialPort::DeviceNotFoundError ||
                                     e == QSerialPort::ReadError || e == QSerialPort::WriteError) {
                                     failed("serial port " + settings_.portName + " vanished (" +
                                            port->errorString().toStdString() +
                                            "); check the cable and connect again");
                                     port->close();
                                 }
                             });
            port_ = port;
            done->set_value(std::string());
        },
        Qt::QueuedConnection);
    if (result.wait_for(std::chrono::seconds(5)) != std::future_status::ready)
        throw RigError("serial port " + settings.portName + ": opening did not finish in 5 s");
    const std::string problem = result.get();
    if (!problem.empty()) throw RigError(problem);
    std::lock_guard lock(mutex_);
    open_ = true;
    failure_.clear();
    lines_.clear();
    partial_.clear();
}

void SerialLineChannel::close() {
    {
        std::lock_guard lock(mutex_);
        if (!open_) return;
        open_ = false;
    }
    auto done = std::make_shared<std::promise<void>>();
    auto result = done->get_future();
    QMetaObject::invokeMethod(
        context_,
        [this, done] {
            if (port_) {
                port_->close();
                delete port_;
                port_ = nullptr;
            }
            done->set_value();
        },
        Qt::QueuedConnection);
    result.wait_for(std::chrono::seconds(2));
    cv_.notify_all();
}

void SerialLineChannel::requireOpen() const {
    std::lock_guard lock(mutex_);
    if (!failure_.empty()) throw RigError(failure_);
    if (!open_) throw RigError("serial port " + settings_.portName + " is not open");
}

void SerialLineChannel::write(const std::string& bytes) {
    requireOpen();
    QMetaObject::invokeMethod(
        context_,
        [this, data = QByteArray::fromStdString(bytes)] {
            if (port_ && port_->isOpen()) {
                port_->write(data);
                port_->flush();
            }
        },
        Qt::QueuedConnection);
}

bool SerialLineChannel::writeNow(const std::string& bytes, int timeoutMs) {
    requireOpen();
    auto done = std::make_shared<std::promise<bool>>();
    auto result = done->get_future();
    auto writeAll = [this, done, data = QByteArray::fromStdString(bytes), timeoutMs] {
        bool written = false;
        if (port_ && port_->isOpen()) {
            port_->write(data);
            port_->flush();
            written = port_->bytesToWrite() == 0 || port_->waitForBytesWritten(timeoutMs);
        }
        done->set_value(written);
    };
    if (QThread::currentThread() == context_->thread())
        writeAll();
    else
        QMetaObject::invokeMethod(context_, writeAll, Qt::QueuedConnection);
    return result.wait_for(std::chrono::milliseconds(timeoutMs)) == std::future_status::ready &&
           result.get();
}

std::optional<std::string> SerialLineChannel::readLine(int timeoutMs) {
    std::unique_lock lock(mutex_);
    cv_.wait_for(lock, std::chrono::milliseconds(timeoutMs),
                 [&] { return !lines_.empty() || !failure_.empty() || !open_; });
    if (!lines_.empty()) {
        std::string line = std::move(lines_.front());
        lines_.pop_front();
        return line;
    }
    if (!failure_.empty()) throw RigError(failure_);
    return std::nullopt;
}

void SerialLineChannel::discardInput() {
    std::lock_guard lock(mutex_);
    lines_.clear();
}

void SerialLineChannel::received(const QByteArray& bytes) {
    std::lock_guard lock(mutex_);
    if (!failure_.empty()) return;
    partial_.append(bytes.constData(), static_cast<std::size_t>(bytes.size()));
    std::size_t nl;
    while ((nl = partial_.find('\n')) != std::string::npos) {
        std::string line = partial_.substr(0, nl);
        partial_.erase(0, nl + 1);
        if (!line.empty() && line.back() == '\r') line.pop_back();
        lines_.push_back(std::move(line));
    }
    // A controller's replies are short lines read as they come: a line that never ends, or
    // lines nobody reads, mean a wrong baud rate or something else on the port.
    if (partial_.size() > kMaxLineBytes || lines_.size() > kMaxUnreadLines) {
        failure_ = "serial port " + settings_.portName +
                   (partial_.size() > kMaxLineBytes
                        ? " sent more than " + std::to_string(kMaxLineBytes) +
                              " bytes without a line end"
                        : " sent more than " + std::to_string(kMaxUnreadLines) +
                              " lines nobody asked for") +
                   "; check the baud rate, the parity and that the controller is on this port";
        partial_.clear();
        lines_.clear();
    }
    cv_.notify_all();
}

void SerialLineChannel::failed(const std::string& why) {
    std::lock_guard lock(mutex_);
    if (failure_.empty()) failure_ = why;
    cv_.notify_all();
}

}  // namespace activetouch::rcx
