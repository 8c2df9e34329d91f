// `sombra render … --display-server HOST:PORT` (spec §20): the image as it
// refines, streamed to a running tev viewer over its network protocol
// (image/tev_packets.h). The display is a nicety: when nobody listens, or
// tev goes away or stops reading, the render goes on after one warning.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <string_view>

#include "image/image_io.h"

namespace sombra {

struct DisplayAddress {
    std::string host;  // a name or an address; an IPv6 address without its brackets
    std::string port;  // 1 … 65535, in decimal
};

// HOST:PORT, [IPV6]:PORT; nullopt when it is not of that form.
std::optional<DisplayAddress> parse_display_address(std::string_view text);

class DisplayConnection {
public:
    // Connects to tev at `address` (waiting at most `timeout`) and creates
    // the image `name`; on failure prints one warning line to stderr
    // ("sombra: warning: display server HOST:PORT: WHAT; rendering without
    // it") and every later call does nothing.
    DisplayConnection(const DisplayAddress& address, std::string name, int width, int height,
                      std::chrono::milliseconds timeout = std::chrono::milliseconds(1000));
    ~DisplayConnection();
    DisplayConnection(const DisplayConnection&) = delete;
    DisplayConnection& operator=(const DisplayConnection&) = delete;

    // Sends the whole image. A send that cannot finish within the timeout
    // (tev stopped reading) or fails warns once and ends the connection.
    void show(ImageView image);

    bool connected() const { return socket_ >= 0; }

private:
    bool send_all(const std::vector<std::uint8_t>& packet);
    void give_up(const std::string& what);

    std::string where_;  // HOST:PORT, for messages
    std::string name_;
    int socket_ = -1;
};

}  // namespace sombra
