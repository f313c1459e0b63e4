#include "devices/common/DeviceWorker.h"

#include <stdexcept>

namespace activetouch {

DeviceWorker::DeviceWorker(std::string name) : name_(std::move(name)) {}

DeviceWorker::~DeviceWorker() {
    stop();
}

void DeviceWorker::startEventLoop() {
    stop();
    stop_ = false;
    thread_ = std::make_unique<QThread>();
    thread_->setObjectName(QString::fromStdString(name_));
    thread_->start();
}

void DeviceWorker::start(std::function<void()> loop) {
    stop();
    stop_ = false;
    thread_.reset(QThread::create(std::move(loop)));
    thread_->setObjectName(QString::fromStdString(name_));
    thread_->start();
}

void DeviceWorker::stop() {
    if (!thread_) return;
    if (QThread::currentThread() == thread_.get())
        throw std::logic_error(name_ + ": a device thread cannot stop itself");
    stop_ = true;
    thread_->quit();  // ends an event loop once the slot running returns; a loop sees stop_
    thread_->wait();  // bounded by the policy above: no call in the thread blocks for long
    thread_.reset();
}

}  // namespace activetouch
