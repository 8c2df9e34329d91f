// The viewer's server over real HTTP on 127.0.0.1, without a browser: the
// security rules of spec §20, the event stream, the images against
// `sombra render`, the camera and settings, and explain.
#include "view/view_server.h"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <httplib.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <stb_image.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "io/scene_json/scene_file.h"
#include "view/view_test_util.h"

namespace sombra {
namespace {

using view_test::decode_png;
using view_test::raw_request;
using view_test::Rgb8;
using view_test::ServedScene;

using view_test::kToken;

TEST(ViewServer, RefusesRequestsWithoutTheToken) {
    ServedScene s(4);
    httplib::Client client("127.0.0.1", s.port());
    for (const std::string path : {"/", "/state", "/image.png", "/events", "/explain?x=1&y=1"}) {
        const auto none = client.Get(path);
        ASSERT_TRUE(none) << path;
        EXPECT_EQ(none->status, 403) << path;
        const std::string join = path.find('?') == std::string::npos ? "?" : "&";
        const auto wrong = client.Get(path + join + "token=00112233445566778899aabbccddeefe");
        ASSERT_TRUE(wrong) << path;
        EXPECT_EQ(wrong->status, 403) << path;
    }
    const auto right = client.Get("/?token=" + std::string(kToken));
    ASSERT_TRUE(right);
    EXPECT_EQ(right->status, 200);
    EXPECT_NE(right->body.find("<html"), std::string::npos);
    EXPECT_FALSE(right->has_header("Access-Control-Allow-Origin"));
}

TEST(ViewServer, NoPathReachesTheFileSystem) {
    ServedScene s(4);
    for (const std::string path :
         {"/../../../../etc/passwd", "/%2e%2e/%2e%2e/%2e%2e/etc/passwd", "/..%2f..%2f..%2fetc%2fpasswd", "//etc/passwd",
          "/etc/passwd", "/scene.json", "/square.obj", "/page.html", "/view_server.cpp"}) {
        const std::string answer =
            raw_request(s.port(), "GET " + path + "?token=" + kToken + " HTTP/1.1\r\nHost: 127.0.0.1:" +
                                      std::to_string(s.port()) + "\r\nConnection: close\r\n\r\n");
        EXPECT_TRUE(answer.starts_with("HTTP/1.1 404") || answer.starts_with("HTTP/1.1 403") ||
                    answer.starts_with("HTTP/1.1 400"))
            << path << ": " << answer.substr(0, 40);
        EXPECT_EQ(answer.find("root:"), std::string::npos) << path;
        EXPECT_EQ(answer.find("\"objects\""), std::string::npos) << path;  // not the scene file
        EXPECT_EQ(answer.find("v -1 -1 0"), std::string::npos) << path;    // not the mesh
    }
}

TEST(ViewServer, RefusesForeignHostAndOrigin) {
    ServedScene s(4);
    const std::string port = std::to_string(s.port());
    const std::string get = "GET /state?token=" + std::string(kToken) + " HTTP/1.1\r\n";
    const std::string close = "Connection: close\r\n\r\n";
    EXPECT_TRUE(raw_request(s.port(), get + "Host: 127.0.0.1:" + port + "\r\n" + close).starts_with("HTTP/1.1 200"));
    EXPECT_TRUE(
        raw_request(s.port(), get + "Host: localhost:" + port + "\r\nOrigin: http://localhost:" + port + "\r\n" + close)
            .starts_with("HTTP/1.1 200"));
    for (const std::string& host : std::vector<std::string>{"evil.example", "evil.example:" + port, "127.0.0.1:1"})
        EXPECT_TRUE(raw_request(s.port(), get + "Host: " + host + "\r\n" + close).starts_with("HTTP/1.1 403")) << host;
    EXPECT_TRUE(raw_request(s.port(), get + close).starts_with("HTTP/1.1 403"));  // no Host at all
    for (const std::string& origin :
         std::vector<std::string>{"http://evil.example", "http://evil.example:" + port, "null"})
        EXPECT_TRUE(raw_request(s.port(), get + "Host: 127.0.0.1:" + port + "\r\nOrigin: " + origin + "\r\n" + close)
                        .starts_with("HTTP/1.1 403"))
            << origin;
}

TEST(ViewServer, RefusesOversizedAndMalformedRequestsAndGoesOn) {
    ServedScene s(4);
    httplib::Client client("127.0.0.1", s.port());
    const std::string body(kMaxViewBody + 1, 'x');
    const auto big = client.Post("/camera?token=" + std::string(kToken), body, "text/plain");
    ASSERT_TRUE(big);
    EXPECT_EQ(big->status, 413);
    EXPECT_EQ(big->body, "413 payload too large: a body holds at most " + std::to_string(kMaxViewBody) + " bytes\n");
    const auto nowhere = client.Get("/nowhere?token=" + std::string(kToken));
    ASSERT_TRUE(nowhere);
    EXPECT_EQ(nowhere->status, 404);
    EXPECT_TRUE(nowhere->body.starts_with("404 not found: no such page")) << nowhere->body;
    const auto long_uri = client.Get("/state?token=" + std::string(kToken) + "&pad=" + std::string(20000, 'a'));
    if (long_uri) {
        EXPECT_GE(long_uri->status, 400);  // or the connection was closed on it
    }
    for (const std::string& request : {std::string("GARBAGE\r\n\r\n"), std::string("GET\r\n\r\n"),
                                       std::string("GET / HTTP/9.9\r\n\r\n"), std::string("\x01\x02\x03\xff\r\n\r\n"),
                                       "GET /state?token=" + std::string(kToken) + " HTTP/1.1\r\nHost\r\n\r\n",
                                       "POST /camera?token=" + std::string(kToken) + " HTTP/1.1\r\nHost: 127.0.0.1:" +
                                           std::to_string(s.port()) + "\r\nContent-Length: x\r\n\r\n"}) {
        const std::string answer = raw_request(s.port(), request);
        EXPECT_TRUE(answer.empty() || answer.starts_with("HTTP/1.1 4")) << request << " -> " << answer.substr(0, 40);
    }
    const auto after = client.Get("/state?token=" + std::string(kToken));
    ASSERT_TRUE(after);
    EXPECT_EQ(after->status, 200);
}

TEST(ViewServer, StreamsPassesAndItsImageEqualsSombraRender) {
    ServedScene s(64, "", 320, 240);  // 32 passes of 2 samples
    const std::vector<nlohmann::json> events = s.read_events(2);
    ASSERT_GE(events.size(), 2u);
    EXPECT_EQ(events[0]["generation"], events[1]["generation"]);
    // The stream says every pass: two samples a pixel each, up to the 4 asked for.
    const nlohmann::json last = s.wait_done();
    EXPECT_EQ(last["passes"], 32);
    EXPECT_EQ(last["spp"], 64);
    EXPECT_GT(last["passes_per_second"].get<double>(), 0.0);

    httplib::Client client("127.0.0.1", s.port());
    const auto png = client.Get("/image.png?token=" + std::string(kToken));
    ASSERT_TRUE(png);
    ASSERT_EQ(png->status, 200);
    EXPECT_EQ(png->get_header_value("Content-Type"), "image/png");
    const view_test::Rgb8 served = view_test::decode_png(png->body);
    const view_test::Rgb8 rendered = s.sombra_render_png("--spp 64");
    ASSERT_EQ(served.width, 320);
    ASSERT_EQ(served.height, 240);
    ASSERT_EQ(served.pixels.size(), rendered.pixels.size());
    int differ = 0, nonzero = 0;
    for (std::size_t k = 0; k < served.pixels.size(); ++k) {
        differ += std::abs(int(served.pixels[k]) - int(rendered.pixels[k])) > 1;
        nonzero += served.pixels[k] != 0;
    }
    EXPECT_EQ(differ, 0);
    EXPECT_GT(nonzero, 100);  // the square is lit: not a black image compared with a black image

    const auto exr = client.Get("/image.exr?token=" + std::string(kToken));
    ASSERT_TRUE(exr);
    EXPECT_EQ(exr->status, 200);
    EXPECT_TRUE(exr->body.starts_with("\x76\x2f\x31\x01"));  // OpenEXR's magic number
}

TEST(ViewServer, CameraAndSettingsAreCheckedAndRestartThePasses) {
    ServedScene s(4);
    const nlohmann::json first = s.wait_done();
    httplib::Client client("127.0.0.1", s.port());
    const std::string t = "token=" + std::string(kToken);
    for (const std::string bad :
         {"origin=0,0,4&look_at=0,0,4&up=0,1,0&fov=40", "origin=0,0,4&look_at=0,0,0&up=0,0,1&fov=40",
          "origin=0,0,4&look_at=0,0,0&up=0,1,0&fov=180", "origin=0,0,nan&look_at=0,0,0&up=0,1,0&fov=40",
          "origin=0,0,4&look_at=0,0,0&up=0,1,0", "origin=1,2&look_at=0,0,0&up=0,1,0&fov=40"}) {
        const auto r = client.Post("/camera?" + t + "&" + bad, "", "text/plain");
        ASSERT_TRUE(r) << bad;
        EXPECT_EQ(r->status, 400) << bad;
        EXPECT_TRUE(r->body.starts_with("400 bad request: ")) << r->body;
    }
    for (const std::string bad : {"spp=0", "spp=70000", "max_depth=-1", "integrator=bidir", "spp=x"}) {
        const auto r = client.Post("/settings?" + t + "&" + bad, "", "text/plain");
        ASSERT_TRUE(r) << bad;
        EXPECT_EQ(r->status, 400) << bad;
    }
    const auto moved = client.Post("/camera?" + t + "&origin=1,0.5,4&look_at=0,0,0&up=0,1,0&fov=35", "", "text/plain");
    ASSERT_TRUE(moved);
    ASSERT_EQ(moved->status, 200) << moved->body;
    const nlohmann::json state = nlohmann::json::parse(moved->body);
    EXPECT_EQ(state["camera"]["fov"], 35.0);
    const nlohmann::json again = s.wait_done();
    EXPECT_GT(again["generation"].get<int>(), first["generation"].get<int>());
    const auto spp = client.Post("/settings?" + t + "&spp=6&integrator=path&max_depth=3", "", "text/plain");
    ASSERT_TRUE(spp);
    ASSERT_EQ(spp->status, 200) << spp->body;
    const nlohmann::json six = s.wait_done();
    EXPECT_EQ(six["spp"], 6);
    EXPECT_EQ(six["passes"], 3);
}

// An orthographic camera (a glTF file's) zooms by its half-height: the
// state says so, /camera takes half_height and refuses fov, and the render
// follows. The unit square at half-height 2 on 32 × 24 pixels (half-width
// 8/3) covers exactly columns 10–21 and rows 6–17: pixel (i, j) sees
// x = (1 − 2(i + ½)/32)·8/3 and y = (1 − 2(j + ½)/24)·2.
TEST(ViewServer, AnOrthographicCameraZoomsByItsHalfHeight) {
    ServedScene s(1, "", 32, 24, 1.5f);
    s.wait_done();
    httplib::Client client("127.0.0.1", s.port());
    const std::string t = "token=" + std::string(kToken);
    const auto initial = client.Get("/state?" + t);
    ASSERT_TRUE(initial);
    const nlohmann::json state = nlohmann::json::parse(initial->body);
    EXPECT_EQ(state["camera"]["projection"], "orthographic");
    EXPECT_EQ(state["camera"]["half_height"], 1.5);
    EXPECT_FALSE(state["camera"].contains("fov"));

    const std::string pose = "&origin=0,0,4&look_at=0,0,0&up=0,1,0";
    for (const std::string bad : {"&fov=40", "&half_height=0", "&half_height=-1", "&half_height=nan",
                                  "&half_height=1e39", "&half_height=2&fov=40", ""}) {
        const auto r = client.Post("/camera?" + t + pose + bad, "", "text/plain");
        ASSERT_TRUE(r) << bad;
        EXPECT_EQ(r->status, 400) << bad;
        EXPECT_TRUE(r->body.starts_with("400 bad request: ")) << r->body;
    }
    const auto moved = client.Post("/camera?" + t + pose + "&half_height=2", "", "text/plain");
    ASSERT_TRUE(moved);
    ASSERT_EQ(moved->status, 200) << moved->body;
    const nlohmann::json after = nlohmann::json::parse(moved->body);
    EXPECT_EQ(after["camera"]["half_height"], 2.0);
    const int generation = after["frame"]["generation"].get<int>();
    s.read_events_until([&](const std::vector<nlohmann::json>& e) {
        return !e.empty() && e.back()["done"].get<bool>() && e.back()["generation"].get<int>() >= generation;
    });
    const auto png = client.Get("/image.png?" + t);
    ASSERT_TRUE(png);
    const Rgb8 image = decode_png(png->body);
    ASSERT_EQ(image.width, 32);
    ASSERT_EQ(image.height, 24);
    for (int j = 0; j < 24; ++j)
        for (int i = 0; i < 32; ++i) {
            const unsigned char* p = &image.pixels[(std::size_t(j) * 32 + std::size_t(i)) * 3];
            const bool lit = p[0] + p[1] + p[2] > 0;
            EXPECT_EQ(lit, i >= 10 && i <= 21 && j >= 6 && j <= 17) << i << ", " << j;
        }

    // A perspective camera refuses half_height.
    ServedScene perspective(1);
    httplib::Client other("127.0.0.1", perspective.port());
    const auto refused = other.Post("/camera?" + t + pose + "&fov=40&half_height=2", "", "text/plain");
    ASSERT_TRUE(refused);
    EXPECT_EQ(refused->status, 400);
}

// Bytes of `a` and `b` that differ by more than 8-bit rounding (1), or -1
// for images of different sizes.
int bytes_apart(const Rgb8& a, const Rgb8& b) {
    if (a.width != b.width || a.height != b.height || a.pixels.size() != b.pixels.size()) return -1;
    int differ = 0;
    for (std::size_t k = 0; k < a.pixels.size(); ++k) differ += std::abs(int(a.pixels[k]) - int(b.pixels[k])) > 1;
    return differ;
}

// Spec §25's switch: the newest finished pass denoised (after the last
// pass, `sombra render --denoise`'s image); off, the raw image at once,
// without a restart; below 2 samples a pixel, the raw image.
TEST(ViewServer, TheDenoiseSwitchShowsTheNewestPassDenoised) {
    ServedScene s(8);
    const nlohmann::json raw_done = s.wait_done();
    EXPECT_FALSE(raw_done["denoise"].get<bool>());
    EXPECT_EQ(raw_done["denoised"], 0);
    httplib::Client client("127.0.0.1", s.port());
    const std::string t = "token=" + std::string(kToken);
    const auto image = [&] {
        const auto r = client.Get("/image.png?" + t);
        return r ? decode_png(r->body) : Rgb8{};
    };
    const auto post = [&](const std::string& query) {
        const auto r = client.Post("/settings?" + t + "&" + query, "", "text/plain");
        EXPECT_TRUE(r && r->status == 200) << query << ": " << (r ? r->body : "no answer");
        return r && r->status == 200 ? nlohmann::json::parse(r->body) : nlohmann::json{};
    };
    const auto denoised_to_the_end = [](const std::vector<nlohmann::json>& e) {
        return !e.empty() && e.back()["done"].get<bool>() && e.back()["denoised"] == e.back()["version"];
    };
    for (const std::string bad : {"denoise=1", "denoise=", "denoise=ON", "denoise=on&spp=0"}) {
        const auto r = client.Post("/settings?" + t + "&" + bad, "", "text/plain");
        ASSERT_TRUE(r) << bad;
        EXPECT_EQ(r->status, 400) << bad;
    }
    const Rgb8 raw = image();
    EXPECT_EQ(bytes_apart(raw, s.sombra_render_png("--spp 8")), 0);

    // On: the passes began without the denoiser's layers, so they start again with them.
    const nlohmann::json on = post("denoise=on");
    EXPECT_TRUE(on["denoise"].get<bool>());
    EXPECT_GT(on["frame"]["generation"].get<int>(), raw_done["generation"].get<int>());
    const std::vector<nlohmann::json> events = s.read_events_until(denoised_to_the_end);
    ASSERT_TRUE(denoised_to_the_end(events));
    EXPECT_EQ(events.back()["denoised_spp"], 8);
    for (const nlohmann::json& e : events) {
        if (e["denoised"].get<int>() > 0) {
            EXPECT_GE(e["denoised_spp"].get<int>(), 2);
        }
    }
    const Rgb8 denoised = image();
    EXPECT_EQ(bytes_apart(denoised, s.sombra_render_png("--spp 8 --denoise")), 0);
    EXPECT_GT(bytes_apart(denoised, raw), 0);  // the denoised image is what is served

    // Off: the raw image again, the passes where they were.
    const nlohmann::json off = post("denoise=off");
    EXPECT_FALSE(off["denoise"].get<bool>());
    EXPECT_EQ(off["frame"]["generation"], events.back()["generation"]);
    EXPECT_EQ(off["frame"]["denoised"], 0);
    EXPECT_EQ(bytes_apart(image(), raw), 0);

    // On again: the passes gathered the layers, so the last is denoised without a restart.
    const nlohmann::json again = post("denoise=on");
    EXPECT_EQ(again["frame"]["generation"], events.back()["generation"]);
    ASSERT_TRUE(denoised_to_the_end(s.read_events_until(denoised_to_the_end)));
    EXPECT_EQ(bytes_apart(image(), denoised), 0);

    // One sample a pixel: nothing to denoise, the raw image shows.
    post("spp=1");
    const nlohmann::json one = s.wait_done();
    EXPECT_TRUE(one["denoise"].get<bool>());
    EXPECT_EQ(one["denoised"], 0);
    EXPECT_EQ(bytes_apart(image(), s.sombra_render_png("--spp 1")), 0);
}

// `sombra view --denoise`: the switch is on from the first pass, which
// gathers the denoiser's layers, so nothing restarts.
TEST(ViewServer, StartsWithTheDenoiseSwitchOnWhenAsked) {
    ServedScene s(8, "", 32, 24, std::nullopt, /*denoise=*/true);
    const auto denoised_to_the_end = [](const std::vector<nlohmann::json>& e) {
        return !e.empty() && e.back()["done"].get<bool>() && e.back()["denoised"] == e.back()["version"];
    };
    const std::vector<nlohmann::json> events = s.read_events_until(denoised_to_the_end);
    ASSERT_TRUE(denoised_to_the_end(events));
    EXPECT_TRUE(events.back()["denoise"].get<bool>());
    EXPECT_EQ(events.back()["generation"], 1);
    EXPECT_EQ(events.back()["denoised_spp"], 8);
    httplib::Client client("127.0.0.1", s.port());
    const auto r = client.Get("/image.png?token=" + std::string(kToken));
    ASSERT_TRUE(r);
    EXPECT_EQ(bytes_apart(decode_png(r->body), s.sombra_render_png("--spp 8 --denoise")), 0);
}

TEST(ViewServer, ExplainsAPixelWithTheRendersValue) {
    ServedScene s(1);  // one sample a pixel: the pixel's value is sample 0's
    s.wait_done();
    const std::shared_ptr<const Film> image = s.server().render().latest().image;
    ASSERT_TRUE(image);
    httplib::Client client("127.0.0.1", s.port());
    const auto r = client.Get("/explain?token=" + std::string(kToken) + "&x=16&y=12");
    ASSERT_TRUE(r);
    ASSERT_EQ(r->status, 200) << r->body;
    const nlohmann::json story = nlohmann::json::parse(r->body);
    const Vec3 value{story["json"]["value"][0].get<float>(), story["json"]["value"][1].get<float>(),
                     story["json"]["value"][2].get<float>()};
    const Vec3 pixel = image->at(16, 12);
    EXPECT_EQ(value.x, pixel.x);
    EXPECT_EQ(value.y, pixel.y);
    EXPECT_EQ(value.z, pixel.z);
    EXPECT_GT(pixel.x, 0.0f);
    EXPECT_EQ(story["json"]["pixel"], nlohmann::json::array({16, 12}));
    EXPECT_NE(story["text"].get<std::string>().find("16"), std::string::npos);
    EXPECT_TRUE(story["svg"].get<std::string>().starts_with("<?xml") ||
                story["svg"].get<std::string>().starts_with("<svg"));
    for (const std::string bad : {"x=32&y=0", "x=0&y=24", "x=-1&y=0", "y=3", "x=1&y=1&sample=1"}) {
        const auto b = client.Get("/explain?token=" + std::string(kToken) + "&" + bad);
        ASSERT_TRUE(b) << bad;
        EXPECT_EQ(b->status, 400) << bad;
    }
}

TEST(ViewServer, AClientThatStopsReadingStallsNothing) {
    // Path tracing a larger image to many samples: passes go on for minutes.
    ServedScene s(65536, R"("integrator": "path")", 256, 192);
    // Event streams that are opened and never read: all but one the server takes.
    std::vector<int> stalled;
    for (int k = 0; k < kMaxViewStreams - 1; ++k)
        stalled.push_back(view_test::open_unread_stream(s.port(), "/events?token=" + std::string(kToken)));
    // Another client still sees the passes come, and a second tab the same render.
    const std::vector<nlohmann::json> a = s.read_events(3);
    ASSERT_GE(a.size(), 3u);
    EXPECT_LT(a[0]["version"].get<int>(), a[2]["version"].get<int>());
    httplib::Client client("127.0.0.1", s.port());
    const auto state = client.Get("/state?token=" + std::string(kToken));
    ASSERT_TRUE(state);
    EXPECT_EQ(state->status, 200);
    for (int fd : stalled) ::close(fd);
}

}  // namespace
}  // namespace sombra
