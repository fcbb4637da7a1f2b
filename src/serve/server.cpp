// SPDX-License-Identifier: GPL-3.0-or-later
#include "serve/server.hpp"

#include <algorithm>
#include <boost/asio.hpp>
#include <boost/beast.hpp>
#include <chrono>
#include <deque>
#include <fstream>
#include <list>
#include <map>
#include <ostream>
#include <sstream>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/interrupt.hpp"
#include "serve/compare_loop.hpp"
#include "serve/hand_message.hpp"
#include "serve/hand_recording.hpp"
#include "serve/page_messages.hpp"
#include "serve/request_guard.hpp"
#include "serve/scalpel.hpp"

namespace roifem::serve {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;

namespace {

constexpr std::size_t largest_frame = 1024;      // bytes: a hand message has 32 at most
constexpr long most_messages_per_second = 2000;  // per client
constexpr std::size_t most_queued_frames = 4;    // per client: a slow page skips frames

struct Outgoing {
  std::string data;
  bool binary = false;
};

/// What a client had refused within the current second, for one log line.
struct Refusals {
  long malformed = 0, over_rate = 0, watcher = 0, queue = 0;
  long frames_skipped = 0;  ///< not a refusal: frames a slow page did not get
  std::string last_malformed;
  long total() const { return malformed + over_rate + watcher + queue; }
};

}  // namespace

class WsSession;

class Server::Impl {
 public:
  Impl(LiveScene& scene, PhysicsLoop& physics, AssetFiles assets, ServeOptions options, std::ostream& log)
      : scene_(scene),
        physics_(physics),
        assets_(std::move(assets)),
        options_(std::move(options)),
        log_(log),
        acceptor_(io_),
        frame_timer_(io_),
        collect_timer_(io_),
        second_timer_(io_),
        ticks_(scene.dt()) {
    check_listen_address(options_.host);
    beast::error_code ec;
    const auto address = net::ip::make_address(options_.host, ec);
    const tcp::endpoint endpoint(address, options_.port);
    acceptor_.open(endpoint.protocol(), ec);
    if (!ec) acceptor_.set_option(net::socket_base::reuse_address(true), ec);
    if (!ec) acceptor_.bind(endpoint, ec);
    if (!ec) acceptor_.listen(net::socket_base::max_listen_connections, ec);
    if (ec)
      throw InputError(
          format("serve: cannot listen on %s port %u: %s", options_.host.c_str(), options_.port, ec.message().c_str()));
    snapshot_.model = scene_.default_model();  // the physics' first, until it publishes
    mesh_for(snapshot_.model);
  }

  unsigned short port() const { return acceptor_.local_endpoint().port(); }

  int run() {
    const InterruptGuard interrupts;
    accept();
    on_frame_timer();
    on_second_timer();
    physics_.start();
    io_.run();
    physics_.stop();
    finish_grab();
    return interrupts.signal_received();
  }

  void stop() {
    net::post(io_, [this] { shut_down(); });
  }

  // Called by the sessions (all on the io thread).
  const AssetFiles& assets() const { return assets_; }
  std::ostream& log() { return log_; }
  bool origin_allowed(const http::request<http::string_body>& request) const;
  bool host_allowed(const http::request<http::string_body>& request) const;
  void joined(const std::shared_ptr<WsSession>& session);
  void left(WsSession& session);
  void received(WsSession& session, const std::string& bytes, bool text);

