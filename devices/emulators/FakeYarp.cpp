#include "devices/emulators/FakeYarp.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <sstream>
#include <stdexcept>

namespace activetouch::emu {
namespace {

int listenOn(int port) {
    const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0) throw std::runtime_error("fake YARP: cannot create a socket");
    int one = 1;
    ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = htons(static_cast<std::uint16_t>(port));
    if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 || ::listen(fd, 8) != 0) {
        ::close(fd);
        throw std::runtime_error("fake YARP: cannot listen on loopback port " +
                                 std::to_string(port));
    }
    return fd;
}

int portOf(int fd) {
    sockaddr_in a{};
    socklen_t n = sizeof a;
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &n);
    return ntohs(a.sin_port);
}

void put32(std::string& s, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) s.push_back(static_cast<char>((v >> (8 * i)) & 0xFF));
}

}  // namespace

struct FakeYarp::Client {
    int fd = -1;
    bool nameServer = false;
    std::string in, out;
    enum class State {
        Greeting,
        Query,
        Handshake,
        BinaryName,
        Reader,
        Closed
    } state = State::Greeting;
    bool binary = false, reader = false;
    bool closeAfterSending = false;  ///< closed once `out` is sent (after ~q)
    std::chrono::steady_clock::time_point nextFrame;
};

FakeYarp::FakeYarp(FakeYarpSettings settings, Source fingertip)
    : s_(std::move(settings)), source_(std::move(fingertip)) {}

FakeYarp::~FakeYarp() {
    stop();
}

void FakeYarp::start() {
    nameServerFd_ = listenOn(0);
    nameServerPort_ = portOf(nameServerFd_);
    dataFd_ = listenOn(0);
    dataPort_ = portOf(dataFd_);
    running_ = true;
    thread_ = std::thread([this] { loop(); });
}

void FakeYarp::stop() {
    running_ = false;
    if (thread_.joinable()) thread_.join();
    for (Client& c : clients_)
        if (c.fd >= 0) ::close(c.fd);
    clients_.clear();
    for (int* fd : {&nameServerFd_, &dataFd_})
        if (*fd >= 0) {
            ::close(*fd);
            *fd = -1;
        }
}

void FakeYarp::setNameServerUp(bool up) {
    nameServerUp_ = up;
}
void FakeYarp::setPortRegistered(bool known) {
    registered_ = known;
}
void FakeYarp::setStalled(bool stalled) {
    stalled_ = stalled;
}
void FakeYarp::injectMalformedLine() {
    malformed_ = true;
}
void FakeYarp::injectWrongSize(int values) {
    wrongSize_ = values;
}
void FakeYarp::setWrongSize(int values) {
    alwaysWrongSize_ = values;
}
void FakeYarp::injectRawBytes(std::string bytes) {
    std::lock_guard lock(rawMutex_);
    raw_ = std::move(bytes);
}
void FakeYarp::dropReaders() {
    dropReaders_ = true;
}
void FakeYarp::closePort() {
    closePort_ = true;
}

std::vector<double> FakeYarp::handVector() {
    std::vector<double> hand(192, 0.0);
    const std::vector<double> tip = source_();
    for (std::size_t i = 0; i < tip.size() && i < 12; ++i)
        hand[static_cast<std::size_t>(s_.fingerOffset) + i] = tip[i];
    if (const int n = wrongSize_.exchange(0)) hand.resize(static_cast<std::size_t>(n), 0.0);
    if (const int n = alwaysWrongSize_.load()) hand.resize(static_cast<std::size_t>(n), 0.0);
    return hand;
}

std::string FakeYarp::textMessage() {
    const std::vector<double> hand = handVector();
    std::ostringstream o;
    o << s_.header;
    if (s_.envelope) o << ' ' << count_ << ' ' << count_ / s_.rate_hz;
    o << '\n';
    if (malformed_.exchange(false)) {
        o << "12.5 oops 3\n";
        return o.str();
    }
    o.precision(10);
    for (std::size_t i = 0; i < hand.size(); ++i) o << (i ? " " : "") << hand[i];
    o << '\n';
    return o.str();
}

