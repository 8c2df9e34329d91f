#include "view/request_guard.h"

#include <gtest/gtest.h>

#include <cctype>

namespace sombra {
namespace {

constexpr std::string_view kToken = "0123456789abcdef0123456789abcdef";

TEST(ViewToken, Is128RandomBitsInHex) {
    const std::string a = make_view_token(), b = make_view_token();
    EXPECT_EQ(a.size(), 32u);
    for (char c : a) EXPECT_TRUE(std::isxdigit(static_cast<unsigned char>(c)) && !std::isupper(c)) << a;
    EXPECT_NE(a, b);
}

TEST(RequestGuard, LetsTheOwnPageThrough) {
    EXPECT_EQ(check_request(kToken, 8123, "127.0.0.1:8123", std::nullopt, kToken), Refusal::None);
    EXPECT_EQ(check_request(kToken, 8123, "localhost:8123", std::string_view("http://localhost:8123"), kToken),
              Refusal::None);
    EXPECT_EQ(check_request(kToken, 8123, "127.0.0.1:8123", std::string_view("http://127.0.0.1:8123"), kToken),
              Refusal::None);
}

TEST(RequestGuard, RefusesAMissingOrWrongToken) {
    EXPECT_EQ(check_request(kToken, 8123, "127.0.0.1:8123", std::nullopt, std::nullopt), Refusal::BadToken);
    EXPECT_EQ(check_request(kToken, 8123, "127.0.0.1:8123", std::nullopt, std::string_view("")), Refusal::BadToken);
    EXPECT_EQ(check_request(kToken, 8123, "127.0.0.1:8123", std::nullopt, kToken.substr(1)), Refusal::BadToken);
    std::string wrong(kToken);
    wrong.back() = '0';
    EXPECT_EQ(check_request(kToken, 8123, "127.0.0.1:8123", std::nullopt, wrong), Refusal::BadToken);
    // An empty expected token never matches (a server without one serves nothing).
    EXPECT_EQ(check_request("", 8123, "127.0.0.1:8123", std::nullopt, std::string_view("")), Refusal::BadToken);
}

TEST(RequestGuard, RefusesForeignHostsAndOrigins) {
    for (std::string_view host : {"", "evil.example", "evil.example:8123", "127.0.0.1", "127.0.0.1:8124",
                                  "localhost:81234", "127.0.0.1:8123 ", "[::1]:8123", "127.0.0.2:8123"})
        EXPECT_EQ(check_request(kToken, 8123, host, std::nullopt, kToken), Refusal::BadHost) << host;
    for (std::string_view origin : {"http://evil.example", "http://evil.example:8123", "https://127.0.0.1:8123", "null",
                                    "", "http://127.0.0.1:8124", "http://localhost:8123/x"})
        EXPECT_EQ(check_request(kToken, 8123, "127.0.0.1:8123", origin, kToken), Refusal::ForeignOrigin) << origin;
}

}  // namespace
}  // namespace sombra