 private:
  LiveScene& scene_;
  PhysicsLoop& physics_;
  AssetFiles assets_;
  ServeOptions options_;
  std::ostream& log_;
  net::io_context io_{1};
  tcp::acceptor acceptor_;
  net::steady_timer frame_timer_, collect_timer_, second_timer_;
  std::list<std::shared_ptr<WsSession>> sessions_;  ///< in the order they joined: the first drives
  std::shared_ptr<const Outgoing> mesh_;            ///< the surface the page draws, and which
  std::shared_ptr<const SurfaceView> mesh_view_;    ///< (held: a new surface never takes its address)
  std::vector<LiveCut> cuts_;                       ///< every cut the physics took, in order (replays)
  bool stopping_ = false;
  long next_client_ = 1;
  TickWindow ticks_;
  std::vector<float> tick_seconds_;
  std::vector<HandSample> samples_;
  PhysicsSnapshot snapshot_;
  std::vector<float> displacement_;
  GrabRecord grab_;
  int saved_ = 0;
  double last_second_ = 0;
  // The display: when the static part's surface was last recovered, and what frames cost.
  double next_recovery_ = 0, frame_ms_ = 0, recovery_ms_ = 0;
  std::uint32_t recovered_grab_ = 0;
  std::size_t recovered_model_ = 0;
  // Compare: the full model on the same hand, and the live model's force error against it.
  std::unique_ptr<CompareLoop> compare_;
  std::vector<CompareSample> compared_;
  CompareFigures comparison_;
  std::uint32_t compare_lost_grab_ = 0;
  const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();

  void accept();
  /// mesh_ for model k's surface; whether it changed.
  bool mesh_for(std::size_t k);
  /// A scalpel's stroke: the tetrahedra its blade crosses, to the physics.
  void cut(HandMessage message);
  /// Cuts the physics took: the display's surfaces follow.
  void follow_cuts();
  void on_frame_timer();
  void collect_frame(int tries);
  /// What the physics left since the last frame: tick times, notices, the hand's samples (the grab
  /// and Compare follow them).
  void take_what_came(double now);
  /// The snapshot's surface and state, to every client.
  void send_frame(double now);
  void on_second_timer();
  /// To every client; a binary frame is dropped for a client that is behind (a mesh never).
  void broadcast(const std::shared_ptr<const Outgoing>& message, bool droppable = true);
  /// Logs what the client had refused since the last report, in one line, and starts counting afresh.
  void report_refusals(WsSession& session);
  void say(const std::string& text);
  /// The grab's samples as they come; a new grab finishes the one before.
  void follow_grab();
  /// Writes the grab in progress for replay (with --record, or when the page asks).
  void finish_grab();
  void save_grab(const std::string& why);
  void set_compare(bool on);
  /// The reference's forces that came, against the live grab's at the same ticks.
  void follow_comparison();
  void shut_down();
  WsSession* driver() const { return sessions_.empty() ? nullptr : sessions_.front().get(); }
};

class WsSession : public std::enable_shared_from_this<WsSession> {
 public:
  WsSession(tcp::socket socket, Server::Impl& server, long id) : ws_(std::move(socket)), server_(server), id_(id) {}
  long id() const { return id_; }
  Refusals& refusals() { return refusals_; }
  long& messages_this_second() { return messages_this_second_; }

  void start(const http::request<http::string_body>& request) {
    ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    ws_.read_message_max(largest_frame);
    ws_.async_accept(request, [self = shared_from_this()](beast::error_code ec) {
      if (ec) return;
      self->open_ = true;
      self->server_.joined(self);
      self->read();
    });
  }
  /// Queues a message; a frame (droppable) is skipped while the client is behind.
  void send(const std::shared_ptr<const Outgoing>& message, bool droppable) {
    if (!open_) return;
    if (droppable && queue_.size() >= most_queued_frames) {
      ++refusals_.frames_skipped;
      return;
    }
    queue_.push_back(message);
    if (queue_.size() == 1) write_next();
  }
  void close() {
    if (!open_) return;
    open_ = false;
    ws_.async_close(websocket::close_code::going_away, [self = shared_from_this()](beast::error_code) {});
  }

 private:
  websocket::stream<beast::tcp_stream> ws_;
  Server::Impl& server_;
  long id_;
  beast::flat_buffer buffer_;
  std::deque<std::shared_ptr<const Outgoing>> queue_;
  bool open_ = false;
  Refusals refusals_;
  long messages_this_second_ = 0;

