// What the viewer's tests share: a scene served in-process on a free port,
// raw sockets for requests no well-behaved client sends, the event stream
// read as JSON, and `sombra render` of the same scene for comparison.
#pragma once

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <httplib.h>
#include <netinet/in.h>
#include <stb_image.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "accel/accel.h"
#include "io/scene_json/scene_file.h"
#include "view/view_server.h"

namespace sombra::view_test {

namespace fs = std::filesystem;

inline constexpr const char* kToken = "00112233445566778899aabbccddeeff";

// A socket connected to 127.0.0.1:port with 10-second send and receive time-outs, or -1.
inline int connect_loopback(int port, int receive_buffer = 0) {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    if (fd < 0) return -1;
    const timeval limit{10, 0};
    ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &limit, sizeof limit);
    ::setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &limit, sizeof limit);
    if (receive_buffer > 0) ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &receive_buffer, sizeof receive_buffer);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
        ::close(fd);
        return -1;
    }
    return fd;
}

// Sends `request` as it is and returns the server's first answer: its
// head and, when it says its Content-Length, that much body ("" when it
// answers nothing before closing or 10 s pass).
inline std::string raw_request(int port, const std::string& request) {
    const int fd = connect_loopback(port);
    EXPECT_GE(fd, 0);
    if (fd < 0) return {};
    [[maybe_unused]] const ssize_t sent = ::send(fd, request.data(), request.size(), MSG_NOSIGNAL);
    std::string answer;
    char buffer[4096];
    for (ssize_t got; (got = ::recv(fd, buffer, sizeof buffer, 0)) > 0;) {
        answer.append(buffer, std::size_t(got));
        const std::size_t head = answer.find("\r\n\r\n");
        if (head == std::string::npos) continue;
        const std::size_t length = answer.find("Content-Length: ");
        if (length == std::string::npos || length > head) continue;  // read until the server closes
        if (answer.size() >= head + 4 + std::stoul(answer.substr(length + 16))) break;
    }
    ::close(fd);
    return answer;
}

// Opens GET `path` with a tiny receive buffer and never reads: a stalled browser tab.
inline int open_unread_stream(int port, const std::string& path) {
    const int fd = connect_loopback(port, 1024);
    const std::string request = "GET " + path + " HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) + "\r\n\r\n";
    if (fd >= 0) [[maybe_unused]]
        const ssize_t sent = ::send(fd, request.data(), request.size(), MSG_NOSIGNAL);
    return fd;
}

struct Rgb8 {
    int width = 0, height = 0;
    std::vector<unsigned char> pixels;
};

inline Rgb8 decode_png(const std::string& bytes) {
    Rgb8 image;
    int channels = 0;
    unsigned char* data =
        stbi_load_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<int>(bytes.size()),
                              &image.width, &image.height, &channels, 3);
    if (data == nullptr) return {};
    image.pixels.assign(data, data + std::size_t(image.width) * std::size_t(image.height) * 3);
    stbi_image_free(data);
    return image;
}