std::string FakeYarp::binaryMessage() {
    const std::vector<double> hand = handVector();
    yarp::BinaryFrame f;
    f.layout = s_.binaryLayout;
    f.tag = s_.binaryTag;
    f.floats = s_.binaryFloats;
    if (s_.envelope) {
        std::ostringstream stamp;
        stamp.precision(15);
        stamp << count_ << ' ' << 1795648690.0 + static_cast<double>(count_) / s_.rate_hz;
        f.envelope = stamp.str();
    }
    if (malformed_.exchange(false)) {  // a torn vector: 192 claimed, five bytes sent
        std::string torn;
        put32(torn, s_.binaryTag);
        put32(torn, static_cast<std::uint32_t>(hand.size()));
        torn.append(5, '\x7f');
        return yarp::binaryMessage({yarp::portCommand('D'), torn});
    }
    return yarp::binaryDataMessage(hand, f);
}

void FakeYarp::serveNameServer(Client& c) {
    std::size_t nl;
    while ((nl = c.in.find('\n')) != std::string::npos) {
        std::string line = c.in.substr(0, nl);
        c.in.erase(0, nl + 1);
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (c.state == Client::State::Greeting) {
            if (line == "CONNACK extern") {
                c.out += "Welcome extern\r\n";
                c.state = Client::State::Query;
            } else {
                c.state = Client::State::Closed;  // plain CONNECT gets nothing
            }
        } else if (line == "d") {
            continue;
        } else if (line.rfind("query ", 0) == 0 || line.rfind("NAME_SERVER query ", 0) == 0) {
            const std::string port = line.substr(line.rfind(' ') + 1);
            if (registered_ && port == s_.portName)
                c.out += "registration name " + port + " ip 127.0.0.1 port " +
                         std::to_string(dataPort_) + " type tcp\r\n";
            c.out += "*** end of message\r\n<ACK>\r\n";
        }
    }
}

void FakeYarp::greet(Client& c) {
    if (c.in[0] == 'Y') {
        if (c.in.size() < 8) return;
        // "YA" int16 7777 + carrier "RP": only fast_tcp (3, no acknowledgements) is served.
        const int spec =
            static_cast<unsigned char>(c.in[2]) | (static_cast<unsigned char>(c.in[3]) << 8);
        if (c.in[1] != 'A' || c.in[6] != 'R' || c.in[7] != 'P' || spec != 7777 + 3) {
            c.state = Client::State::Closed;
            return;
        }
        c.binary = true;
        c.in.erase(0, 8);
        c.state = Client::State::BinaryName;
        return;
    }
    const auto nl = c.in.find('\n');
    if (nl == std::string::npos) return;
    const std::string line = c.in.substr(0, nl);
    c.in.erase(0, nl + 1);
    if (line.rfind("CONNECT ", 0) != 0) {
        c.state = Client::State::Closed;
        return;
    }
    c.out += "Welcome " + line.substr(8, line.find_first_of("\r") - 8) + "\n";
    c.state = Client::State::Handshake;
}

void FakeYarp::readBinaryName(Client& c) {
    if (c.in.size() < 4) return;
    std::uint32_t n = 0;
    std::memcpy(&n, c.in.data(), 4);
    if (n > 1000) {
        c.state = Client::State::Closed;
        return;
    }
    if (c.in.size() < 4 + n) return;
    c.in.erase(0, 4 + n);
    c.out += yarp::headerReply(dataPort_);
    c.state = Client::State::Handshake;
}

bool FakeYarp::reversedBinary(Client& c) {
    // A whole message whose port command is ~r; anything else leaves the connection an input of
    // the port, which never streams to it (a bare "~r\n" among them).
    static const std::string kIndex = yarp::headerReply(10);
    if (c.in.size() < 18) return false;
    if (c.in.compare(0, 8, kIndex) != 0) {
        c.in.clear();
        return false;
    }
    const int blocks = static_cast<unsigned char>(c.in[8]) + static_cast<unsigned char>(c.in[9]);
    const std::size_t head = 18 + 4 * static_cast<std::size_t>(blocks);
    if (c.in.size() < head) return false;
    std::size_t total = 0;
    for (int b = 0; b < blocks; ++b) {
        std::uint32_t n = 0;
        std::memcpy(&n, c.in.data() + 18 + 4 * b, 4);
        total += n;
    }
    if (total > (1u << 20)) {
        c.state = Client::State::Closed;
        return false;
    }
    if (c.in.size() < head + total) return false;
    bool reverse = false;
    try {
        reverse = yarp::parseBinaryContent(c.in.data() + head, total).command == 'r';
    } catch (const yarp::YarpError&) {
    }
    c.in.erase(0, head + total);
    return reverse;
}