  void read() {
    ws_.async_read(buffer_, [self = shared_from_this()](beast::error_code ec, std::size_t) {
      if (ec) {
        if (ec != websocket::error::closed && ec != net::error::operation_aborted && ec != net::error::eof)
          self->server_.log() << "serve: client " << self->id_ << " closed: " << ec.message() << "\n" << std::flush;
        self->open_ = false;
        self->server_.left(*self);
        return;
      }
      const std::string bytes = beast::buffers_to_string(self->buffer_.data());
      self->buffer_.consume(self->buffer_.size());
      self->server_.received(*self, bytes, self->ws_.got_text());
      self->read();
    });
  }
  void write_next() {
    ws_.binary(queue_.front()->binary);
    ws_.async_write(net::buffer(queue_.front()->data), [self = shared_from_this()](beast::error_code ec, std::size_t) {
      if (ec) {
        self->queue_.clear();
        return;
      }
      self->queue_.pop_front();
      if (!self->queue_.empty() && self->open_) self->write_next();
    });
  }
};

/// One HTTP connection: files, or the upgrade to the WebSocket.
class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(tcp::socket socket, Server::Impl& server, long id) : stream_(std::move(socket)), server_(server), id_(id) {}
  void start() { read(); }

 private:
  beast::tcp_stream stream_;
  Server::Impl& server_;
  long id_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;

  void read() {
    parser_.emplace();
    parser_->header_limit(8192);
    parser_->body_limit(8192);
    stream_.expires_after(std::chrono::seconds(30));
    http::async_read(stream_, buffer_, *parser_, [self = shared_from_this()](beast::error_code ec, std::size_t) {
      if (ec) {
        if (ec != http::error::end_of_stream && ec != beast::error::timeout)
          self->server_.log() << "serve: refused a request: " << ec.message() << "\n" << std::flush;
        beast::error_code ignored;
        self->stream_.socket().shutdown(tcp::socket::shutdown_both, ignored);
        return;
      }
      self->on_request(self->parser_->release());
    });
  }

  void on_request(const http::request<http::string_body>& request) {
    if (!server_.host_allowed(request)) {
      server_.log() << "serve: refused a request for host '" << request[http::field::host]
                    << "' (not this machine's loopback or listening address: a rebound name?)\n"
                    << std::flush;
      return respond(request, http::status::forbidden, "not a host this server answers for\n");
    }
    if (websocket::is_upgrade(request)) {
      if (request.target() != "/ws") return respond(request, http::status::not_found, "no WebSocket here: it is /ws\n");
      if (!server_.origin_allowed(request)) {
        server_.log() << "serve: refused a WebSocket from origin '" << request[http::field::origin] << "'\n" << std::flush;
        return respond(request, http::status::forbidden, "another page's origin\n");
      }
      stream_.expires_never();
      std::make_shared<WsSession>(stream_.release_socket(), server_, id_)->start(request);
      return;
    }
    if (request.method() != http::verb::get && request.method() != http::verb::head)
      return respond(request, http::status::method_not_allowed, "GET or HEAD only\n");
    const auto file = server_.assets().resolve(std::string(request.target()));
    if (!file) {
      server_.log() << "serve: 404 " << request.target() << "\n" << std::flush;
      return respond(request, http::status::not_found, "not found\n");
    }
    std::ifstream in(*file, std::ios::binary);
    std::ostringstream body;
    body << in.rdbuf();
    respond(request, http::status::ok, body.str(), AssetFiles::content_type(*file));
  }

