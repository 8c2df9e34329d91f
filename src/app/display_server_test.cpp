// `sombra render --display-server HOST:PORT` (spec §20) against a listener
// of the test's own on 127.0.0.1 that decodes tev's packets as tev would
// (image/tev_test_decoder.h): the image it paints ends equal to the file
// written, a render streams more than once, and a viewer that is absent or
// stops reading costs one warning, not the render.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <thread>

#include "cli_test_fixture.h"
#include "image/tev_test_decoder.h"

namespace {

using namespace sombra::cli_test;

// A TCP socket listening on 127.0.0.1 at a port the system picks.
struct Listener {
    int fd = -1;
    int port = 0;
    Listener() {
        fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
        sockaddr_in a{};
        a.sin_family = AF_INET;
        a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        socklen_t len = sizeof a;
        if (fd < 0 || bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 || listen(fd, 1) != 0 ||
            getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) != 0)
            ADD_FAILURE() << "cannot listen on 127.0.0.1";
        port = ntohs(a.sin_port);
    }
    ~Listener() {
        if (fd >= 0) close(fd);
    }
    Listener(const Listener&) = delete;
    Listener& operator=(const Listener&) = delete;
    std::string address() const { return "127.0.0.1:" + std::to_string(port); }
};

// Accepts one connection within `seconds` and feeds what arrives to `decoder` until it closes.
void receive(const Listener& l, sombra::testing::TevDecoder& decoder, std::string& error, int seconds = 30) {
    pollfd p{l.fd, POLLIN, 0};
    if (poll(&p, 1, seconds * 1000) != 1) {
        error = "nobody connected";
        return;
    }
    const int c = accept(l.fd, nullptr, nullptr);
    std::vector<std::uint8_t> buffer(1 << 16);
    try {
        for (ssize_t n; (n = read(c, buffer.data(), buffer.size())) > 0;)
            decoder.feed(buffer.data(), static_cast<std::size_t>(n));
    } catch (const std::exception& e) {
        error = e.what();
    }
    close(c);
}

class DisplayServer : public CliFixture {};

TEST_F(DisplayServer, TevPaintsTheImageTheFileHolds) {
    write_text(dir_ / "s.json", scene(R"({"width": 40, "height": 30, "spp": 64})"));
    Listener tev;
    sombra::testing::TevDecoder decoder;
    std::string error;
    std::thread viewer([&] { receive(tev, decoder, error); });
    const RunResult r = run("render s.json -o out.pfm --integrator path --quiet --display-server " + tev.address());
    viewer.join();
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    ASSERT_EQ(error, "");
    ASSERT_EQ(decoder.images.count("out.pfm"), 1u);
    const sombra::testing::TevImage& image = decoder.images["out.pfm"];
    EXPECT_EQ(image.creates, 1);
    EXPECT_GE(image.updates, 2);  // the first pass, and the final image
    EXPECT_EQ(image.channels, (std::vector<std::string>{"R", "G", "B"}));
    const Pfm pfm = read_pfm(dir_ / "out.pfm");
    ASSERT_EQ(image.width, pfm.width);
    ASSERT_EQ(image.height, pfm.height);
    // Float for float; tev's rows run top to bottom, the PFM's bottom to top.
    std::vector<float> top_first;
    for (int y = pfm.height - 1; y >= 0; --y)
        top_first.insert(top_first.end(), pfm.rgb.begin() + std::ptrdiff_t(y) * pfm.width * 3,
                         pfm.rgb.begin() + std::ptrdiff_t(y + 1) * pfm.width * 3);
    EXPECT_EQ(image.values, top_first);
    EXPECT_FALSE(decoder.has_partial_packet());

    // Streaming took the render in passes; the image is the one-pass render's, bit for bit.
    const RunResult plain = run("render s.json -o plain.pfm --integrator path --quiet");
    ASSERT_EQ(plain.status, 0) << plain.err;
    EXPECT_EQ(read_text(dir_ / "out.pfm"), read_text(dir_ / "plain.pfm"));
}

TEST_F(DisplayServer, NobodyListeningIsOneWarningAndTheRenderGoesOn) {
    write_text(dir_ / "s.json", scene());
    int port = 0;
    {
        const Listener closed;  // a port that was free a moment ago, now refusing
        port = closed.port;
    }
    const RunResult r = run("render s.json -o out.png --quiet --display-server 127.0.0.1:" + std::to_string(port));
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir_ / "out.png"));
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.rfind("sombra: warning: display server 127.0.0.1:" + std::to_string(port) + ": ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("rendering without it"), std::string::npos) << r.err;
}

TEST_F(DisplayServer, AViewerThatStopsReadingIsDroppedWithOneWarning) {
    // 1000 × 1000 RGB floats are 12 MB an image, more than the sockets
    // buffer: sends block, time out after a second, and the render goes on alone.
    write_text(dir_ / "s.json", scene(R"({"width": 1000, "height": 1000, "spp": 2})"));
    Listener tev;
    std::atomic<bool> done{false};
    std::thread stalled([&] {
        pollfd p{tev.fd, POLLIN, 0};
        if (poll(&p, 1, 30000) != 1) return;
        const int c = accept(tev.fd, nullptr, nullptr);
        int small = 4096;
        setsockopt(c, SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
        while (!done.load()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
        close(c);
    });
    const RunResult r = run("render s.json -o out.png --quiet --display-server " + tev.address());
    done = true;
    stalled.join();
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir_ / "out.png"));
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("it stopped reading; rendering without it"), std::string::npos) << r.err;
}

TEST_F(DisplayServer, AMalformedAddressIsACommandLineError) {
    write_text(dir_ / "s.json", scene());
    for (const char* bad : {"localhost", "127.0.0.1:", ":14158", "127.0.0.1:0", "127.0.0.1:65536", "1:2:3",
                            "[::1]14158", "127.0.0.1:14x"}) {
        const RunResult r = run(std::string("render s.json -o out.png --display-server ") + shell_quote(bad));
        EXPECT_EQ(r.status, 2) << bad << ": " << r.err;
        EXPECT_EQ(r.err.rfind("sombra: error: command line: --display-server", 0), 0u) << bad << ": " << r.err;
        EXPECT_FALSE(fs::exists(dir_ / "out.png"));
    }
}

}  // namespace
