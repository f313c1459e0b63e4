// A skin port as an iCub publishes one, for the real-YARP test: 192 values at a set rate, as a
// yarp::sig::Vector (skinManager's type) or a Bottle of float64, with or without a Stamp.
// Value k of frame n is 100 + k, except the last, which is n (a frame counter).
//   yarp_skin_publisher <port> vector|bottle stamp|plain <rate Hz> <frames before it stalls, -1: never>
// Stalled, it keeps its port open and writes nothing more.
#include <yarp/os/Bottle.h>
#include <yarp/os/BufferedPort.h>
#include <yarp/os/Network.h>
#include <yarp/os/Stamp.h>
#include <yarp/os/Time.h>
#include <yarp/sig/Vector.h>

#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

template <typename Frame, typename Fill>
int publish(const std::string& name, bool stamp, double rate, long stallAfter, Fill fill) {
    yarp::os::BufferedPort<Frame> port;
    if (!port.open(name)) {
        std::fprintf(stderr, "cannot open %s\n", name.c_str());
        return 2;
    }
    std::printf("publishing %s\n", name.c_str());
    std::fflush(stdout);
    double next = yarp::os::Time::now();
    for (long n = 0;; ++n) {
        if (stallAfter < 0 || n < stallAfter) {
            Frame& f = port.prepare();
            fill(f, n);
            if (stamp) {
                yarp::os::Stamp s(static_cast<int>(n), yarp::os::Time::now());
                port.setEnvelope(s);
            }
            port.write();
        }
        next += 1.0 / rate;
        const double wait = next - yarp::os::Time::now();
        if (wait > 0) yarp::os::Time::delay(wait);
    }
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 6) {
        std::fprintf(stderr,
                     "usage: %s <port> vector|bottle stamp|plain <rate Hz> <frames before stall>\n",
                     argv[0]);
        return 1;
    }
    yarp::os::Network network;
    if (!yarp::os::Network::checkNetwork(5.0)) {
        std::fprintf(stderr, "no YARP name server\n");
        return 2;
    }
    const std::string name = argv[1], layout = argv[2];
    const bool stamp = std::string(argv[3]) == "stamp";
    const double rate = std::atof(argv[4]);
    const long stallAfter = std::atol(argv[5]);
    if (layout == "vector")
        return publish<yarp::sig::Vector>(name, stamp, rate, stallAfter,
                                          [](yarp::sig::Vector& v, long n) {
                                              v.resize(192);
                                              for (int k = 0; k < 191; ++k) v[k] = 100.0 + k;
                                              v[191] = static_cast<double>(n);
                                          });
    return publish<yarp::os::Bottle>(name, stamp, rate, stallAfter, [](yarp::os::Bottle& b, long n) {
        b.clear();
        for (int k = 0; k < 191; ++k) b.addFloat64(100.0 + k);
        b.addFloat64(static_cast<double>(n));
    });
}