  void respond(const http::request<http::string_body>& request, http::status status, std::string body,
               std::string_view type = "text/plain; charset=utf-8") {
    auto response = std::make_shared<http::response<http::string_body>>(status, request.version());
    response->set(http::field::server, "roifem serve");
    response->set(http::field::content_type, std::string(type));
    response->set(http::field::cache_control, "no-store");
    response->set("X-Content-Type-Options", "nosniff");
    response->keep_alive(request.keep_alive() && status == http::status::ok);
    if (request.method() == http::verb::head)
      response->content_length(body.size());
    else
      response->body() = std::move(body);
    if (request.method() != http::verb::head) response->prepare_payload();
    http::async_write(stream_, *response, [self = shared_from_this(), response](beast::error_code ec, std::size_t) {
      if (!ec && response->keep_alive()) return self->read();
      beast::error_code ignored;
      self->stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
    });
  }
};

namespace {

std::optional<std::string_view> header(const http::request<http::string_body>& request, http::field field) {
  const auto it = request.find(field);
  if (it == request.end()) return std::nullopt;
  return std::string_view(it->value().data(), it->value().size());
}

}  // namespace

bool Server::Impl::origin_allowed(const http::request<http::string_body>& request) const {
  return serve::origin_allowed(header(request, http::field::origin), header(request, http::field::host));
}

bool Server::Impl::host_allowed(const http::request<http::string_body>& request) const {
  return serve::host_allowed(header(request, http::field::host), options_.host);
}

void Server::Impl::accept() {
  acceptor_.async_accept([this](beast::error_code ec, tcp::socket socket) {
    if (stopping_) return;
    if (!ec) {
      // Each frame leaves at once: without this, Nagle's algorithm holds a frame's last segment until
      // the page acknowledges the one before, and while the page sends the hand (its messages carry
      // those acknowledgements) frames arrive in pairs, every other 60 Hz turn.
      beast::error_code ignored;
      socket.set_option(tcp::no_delay(true), ignored);
      std::make_shared<HttpSession>(std::move(socket), *this, next_client_++)->start();
    }
    accept();
  });
}

void Server::Impl::joined(const std::shared_ptr<WsSession>& session) {
  if (stopping_) return session->close();
  const bool drives = sessions_.empty();
  sessions_.push_back(session);
  log_ << "serve: client " << session->id() << " connected, " << (drives ? "drives" : "watches") << "\n" << std::flush;
  session->send(std::make_shared<const Outgoing>(Outgoing{hello_message(scene_, snapshot_.model, drives), false}), false);
  mesh_for(snapshot_.model);
  session->send(mesh_, false);
}

void Server::Impl::left(WsSession& session) {
  report_refusals(session);
  const bool drove = driver() == &session;
  sessions_.remove_if([&](const auto& s) { return s.get() == &session; });
  log_ << "serve: client " << session.id() << " left" << (drove ? " (it drove: its grab is released)" : "") << "\n" << std::flush;
  if (!drove) return;
  physics_.post({.kind = HandKind::release, .sequence = 0, .point_mm = Vec3::Zero(), .model = 0});
  if (WsSession* next = driver()) {
    next->send(std::make_shared<const Outgoing>(Outgoing{role_message(true), false}), false);
    log_ << "serve: client " << next->id() << " drives\n" << std::flush;
  }
}

void Server::Impl::received(WsSession& session, const std::string& bytes, bool text) {
  Refusals& r = session.refusals();
  if (++session.messages_this_second() > most_messages_per_second) {
    ++r.over_rate;
    return;
  }
  if (text) {
    ++r.malformed;
    r.last_malformed = "a text frame (the page sends binary hand messages)";
    return;
  }
  auto decoded = decode_hand_message(std::span(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()));
  if (auto* why = std::get_if<std::string>(&decoded)) {
    ++r.malformed;
    r.last_malformed = *why;
    return;
  }
  if (&session != driver()) {  // one client drives at a time
    ++r.watcher;
    return;
  }
  const HandMessage& message = std::get<HandMessage>(decoded);
  if (message.kind == HandKind::save) return save_grab("the page asked");
  if (message.kind == HandKind::compare) return set_compare(message.model != 0);
  if (message.kind == HandKind::cut) return cut(message);
  if (const std::string refused = physics_.post(message); !refused.empty()) ++r.queue;
}