bool FakeYarp::reversed(Client& c) {
    if (c.binary) return reversedBinary(c);
    const auto at = c.in.find("r\n");
    if (at == std::string::npos) return false;
    c.in.erase(0, at + 2);
    return true;
}

void FakeYarp::serveData(Client& c) {
    if (c.state == Client::State::Greeting && !c.in.empty()) greet(c);
    if (c.state == Client::State::BinaryName) readBinaryName(c);
    if (c.state != Client::State::Handshake || !reversed(c)) return;
    c.state = Client::State::Reader;
    c.reader = true;
    c.nextFrame = std::chrono::steady_clock::now();
    ++readers_;
}

void FakeYarp::publish(Client& c) {
    const auto now = std::chrono::steady_clock::now();
    if (now < c.nextFrame) return;
    c.nextFrame += std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(1.0 / s_.rate_hz));
    if (c.nextFrame < now) c.nextFrame = now;
    if (stalled_) return;
    if (c.out.size() > (1u << 20)) return;  // the reader is not reading: drop frames
    {
        std::lock_guard lock(rawMutex_);
        if (!raw_.empty()) {
            c.out += raw_;
            raw_.clear();
            return;
        }
    }
    c.out += c.binary ? binaryMessage() : textMessage();
    ++count_;
    ++frames_;
}

void FakeYarp::loop() {
    while (running_) {
        if (dropReaders_.exchange(false))
            for (Client& c : clients_)
                if (c.reader) c.state = Client::State::Closed;
        if (closePort_.exchange(false))
            for (Client& c : clients_)
                if (c.reader && c.binary) {
                    c.out += yarp::binaryMessage({yarp::portCommandWithText("q")});
                    c.closeAfterSending = true;
                }
        if (!nameServerUp_ && nameServerFd_ >= 0) {
            ::close(nameServerFd_);
            nameServerFd_ = -1;
            for (Client& c : clients_)
                if (c.nameServer) c.state = Client::State::Closed;
        } else if (nameServerUp_ && nameServerFd_ < 0) {
            nameServerFd_ = listenOn(nameServerPort_);
        }
        std::vector<pollfd> fds;
        for (int fd : {nameServerFd_, dataFd_}) fds.push_back({fd, POLLIN, 0});
        for (Client& c : clients_)
            fds.push_back({c.fd, static_cast<short>(POLLIN | (c.out.empty() ? 0 : POLLOUT)), 0});
        ::poll(fds.data(), fds.size(), 1);
        for (int i = 0; i < 2; ++i) {
            if (fds[i].fd < 0 || !(fds[i].revents & POLLIN)) continue;
            const int fd = ::accept4(fds[i].fd, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
            if (fd < 0) continue;
            Client c;
            c.fd = fd;
            c.nameServer = i == 0;
            clients_.push_back(std::move(c));
        }
        for (std::size_t k = 0; k < clients_.size(); ++k) {
            Client& c = clients_[k];
            const short re = k + 2 < fds.size() ? fds[k + 2].revents : 0;
            if (re & (POLLIN | POLLHUP | POLLERR)) {
                char buf[4096];
                const ssize_t n = ::recv(c.fd, buf, sizeof buf, 0);
                if (n <= 0)
                    c.state = Client::State::Closed;
                else
                    c.in.append(buf, static_cast<std::size_t>(n));
            }
            if (c.state != Client::State::Closed) {
                if (c.nameServer)
                    serveNameServer(c);
                else
                    serveData(c);
                if (c.state == Client::State::Reader && !c.closeAfterSending) publish(c);
            }
            if (!c.out.empty() && c.state != Client::State::Closed) {
                const ssize_t n = ::send(c.fd, c.out.data(), c.out.size(), MSG_NOSIGNAL);
                if (n > 0)
                    c.out.erase(0, static_cast<std::size_t>(n));
                else if (n < 0 && errno != EAGAIN)
                    c.state = Client::State::Closed;
            }
            if (c.closeAfterSending && c.out.empty()) c.state = Client::State::Closed;
        }
        for (std::size_t k = clients_.size(); k-- > 0;) {
            if (clients_[k].state != Client::State::Closed) continue;
            if (!clients_[k].nameServer && clients_[k].reader) --readers_;
            ::close(clients_[k].fd);
            clients_.erase(clients_.begin() + static_cast<std::ptrdiff_t>(k));
        }
    }
}

}  // namespace activetouch::emu
