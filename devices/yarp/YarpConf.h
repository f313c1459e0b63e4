#pragma once
// Where the YARP name server is (docs/protocols.md §3): the address set for the rig, else the one
// YARP's own conf file gives, as `yarp conf` writes and reads it, else loopback as a last resort.
#include <optional>
#include <string>

namespace activetouch::yarp {

struct NameServerAddress {
    std::string host;
    int port = 0;
    /// Where the address came from, in words: "set for the rig", the conf file's path, or
    /// "loopback: no YARP conf file at <path>".
    std::string source;
};

/// The conf file YARP reads: in $YARP_CONFIG_HOME, else $XDG_CONFIG_HOME/yarp, else
/// $HOME/.config/yarp; named yarp.conf for the default namespace (/root), else after the
/// namespace with every character but letters and digits made '_', plus ".conf". The namespace
/// is $YARP_NAMESPACE, else the first word of yarp_namespace.conf in the same folder. Empty if
/// there is no home to look in.
std::string yarpConfFile();

/// Reads a conf file's text: "host port [mode]", or a "[name]" group with "host" and "port"
/// lines. Nothing for an empty file; throws YarpError naming `file` for one it cannot read.
std::optional<NameServerAddress> parseYarpConf(const std::string& text, const std::string& file);

/// The name server to ask: `host` and `port` where set (empty host, port 0: not set), the rest
/// from the conf file if there is one, else 127.0.0.1:10000. Throws YarpError for a conf file
/// that exists but cannot be read as one.
NameServerAddress resolveNameServer(const std::string& host, int port);

}  // namespace activetouch::yarp