bool Server::Impl::mesh_for(std::size_t k) {
  std::shared_ptr<const SurfaceView> view = scene_.view_of(k);
  if (view == mesh_view_) return false;
  mesh_ = std::make_shared<const Outgoing>(Outgoing{mesh_message(scene_, *view), true});
  mesh_view_ = std::move(view);
  return true;
}

void Server::Impl::cut(HandMessage message) {
  // The blade's geometry against the whole mesh here, not between two ticks (on the 100k brain it
  // takes some 20 ticks: docs/design-figures.md); which of those tetrahedra are still there is the
  // physics' to say.
  const cutting::Blade blade = scalpel_blade("scalpel", message.point_mm, message.edge_to_mm, message.move_mm, 0, 1);
  try {
    message.crossed = crossed_tetrahedra(blade, scene_.mesh());
  } catch (const InputError& e) {  // a degenerate stroke: refused by the same rule as a [[cut]]'s
    say(std::string("refused cut: ") + e.what());
    return;
  }
  if (const std::string refused = physics_.post(message); !refused.empty()) say("cut " + refused);
}

void Server::Impl::follow_cuts() {
  for (LiveCut& c : physics_.take_cuts()) {
    if (c.whole)
      scene_.show_whole(c.model, std::move(c.fresh));
    else
      scene_.cut_surface(c.model, c.elements);
    next_recovery_ = 0;  // the static part's values on the new surface's vertices
    cuts_.push_back(std::move(c));
  }
}

void Server::Impl::on_frame_timer() {
  if (stopping_) return;
  frame_timer_.expires_after(std::chrono::microseconds(static_cast<long>(1e6 / options_.display_hz)));
  frame_timer_.async_wait([this](beast::error_code ec) {
    if (ec) return;
    physics_.request_snapshot();
    collect_frame(0);
    on_frame_timer();
  });
}

void Server::Impl::collect_frame(int tries) {
  // The physics copies its state at the end of its next tick: look again every 0.5 ms, 40 times at
  // most (an attach or a slow tick; the frame is then skipped), so that a frame is at most a tick old.
  collect_timer_.expires_after(std::chrono::microseconds(500));
  collect_timer_.async_wait([this, tries](beast::error_code ec) {
    if (ec || stopping_) return;
    const bool fresh = physics_.take_snapshot(snapshot_);
    if (!fresh && tries < 40) return collect_frame(tries + 1);
    const double now = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    take_what_came(now);
    if (fresh && !sessions_.empty()) send_frame(now);
  });
}

void Server::Impl::take_what_came(double now) {
  tick_seconds_.clear();
  physics_.drain_tick_seconds(tick_seconds_);
  ticks_.add(tick_seconds_, now);
  for (const std::string& notice : physics_.take_notices()) say(notice);
  follow_cuts();
  follow_grab();
  follow_comparison();
}

void Server::Impl::send_frame(double now) {
  if (mesh_for(snapshot_.model)) broadcast(mesh_, false);  // a cut, or a model with another surface
  const auto built = std::chrono::steady_clock::now();
  if (snapshot_.u.size() > 0) {
    // The static part's surface is recovered (a solve with its factor) at most every 0.1 s and at
    // most 1/40 of the time: the solve reads the whole static factor, which pushes the haptic
    // loop's factor out of the shared cache while it runs, and ticks come late (docs/design-figures.md).
    // The ROI's surface moves every frame.
    const bool recover = snapshot_.grab != recovered_grab_ || snapshot_.model != recovered_model_ || now >= next_recovery_;
    scene_.surface_displacement(snapshot_.model, snapshot_.u, snapshot_.t, recover, displacement_);
    if (recover) {
      const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - built).count();
      next_recovery_ = now + std::max(0.1, 40 * took);
      recovered_grab_ = snapshot_.grab;
      recovered_model_ = snapshot_.model;
      recovery_ms_ = 1e3 * took;
    }
  } else {
    displacement_.assign(3 * mesh_view_->nodes.size(), 0.0F);
  }
  frame_ms_ = 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - built).count();
  broadcast(std::make_shared<const Outgoing>(Outgoing{frame_message(snapshot_, displacement_), true}));
  broadcast(
      std::make_shared<const Outgoing>(Outgoing{state_message(scene_, snapshot_, ticks_.figures(physics_.slips()),
                                                              {frame_ms_, recovery_ms_}, comparison_, !options_.record.empty()),
                                                false}));
}

