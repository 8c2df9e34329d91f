#include "view/view_server.h"

#include <dirent.h>
#include <httplib.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/stat.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <optional>
#include <string_view>
#include <thread>

#include "core/error.h"
#include "view/request_guard.h"
#include "view/view_context.h"

namespace sombra {

namespace {

// The reason a request the routes never saw was refused, for the body.
std::string error_text(int status) {
    switch (status) {
        case 400: return "400 bad request: the request could not be read (a malformed request line, header or body)";
        case 404:
            return "404 not found: no such page (the viewer serves /, /state, /image.png, /image.exr, /events, "
                   "/explain, POST /camera and POST /settings)";
        case 405: return "405 method not allowed: GET the pages, POST /camera and /settings";
        case 413: return "413 payload too large: a body holds at most " + std::to_string(kMaxViewBody) + " bytes";
        default: return std::to_string(status);
    }
}

// Shuts down every TCP connection of this process whose local end is
// 127.0.0.1:`port` (those the server accepted; the listening socket has no
// peer): a request thread blocked writing to a client that stopped reading,
// or waiting on a kept-alive connection, then returns at once instead of
// after httplib's 5-second timeouts, and Ctrl-C ends the viewer at once
// (spec §20). httplib 0.11 keeps its connections' sockets to itself, so
// they are found among the process's open files.
void shut_down_connections(int port) {
    DIR* fds = ::opendir("/proc/self/fd");
    if (fds == nullptr) return;
    const int own = ::dirfd(fds);
    while (const dirent* entry = ::readdir(fds)) {
        char* end = nullptr;
        const long fd = std::strtol(entry->d_name, &end, 10);
        if (end == entry->d_name || *end != '\0' || fd == own) continue;
        struct stat info {};
        if (::fstat(static_cast<int>(fd), &info) != 0 || !S_ISSOCK(info.st_mode)) continue;
        sockaddr_in local{}, peer{};
        socklen_t local_size = sizeof local, peer_size = sizeof peer;
        if (::getsockname(static_cast<int>(fd), reinterpret_cast<sockaddr*>(&local), &local_size) != 0 ||
            local.sin_family != AF_INET || ntohs(local.sin_port) != port)
            continue;
        if (::getpeername(static_cast<int>(fd), reinterpret_cast<sockaddr*>(&peer), &peer_size) != 0) continue;
        ::shutdown(static_cast<int>(fd), SHUT_RDWR);
    }
    ::closedir(fds);
}

// Request threads: every event stream holds one while it is open, and the
// page's other requests need a few beside them.
constexpr std::size_t kRequestThreads = kMaxViewStreams + 8;

// Sent with every answer: nothing is cached or sniffed, the token in the
// URL never leaves in a Referer, and the page runs only its own inline
// script and talks only to this server.
httplib::Headers security_headers() {
    return {{"Cache-Control", "no-store"},
            {"X-Content-Type-Options", "nosniff"},
            {"Referrer-Policy", "no-referrer"},
            {"X-Frame-Options", "DENY"},
            {"Content-Security-Policy",
             "default-src 'none'; script-src 'unsafe-inline'; style-src 'unsafe-inline'; img-src 'self' data: "
             "blob:; connect-src 'self'; frame-ancestors 'none'"}};
}

}  // namespace

struct ViewServer::Impl {
    Impl(const Scene& scene, const Accel& accel, const ViewServerOptions& o)
        : live(scene, accel, o.initial, o.threads, o.light_selection, o.denoise),
          context{scene, live, o.scene_file, o.display},
          token(o.token.empty() ? make_view_token() : o.token) {}

    LiveRender live;
    ViewContext context;
    std::string token;
    int port = 0;
    std::atomic<bool> stopping{false};
    std::atomic<bool> serving{false};  // run() is inside listen_after_bind
    httplib::Server server;
};

ViewServer::ViewServer(const Scene& scene, const Accel& accel, const ViewServerOptions& o)
    : impl_(std::make_unique<Impl>(scene, accel, o)) {
    httplib::Server& server = impl_->server;
    server.new_task_queue = [] { return new httplib::ThreadPool(kRequestThreads); };
    server.set_payload_max_length(kMaxViewBody);
    server.set_default_headers(security_headers());
    server.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
        // httplib hands out copies: they live here while the views below look at them.
        const std::string host = req.get_header_value("Host");
        const std::string origin_text = req.get_header_value("Origin");
        const std::string token_text = req.get_param_value("token");
        std::optional<std::string_view> origin, token;
        if (req.has_header("Origin")) origin = origin_text;
        if (req.has_param("token")) token = token_text;
        const Refusal refusal = check_request(impl_->token, impl_->port, host, origin, token);
        if (refusal == Refusal::None) return httplib::Server::HandlerResponse::Unhandled;
        res.status = 403;
        res.set_content(std::string("403 forbidden: ") + refusal_text(refusal) + "\n", "text/plain");
        return httplib::Server::HandlerResponse::Handled;
    });
    server.set_error_handler([](const httplib::Request&, httplib::Response& res) {
        if (res.body.empty()) res.set_content(error_text(res.status) + "\n", "text/plain");
    });
    server.set_exception_handler([](const httplib::Request&, httplib::Response& res, const std::exception_ptr&) {
        res.status = 500;
        res.set_content("500 internal error\n", "text/plain");
    });
    add_view_routes(server, impl_->context);
    add_explain_route(server, impl_->context);

    if (o.port == 0) {
        impl_->port = server.bind_to_any_port("127.0.0.1");
        if (impl_->port <= 0) throw Error("--port", "no free port on 127.0.0.1");
    } else {
        if (!server.bind_to_port("127.0.0.1", o.port))
            throw Error("--port", "cannot listen on 127.0.0.1:" + std::to_string(o.port) + " (in use?)");
        impl_->port = o.port;
    }
}

ViewServer::~ViewServer() { stop(); }

int ViewServer::port() const { return impl_->port; }
const std::string& ViewServer::token() const { return impl_->token; }
std::string ViewServer::url() const {
    return "http://127.0.0.1:" + std::to_string(impl_->port) + "/?token=" + impl_->token;
}
LiveRender& ViewServer::render() { return impl_->live; }

bool ViewServer::run() {
    impl_->serving.store(true);
    const bool ok = impl_->stopping.load() || impl_->server.listen_after_bind();
    impl_->serving.store(false);
    return ok;
}

void ViewServer::stop() {
    impl_->stopping.store(true);
    impl_->live.stop();  // wakes the event streams, which then end
    // httplib's stop() does nothing before listening has begun: a stop that
    // comes while run() is entering it waits the moment until it has.
    while (impl_->serving.load() && !impl_->server.is_running())
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    impl_->server.stop();
    shut_down_connections(impl_->port);
}

}  // namespace sombra
