// Who may talk to the viewer (spec §20): a request must carry the session's
// token, name the server by its loopback address in `Host`, and come from
// the viewer's own page when it has an `Origin` (DNS rebinding: a foreign
// site resolving its name to 127.0.0.1 sends its own Host and Origin).
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace sombra {

// 128 random bits from std::random_device, as 32 lower-case hex digits.
std::string make_view_token();

enum class Refusal {
    None,           // let it through
    BadHost,        // Host is not 127.0.0.1:PORT or localhost:PORT
    ForeignOrigin,  // Origin is set and is not http://127.0.0.1:PORT or http://localhost:PORT
    BadToken,       // no token, or another one
};

// What the server answers a request with `host`, `origin` (nullopt when the
// header is absent) and `token` (the query parameter, nullopt when absent).
// The token is compared in constant time.
Refusal check_request(std::string_view expected_token, int port, std::string_view host,
                      std::optional<std::string_view> origin, std::optional<std::string_view> token);

// A short reason for the 403 page, e.g. "missing or wrong token".
const char* refusal_text(Refusal refusal);

}  // namespace sombra