void Server::Impl::on_second_timer() {
  if (stopping_) return;
  second_timer_.expires_after(std::chrono::milliseconds(100));
  second_timer_.async_wait([this](beast::error_code ec) {
    if (ec) return;
    if (InterruptGuard::signal_received() != 0) {
      log_ << "serve: stopping (signal " << InterruptGuard::signal_received() << ")\n" << std::flush;
      return shut_down();
    }
    const double now = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (now - last_second_ >= 1.0) {
      last_second_ = now;
      for (const auto& session : sessions_) report_refusals(*session);
    }
    on_second_timer();
  });
}

void Server::Impl::report_refusals(WsSession& session) {
  Refusals& r = session.refusals();
  if (r.total() > 0)
    log_ << format(
                "serve: client %ld: refused %ld message(s) in the last second (%ld malformed, %ld over the limit of %ld/s, %ld "
                "from a watcher, %ld with the physics' queue full)%s%s\n",
                session.id(), r.total(), r.malformed, r.over_rate, most_messages_per_second, r.watcher, r.queue,
                r.malformed > 0 ? "; the last malformed: " : "", r.malformed > 0 ? r.last_malformed.c_str() : "")
         << std::flush;
  if (r.frames_skipped > 0)
    log_ << format("serve: client %ld: %ld frame(s) skipped in the last second (the page reads slower than %g Hz)\n",
                   session.id(), r.frames_skipped, options_.display_hz)
         << std::flush;
  r = {};
  session.messages_this_second() = 0;
}

void Server::Impl::broadcast(const std::shared_ptr<const Outgoing>& message, bool droppable) {
  for (const auto& s : sessions_) s->send(message, droppable && message->binary);
}

void Server::Impl::say(const std::string& text) {
  log_ << "serve: " << text << "\n" << std::flush;
  broadcast(std::make_shared<const Outgoing>(Outgoing{notice_message(text), false}));
}

void Server::Impl::follow_grab() {
  samples_.clear();
  physics_.drain_samples(samples_);
  for (const HandSample& s : samples_) {
    if (s.grab != grab_.grab) {
      finish_grab();
      grab_ = GrabRecord{.grab = s.grab, .model = s.model, .center_mm = s.center_mm, .grip_nodes = s.grip_nodes, .samples = {}};
      const auto reference = scene_.reference_of(s.model);
      comparison_ = CompareFigures{.on = compare_ != nullptr};
      if (reference) comparison_.reference = scene_.models()[*reference].name;
      const LiveModel& live = scene_.models()[s.model];
      if (compare_ && live.cuttable())
        say(format("compare: the %s model is the scalpel's and the full model stays whole: nothing to compare",
                   live.name.c_str()));
      else if (compare_ && !reference && live.condensed())
        say(format("compare: no full model with the %s model's law is prepared (--models: full%s): nothing to compare",
                   live.name.c_str(),
                   std::string(model_kind(live.nonlinear() ? ModelKind::neo_hookean : ModelKind::linear).suffix).c_str()));
    }
    grab_.samples.push_back(s);
    if (compare_ && s.grab != compare_lost_grab_ && !compare_->feed(s)) {
      compare_lost_grab_ = s.grab;
      say(format("compare: the full model fell 65,536 ticks behind grab %u: its comparison stops", s.grab));
    }
  }
}

