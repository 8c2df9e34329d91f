// libFuzzer target for the request checks the viewer writes itself (spec
// §20; HTTP parsing is cpp-httplib's): check_request's decision on any Host,
// Origin and token, and the query values' parsers. The input is split at
// NUL bytes into host, origin, token and a query value; each invariant below
// that fails aborts, so libFuzzer keeps the input.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "view/query_values.h"
#include "view/request_guard.h"

namespace {

constexpr std::string_view kToken = "0123456789abcdef0123456789abcdef";
constexpr int kPort = 8765;

[[noreturn]] void broken(const char* what) {
    std::fprintf(stderr, "fuzz_view: %s\n", what);
    std::abort();
}

// What the checks must decide, written out the plain way.
bool allowed(std::string_view host, std::optional<std::string_view> origin, std::optional<std::string_view> token) {
    const auto loopback = [](std::string_view h) { return h == "127.0.0.1:8765" || h == "localhost:8765"; };
    if (!loopback(host)) return false;
    if (origin && !(origin->starts_with("http://") && loopback(origin->substr(7)))) return false;
    return token && *token == kToken;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view input(reinterpret_cast<const char*>(data), size);
    std::vector<std::string_view> parts;
    std::size_t start = 0;
    for (std::size_t i = 0; i <= input.size() && parts.size() < 4; ++i)
        if (i == input.size() || input[i] == '\0') {
            parts.push_back(input.substr(start, i - start));
            start = i + 1;
        }
    while (parts.size() < 4) parts.emplace_back();
    // An empty origin or token stands for the header or parameter being absent.
    const std::optional<std::string_view> origin = parts[1].empty() ? std::nullopt : std::optional(parts[1]);
    const std::optional<std::string_view> token = parts[2].empty() ? std::nullopt : std::optional(parts[2]);

    const sombra::Refusal r = sombra::check_request(kToken, kPort, parts[0], origin, token);
    if ((r == sombra::Refusal::None) != allowed(parts[0], origin, token)) broken("check_request decided wrongly");
    if (sombra::check_request("", kPort, parts[0], origin, token) == sombra::Refusal::None)
        broken("an empty expected token let a request through");
    if (std::string_view(sombra::refusal_text(r)).empty()) broken("a refusal without a reason");

    std::string problem;
    if (const auto v = sombra::parse_query_number("x", parts[3], problem); v ? !std::isfinite(*v) : problem.empty())
        broken("parse_query_number");
    problem.clear();
    if (const auto v = sombra::parse_query_int("spp", parts[3], 1, 65536, problem);
        v ? (*v < 1 || *v > 65536) : problem.empty())
        broken("parse_query_int");
    problem.clear();
    if (const auto v = sombra::parse_query_vec3("origin", parts[3], problem);
        v ? !(std::isfinite(v->x) && std::isfinite(v->y) && std::isfinite(v->z)) : problem.empty())
        broken("parse_query_vec3");
    return 0;
}
