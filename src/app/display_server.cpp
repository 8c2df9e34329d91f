#include "app/display_server.h"

#include <fcntl.h>
#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <iostream>

#include "image/tev_packets.h"

namespace sombra {

namespace {

// A TCP connection to one of `address`'s addresses within `timeout`: a
// non-blocking connect awaited with poll, so that an address that drops
// packets cannot hold up the render. Returns the socket or −1 with `error`.
int connect_with_timeout(const DisplayAddress& address, std::chrono::milliseconds timeout, std::string& error) {
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    addrinfo* found = nullptr;
    if (const int rc = getaddrinfo(address.host.c_str(), address.port.c_str(), &hints, &found); rc != 0) {
        error = gai_strerror(rc);
        return -1;
    }
    error = "no address";
    int result = -1;
    for (addrinfo* a = found; a != nullptr && result < 0; a = a->ai_next) {
        const int s = socket(a->ai_family, a->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, a->ai_protocol);
        if (s < 0) {
            error = std::strerror(errno);
            continue;
        }
        int rc = connect(s, a->ai_addr, a->ai_addrlen);
        if (rc != 0 && errno == EINPROGRESS) {
            pollfd p{s, POLLOUT, 0};
            rc = poll(&p, 1, static_cast<int>(timeout.count()));
            int so_error = ETIMEDOUT;
            socklen_t len = sizeof so_error;
            if (rc == 1) getsockopt(s, SOL_SOCKET, SO_ERROR, &so_error, &len);
            errno = so_error;
            rc = so_error == 0 ? 0 : -1;
        }
        if (rc == 0) {
            result = s;
        } else {
            error = std::strerror(errno);
            close(s);
        }
    }
    freeaddrinfo(found);
    if (result >= 0) {
        // Blocking from now on, but never for longer than the timeout per send.
        fcntl(result, F_SETFL, fcntl(result, F_GETFL) & ~O_NONBLOCK);
        timeval tv{static_cast<time_t>(timeout.count() / 1000),
                   static_cast<suseconds_t>(timeout.count() % 1000) * 1000};
        setsockopt(result, SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv);
    }
    return result;
}

}  // namespace

std::optional<DisplayAddress> parse_display_address(std::string_view text) {
    DisplayAddress out;
    std::string_view port;
    if (!text.empty() && text.front() == '[') {
        const auto close = text.find(']');
        if (close == std::string_view::npos || close + 1 >= text.size() || text[close + 1] != ':') return std::nullopt;
        out.host = std::string(text.substr(1, close - 1));
        port = text.substr(close + 2);
    } else {
        const auto colon = text.rfind(':');
        if (colon == std::string_view::npos || text.find(':') != colon) return std::nullopt;
        out.host = std::string(text.substr(0, colon));
        port = text.substr(colon + 1);
    }
    int value = 0;
    const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), value);
    if (out.host.empty() || port.empty() || ec != std::errc{} || end != port.data() + port.size() || value < 1 ||
        value > 65535)
        return std::nullopt;
    out.port = std::string(port);
    return out;
}

DisplayConnection::DisplayConnection(const DisplayAddress& address, std::string name, int width, int height,
                                     std::chrono::milliseconds timeout)
    : where_(address.host.find(':') != std::string::npos ? "[" + address.host + "]:" + address.port
                                                         : address.host + ":" + address.port),
      name_(std::move(name)) {
    std::string error;
    socket_ = connect_with_timeout(address, timeout, error);
    if (socket_ < 0) {
        std::cerr << "sombra: warning: display server " << where_ << ": " << error << "; rendering without it\n";
        return;
    }
    send_all(tev_create_image_packet(name_, width, height));
}

DisplayConnection::~DisplayConnection() {
    if (socket_ >= 0) close(socket_);
}

void DisplayConnection::show(ImageView image) {
    if (socket_ < 0) return;
    for (const std::vector<std::uint8_t>& packet : tev_update_image_packets(name_, image))
        if (!send_all(packet)) return;
}

bool DisplayConnection::send_all(const std::vector<std::uint8_t>& packet) {
    std::size_t sent = 0;
    while (sent < packet.size()) {
        // MSG_NOSIGNAL: a viewer that closed must not kill the render with SIGPIPE.
        const ssize_t n = send(socket_, packet.data() + sent, packet.size() - sent, MSG_NOSIGNAL);
        if (n > 0) {
            sent += static_cast<std::size_t>(n);
        } else if (n < 0 && errno == EINTR) {
            continue;
        } else {
            give_up(n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK) ? "it stopped reading" : std::strerror(errno));
            return false;
        }
    }
    return true;
}

void DisplayConnection::give_up(const std::string& what) {
    std::cerr << "sombra: warning: display server " << where_ << ": " << what << "; rendering without it\n";
    close(socket_);
    socket_ = -1;
}

}  // namespace sombra