// A lit unit square seen from the front, width × height pixels at `spp` (more
// "render" members in `render_extra`), loaded and served on a free port;
// with `ortho_half_height`, through an orthographic camera of that
// half-height (as a glTF file's: scene files have none).
class ServedScene {
public:
    explicit ServedScene(int spp, const std::string& render_extra = "", int width = 32, int height = 24,
                         std::optional<float> ortho_half_height = std::nullopt, bool denoise = false) {
        dir_ = fs::temp_directory_path() / ("sombra-view-" + std::to_string(::getpid()) + "-" +
                                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        std::ofstream(dir_ / "square.obj") << "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n";
        std::string render = R"({"width": )" + std::to_string(width) + R"(, "height": )" + std::to_string(height) +
                             R"(, "spp": )" + std::to_string(spp);
        if (!render_extra.empty()) render += ", " + render_extra;
        std::ofstream(dir_ / "scene.json")
            << R"({"render": )" << render << R"(}, "camera": {"origin": [0, 0, 4], "look_at": [0, 0, 0], "fov": 40},
                 "materials": {"grey": {"type": "diffuse", "kd": [0.5, 0.5, 0.5]}},
                 "lights": [{"type": "point", "position": [0.5, 0.5, 3], "intensity": [5, 5, 5]}],
                 "objects": [{"file": "square.obj", "material": "grey"}]})";
        Diagnostics diag;
        loaded_ = std::make_unique<LoadedScene>(load_scene_file(dir_ / "scene.json", diag));
        if (ortho_half_height) {
            loaded_->scene.camera.projection = CameraSpec::Projection::Orthographic;
            loaded_->scene.camera.ortho_half_height = *ortho_half_height;
        }
        accel_ = std::make_unique<Accel>(make_accel(loaded_->scene, AccelKind::Bvh));
        ViewServerOptions options;
        options.initial = ViewSettings{loaded_->scene.camera, loaded_->settings};
        options.threads = 2;
        options.scene_file = "scene.json";
        options.token = kToken;
        options.denoise = denoise;
        server_ = std::make_unique<ViewServer>(loaded_->scene, *accel_, options);
        thread_ = std::thread([this] { server_->run(); });
    }
    ~ServedScene() {
        server_->stop();
        thread_.join();
        server_.reset();
        fs::remove_all(dir_);
    }
    ServedScene(const ServedScene&) = delete;
    ServedScene& operator=(const ServedScene&) = delete;

    int port() const { return server_->port(); }
    ViewServer& server() { return *server_; }

    // The "pass" events of /events until `enough` says stop (or 20 s pass), as JSON.
    template <class Enough>
    std::vector<nlohmann::json> read_events_until(Enough enough) {
        httplib::Client client("127.0.0.1", port());
        client.set_read_timeout(20, 0);
        std::vector<nlohmann::json> events;
        std::string buffer;
        const auto start = std::chrono::steady_clock::now();
        client.Get("/events?token=" + std::string(kToken), [&](const char* data, std::size_t size) {
            buffer.append(data, size);
            for (std::size_t end; (end = buffer.find("\n\n")) != std::string::npos;) {
                const std::string block = buffer.substr(0, end);
                buffer.erase(0, end + 2);
                const std::size_t at = block.find("data: ");
                if (block.starts_with("event: pass") && at != std::string::npos)
                    events.push_back(nlohmann::json::parse(block.substr(at + 6)));
            }
            return !enough(events) && std::chrono::steady_clock::now() - start < std::chrono::seconds(20);
        });
        return events;
    }
    // The first `count` events that carry an image.
    std::vector<nlohmann::json> read_events(std::size_t count) {
        std::vector<nlohmann::json> with_image;
        read_events_until([&](const std::vector<nlohmann::json>& events) {
            with_image.clear();
            for (const auto& e : events)
                if (e["version"].get<int>() > 0) with_image.push_back(e);
            return with_image.size() >= count;
        });
        return with_image;
    }
    // The event that says the passes reached their spp.
    nlohmann::json wait_done() {
        const std::vector<nlohmann::json> events = read_events_until(
            [](const std::vector<nlohmann::json>& e) { return !e.empty() && e.back()["done"].get<bool>(); });
        EXPECT_FALSE(events.empty());
        EXPECT_TRUE(!events.empty() && events.back()["done"].get<bool>());
        return events.empty() ? nlohmann::json{} : events.back();
    }

    // `sombra render` of the same scene with `args`, decoded.
    Rgb8 sombra_render_png(const std::string& args) {
        const fs::path out = dir_ / "render.png";
        const std::string cmd = "cd '" + dir_.string() + "' && '" + std::string(SOMBRA_EXE) +
                                "' render scene.json -o render.png --quiet " + args;
        EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
        std::ifstream in(out, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        return decode_png(bytes);
    }

private:
    fs::path dir_;
    std::unique_ptr<LoadedScene> loaded_;
    std::unique_ptr<Accel> accel_;
    std::unique_ptr<ViewServer> server_;
    std::thread thread_;
};

}  // namespace sombra::view_test