void Server::Impl::finish_grab() {
  if (!options_.record.empty() && grab_.samples.size() > 1) save_grab("the grab ended");
}

void Server::Impl::save_grab(const std::string& why) {
  if (options_.record.empty()) return say("not saved: start the server with --record DIR to keep grabs for replay");
  if (grab_.samples.size() < 2) return say("not saved: no grab yet");
  try {
    grab_.cuts = cuts_of_grab(cuts_, grab_);
    const auto file = write_replay(scene_, grab_, options_.record, format("grab-%03u-%d", grab_.grab, ++saved_));
    say(format("saved (%s): %s, %zu ticks; replay: roifem run %s --out DIR", why.c_str(), file.string().c_str(),
               grab_.samples.size() - 1, file.string().c_str()));
  } catch (const Error& e) {
    say(std::string("not saved: ") + e.what());
  }
}

void Server::Impl::set_compare(bool on) {
  if (on == (compare_ != nullptr)) return;
  if (!on) {
    compare_.reset();
    comparison_ = {};
    return say("compare: off");
  }
  if (std::all_of(scene_.models().begin(), scene_.models().end(), [](const LiveModel& m) { return m.condensed(); }))
    return say("compare: not prepared (start the server with the full model among --models)");
  compare_ = std::make_unique<CompareLoop>(scene_);
  compare_->start();
  compare_lost_grab_ = grab_.grab;  // from the next grab: this one's start is gone
  comparison_ = CompareFigures{.on = true};
  say("compare: on, from the next grab: the full model (with the live model's law) follows the same hand in a thread of its "
      "own");
}

void Server::Impl::follow_comparison() {
  if (!compare_) return;
  if (const std::string why = compare_->failure(); !why.empty()) {
    say("compare: stopped: " + why);
    compare_.reset();
    comparison_ = {};
    return;
  }
  compared_.clear();
  compare_->drain(compared_);
  for (const CompareSample& c : compared_) {
    if (c.grab != grab_.grab) continue;
    const auto k = static_cast<std::size_t>(std::lround(c.t / scene_.dt()));
    if (k >= grab_.samples.size()) continue;
    const Vec3 error = grab_.samples[k].force - c.force;
    comparison_.t = c.t;
    comparison_.reference_force = c.force;
    comparison_.error = error;
    comparison_.largest_error = std::max(comparison_.largest_error, error.norm());
    comparison_.largest_force = std::max(comparison_.largest_force, c.force.norm());
    comparison_.behind_s = grab_.samples.back().t - c.t;
  }
}

void Server::Impl::shut_down() {
  if (stopping_) return;
  stopping_ = true;
  beast::error_code ignored;
  acceptor_.close(ignored);
  frame_timer_.cancel();
  collect_timer_.cancel();
  compare_.reset();
  second_timer_.cancel();
  for (const auto& s : sessions_) {
    report_refusals(*s);
    s->close();
  }
  sessions_.clear();
  // Whatever is still open (an HTTP keep-alive, a closing handshake) ends with the io loop: give
  // it a moment, then stop.
  auto timer = std::make_shared<net::steady_timer>(io_, std::chrono::milliseconds(200));
  timer->async_wait([this, timer](beast::error_code) { io_.stop(); });
}

Server::Server(LiveScene& scene, PhysicsLoop& physics, AssetFiles assets, ServeOptions options, std::ostream& log)
    : impl_(std::make_unique<Impl>(scene, physics, std::move(assets), std::move(options), log)) {}
Server::~Server() = default;
unsigned short Server::port() const { return impl_->port(); }
int Server::run() { return impl_->run(); }
void Server::stop() { impl_->stop(); }

}  // namespace roifem::serve
