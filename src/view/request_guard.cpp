#include "view/request_guard.h"

#include <array>
#include <cstdint>
#include <random>

namespace sombra {

namespace {

bool equal_in_constant_time(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    unsigned char difference = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        difference = static_cast<unsigned char>(difference |
                                                (static_cast<unsigned char>(a[i]) ^ static_cast<unsigned char>(b[i])));
    return difference == 0;
}

bool loopback_host(std::string_view host, int port) {
    const std::string digits = std::to_string(port);
    for (const std::string_view name : {std::string_view("127.0.0.1:"), std::string_view("localhost:")})
        if (host.starts_with(name) && host.substr(name.size()) == digits) return true;
    return false;
}

}  // namespace

std::string make_view_token() {
    std::random_device device;
    static constexpr std::array<char, 16> kHex{'0', '1', '2', '3', '4', '5', '6', '7',
                                               '8', '9', 'a', 'b', 'c', 'd', 'e', 'f'};
    std::string token;
    for (int word = 0; word < 4; ++word) {  // 4 × 32 bits
        const std::uint32_t bits = device();
        for (int nibble = 7; nibble >= 0; --nibble) token += kHex[(bits >> (4 * nibble)) & 0xfu];
    }
    return token;
}

Refusal check_request(std::string_view expected_token, int port, std::string_view host,
                      std::optional<std::string_view> origin, std::optional<std::string_view> token) {
    if (!loopback_host(host, port)) return Refusal::BadHost;
    if (origin) {
        constexpr std::string_view scheme = "http://";
        if (!origin->starts_with(scheme) || !loopback_host(origin->substr(scheme.size()), port))
            return Refusal::ForeignOrigin;
    }
    if (!token || expected_token.empty() || !equal_in_constant_time(*token, expected_token)) return Refusal::BadToken;
    return Refusal::None;
}

const char* refusal_text(Refusal refusal) {
    switch (refusal) {
        case Refusal::None: return "allowed";
        case Refusal::BadHost: return "the Host header must be 127.0.0.1:PORT or localhost:PORT";
        case Refusal::ForeignOrigin: return "requests from another origin are refused";
        case Refusal::BadToken: return "missing or wrong token";
    }
    return "refused";
}

}  // namespace sombra
