// SPDX-License-Identifier: GPL-3.0-or-later
// roifem serve's server on loopback: bad messages, floods, two clients, files. Each against what
// the server must do: refuse or clamp, keep ticking, say so in its log.
#include "serve/server.hpp"

#include <gtest/gtest.h>
#include <sys/socket.h>

#include <boost/asio.hpp>
#include <boost/beast.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>
#include <thread>

#include "h5_read.hpp"
#include "serve/hand_message.hpp"
#include "serve_test_support.hpp"
#include "simulation/scenario_run.hpp"
#include "test_support.hpp"

namespace roifem::serve {
namespace {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;
using namespace std::chrono_literals;

/// A server on a free loopback port, in its own thread; stopped and joined on destruction. The
/// log may be read once it stopped (log_text()).
class RunningServer {
 public:
  explicit RunningServer(LiveScene& scene, PhysicsSettings hand = {}, std::filesystem::path record = {})
      : physics_(scene, hand),
        server_(scene, physics_, AssetFiles({{"/", page_directory()}, {"/three/", three_directory()}}),
                ServeOptions{.host = "127.0.0.1", .port = 0, .record = std::move(record), .display_hz = 60}, log_) {
    thread_ = std::thread([this] { signal_ = server_.run(); });
  }
  ~RunningServer() { stop(); }
  unsigned short port() const { return server_.port(); }
  std::string stop_and_read_log() {
    stop();
    return log_.str();
  }

 private:
  std::ostringstream log_;
  PhysicsLoop physics_;
  Server server_;
  std::thread thread_;
  int signal_ = -1;
  void stop() {
    if (!thread_.joinable()) return;
    server_.stop();
    thread_.join();
  }
};

/// A WebSocket client with blocking reads that give up after 10 s.
class Client {
 public:
  /// `host`: the Host header's name ("127.0.0.1:PORT" when empty).
  explicit Client(unsigned short port, const std::string& origin = "", const std::string& host = "") : ws_(io_) {
    tcp::resolver resolver(io_);
    net::connect(ws_.next_layer(), resolver.resolve("127.0.0.1", std::to_string(port)));
    timeval timeout{.tv_sec = 10, .tv_usec = 0};
    setsockopt(ws_.next_layer().native_handle(), SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    if (!origin.empty())
      ws_.set_option(
          websocket::stream_base::decorator([origin](websocket::request_type& r) { r.set(http::field::origin, origin); }));
    ws_.handshake(host.empty() ? "127.0.0.1:" + std::to_string(port) : host, "/ws");
  }
  void send(const std::string& bytes, bool binary = true) {
    ws_.binary(binary);
    ws_.write(net::buffer(bytes));
  }
  void send(HandKind kind, const Vec3& point_mm = Vec3::Zero(), std::uint32_t model = 0) {
    send(encode_hand_message({.kind = kind, .sequence = ++sequence_, .point_mm = point_mm, .model = model}));
  }
  void send_cut(const HandMessage& stroke) {
    HandMessage m = stroke;
    m.sequence = ++sequence_;
    send(encode_hand_message(m));
  }
  /// The next text message whose "type" is `type` (binary frames and other types skipped).
  std::string next(const std::string& type) {
    for (;;) {
      beast::flat_buffer buffer;
      ws_.read(buffer);
      if (!ws_.got_text()) continue;
      std::string text = beast::buffers_to_string(buffer.data());
      if (text.find("\"type\":\"" + type + "\"") != std::string::npos) return text;
    }
  }
  /// The next binary message.
  std::string next_binary() {
    for (;;) {
      beast::flat_buffer buffer;
      ws_.read(buffer);
      if (ws_.got_binary()) return beast::buffers_to_string(buffer.data());
    }
  }
  void close() { ws_.close(websocket::close_code::normal); }

 private:
  net::io_context io_;
  websocket::stream<tcp::socket> ws_;
  std::uint32_t sequence_ = 0;
};

double number_after(const std::string& json, const std::string& key) {
  const auto at = json.find("\"" + key + "\":");
  if (at == std::string::npos) throw std::runtime_error("no " + key + " in " + json);
  return std::stod(json.substr(at + key.size() + 3));
}

Vec3 vector_after(const std::string& json, const std::string& key) {
  const auto at = json.find("\"" + key + "\":[");
  if (at == std::string::npos) throw std::runtime_error("no " + key + " in " + json);
  std::istringstream in(json.substr(at + key.size() + 4));
  Vec3 v;
  char comma = 0;
  in >> v.x() >> comma >> v.y() >> comma >> v.z();
  return v;
}

/// The state once the physics shows the condition (or the last one after 5 s).
template <class Condition>
std::string state_when(Client& client, Condition condition) {
  std::string state;
  const auto until = std::chrono::steady_clock::now() + 5s;
  do state = client.next("state");
  while (!condition(state) && std::chrono::steady_clock::now() < until);
  return state;
}

int http_status(unsigned short port, const std::string& target, http::verb verb = http::verb::get,
                const std::string& host = "127.0.0.1") {
  net::io_context io;
  beast::tcp_stream stream(io);
  stream.connect(tcp::resolver(io).resolve("127.0.0.1", std::to_string(port)));
  http::request<http::string_body> request{verb, target, 11};
  request.set(http::field::host, host);
  http::write(stream, request);
  beast::flat_buffer buffer;
  http::response_parser<http::string_body> parser;
  parser.skip(verb == http::verb::head);  // a HEAD response announces a body it does not send
  http::read(stream, buffer, parser);
  return static_cast<int>(parser.get().result_int());
}

TEST(ServeServer, GreetsTheFirstClientAsDriverWithTheModelsAndTheSurface) {
  const auto scene = test::paper_scene();
  RunningServer server(*scene);
  Client client(server.port());
  const std::string hello = client.next("hello");
  EXPECT_NE(hello.find("\"role\":\"driver\""), std::string::npos) << hello;
  for (const char* name : {"full", "static", "guyan", "craig-bampton-10"}) EXPECT_NE(hello.find(name), std::string::npos) << name;
  const std::string mesh = client.next_binary();
  ASSERT_EQ(mesh.substr(0, 4), "RFMS");
  std::uint32_t V = 0, T = 0;
  std::memcpy(&V, mesh.data() + 4, 4);
  std::memcpy(&T, mesh.data() + 8, 4);
  EXPECT_EQ(V, scene->surface().nodes.size());
  EXPECT_EQ(T, scene->surface().triangles.size());
  // A closed surface: Euler's formula for a sphere, V - E + F = 2 with E = 3F / 2.
  EXPECT_EQ(static_cast<long>(V) - static_cast<long>(T) / 2, 2);
  const std::string frame = client.next_binary();
  ASSERT_EQ(frame.substr(0, 4), "RFFR");
  EXPECT_EQ(frame.size(), 24 + 12 * std::size_t{V});
}

/// The next surface the server sends: its vertex and triangle counts.
std::pair<std::uint32_t, std::uint32_t> next_mesh(Client& client) {
  for (;;) {
    const std::string bytes = client.next_binary();
    if (bytes.substr(0, 4) != "RFMS") continue;
    std::uint32_t V = 0, T = 0;
    std::memcpy(&V, bytes.data() + 4, 4);
    std::memcpy(&T, bytes.data() + 8, 4);
    return {V, T};
  }
}

TEST(ServeServer, AScalpelStrokeSendsTheCutSurfaceAndASavedGrabReplaysTheCut) {
  const auto scene = test::paper_scene({"static", "static-cut"});
  const Vec3 point = test::pickable_point(*scene);
  const HandMessage stroke = test::stroke_beside(*scene, 1, point, 6.0);
  roifem::test::TempDir dir;
  RunningServer server(*scene, {.hand_speed_mm_s = 40, .reach_mm = 20}, dir.path());
  Client client(server.port());
  client.next("hello");
  const auto [V0, T0] = next_mesh(client);
  client.send(HandKind::model, Vec3::Zero(), 1);
  state_when(client, [](const std::string& s) { return s.find("\"model_name\":\"static-cut\"") != std::string::npos; });
  client.send_cut(stroke);
  const std::string said = client.next("notice");
  EXPECT_NE(said.find("tetrahedra removed from the static-cut model between grabs"), std::string::npos) << said;
  const auto [V1, T1] = next_mesh(client);
  EXPECT_GT(T1, T0);  // the cut's walls
  EXPECT_GE(V1, V0);
  // A grab beside it, saved and replayed: the replay's [[cut]] removes the same tetrahedra first.
  client.send(HandKind::pick, point);
  state_when(client, [](const std::string& s) { return number_after(s, "grip_nodes") > 0; });
  client.send(HandKind::target, point + Vec3(1.5, -1, 0.5));
  state_when(client, [](const std::string& s) { return number_after(s, "t") > 0.15; });
  client.send(HandKind::save);
  std::string saved;
  do saved = client.next("notice");
  while (saved.find("saved (") == std::string::npos && saved.find("not saved") == std::string::npos);
  ASSERT_NE(saved.find("saved (the page asked)"), std::string::npos) << saved;
  server.stop_and_read_log();
  EXPECT_EQ(V1, scene->surface(1).nodes.size());  // the model's surface as the cut left it (cut_test.cpp)
  EXPECT_EQ(T1, scene->surface(1).triangles.size());
  std::filesystem::path toml;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
    if (entry.path().extension() == ".toml") toml = entry.path();
  ASSERT_FALSE(toml.empty());
  const scenario::Scenario replay = scenario::read_scenario(toml);
  ASSERT_EQ(replay.cuts.size(), 1U);
  EXPECT_EQ(replay.cuts[0].start, 0.0);
  std::ostringstream log;
  simulation::run_scenario(replay, dir / "replay", log);
  const auto force = roifem::test::read_h5(dir / "replay/results.h5", "tools/hand/force_N");
  std::ifstream live_csv(dir / (toml.stem().string() + "-force.csv"));
  std::string line;
  std::getline(live_csv, line);
  double largest = 0, difference = 0;
  for (std::size_t i = 0; std::getline(live_csv, line); ++i) {
    Vec3 live;
    double t = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf", &t, &live.x(), &live.y(), &live.z()), 4);
    ASSERT_LT(3 * i + 2, force.size());
    largest = std::max(largest, live.norm());
    difference = std::max(difference, (Vec3(force[3 * i], force[3 * i + 1], force[3 * i + 2]) - live).norm());
  }
  EXPECT_GT(largest, 1e-4);
  EXPECT_LT(difference, 1e-9 * largest);
}

TEST(ServeServer, FramesKeepTheirPaceWhileThePageSendsTheHand) {
  // Frames leave as they are made (TCP_NODELAY): with Nagle's algorithm a frame's last segment
  // waited for the page's acknowledgement of the one before, and while the page sent the hand the
  // frames arrived in pairs, every other 60 Hz turn (the browser drew 30 a second, not 55).
  const auto scene = test::paper_scene({"static"});
  const Vec3 point = test::pickable_point(*scene);
  RunningServer server(*scene);
  Client client(server.port());
  client.next("hello");
  client.send(HandKind::pick, point);
  state_when(client, [](const std::string& s) { return number_after(s, "grip_nodes") > 0; });
  std::vector<double> arrivals;
  const auto start = std::chrono::steady_clock::now();
  auto next_hand = start;
  for (int k = 0; arrivals.size() < 90; ++k) {
    const std::string bytes = client.next_binary();
    const auto now = std::chrono::steady_clock::now();
    if (bytes.substr(0, 4) == "RFFR") arrivals.push_back(std::chrono::duration<double>(now - start).count());
    if (now >= next_hand) {  // the hand every 20 ms, between reads, as a page's mouse sends it
      client.send(HandKind::target, point + Vec3(0.01 * (k % 50), 0, 0));
      next_hand += 20ms;
    }
  }
  long paired = 0;
  for (std::size_t i = 1; i < arrivals.size(); ++i) paired += arrivals[i] - arrivals[i - 1] < 0.004 ? 1 : 0;
  std::printf("[ figures ] %ld of %zu frames came within 4 ms of the one before (1.5 s, the hand every 20 ms)\n", paired,
              arrivals.size() - 1);
  EXPECT_LT(paired, 20) << "frames arrive in pairs";
}

TEST(ServeServer, RefusesMalformedAndNonFiniteMessagesClampsFarTargetsAndKeepsTickingThroughAFlood) {
  const auto scene = test::paper_scene();
  const Vec3 point = test::pickable_point(*scene);
  RunningServer server(*scene, {.hand_speed_mm_s = 1000, .reach_mm = 20});
  Client client(server.port());
  client.next("hello");
  client.send(HandKind::pick, point);
  state_when(client, [](const std::string& s) { return number_after(s, "grip_nodes") > 0; });
  // Bad messages: short, unknown kind, text, a NaN target; none may move the tool.
  client.send(std::string("\x02\0\0", 3));
  client.send(std::string("\x09\0\0\0\0\0\0\0", 8));
  client.send("{\"target\": [1, 2, 3]}", false);
  client.send(HandKind::target, Vec3(0, std::nan(""), 0));
  std::string state = client.next("state");
  EXPECT_LT(vector_after(state, "g_mm").norm(), 1e-12) << state;
  // A target a kilometre away: clamped to the reach (20 mm) from where it picked.
  client.send(HandKind::target, point + Vec3(1e6, 0, 0));
  state = state_when(client, [](const std::string& s) { return vector_after(s, "g_mm").norm() > 19.99; });
  EXPECT_NEAR(vector_after(state, "g_mm").norm(), 20.0, 1e-6) << state;
  // A flood: 10,000 targets as fast as the socket takes them.
  const double ticks_before = number_after(client.next("state"), "count");
  for (int k = 0; k < 10000; ++k) client.send(HandKind::target, point + Vec3(0.001 * (k % 100), 0, 0));
  state = client.next("state");
  const double ticks_during = number_after(state, "count");
  std::this_thread::sleep_for(300ms);
  state = state_when(client, [&](const std::string& s) { return number_after(s, "count") > ticks_during + 100; });
  EXPECT_GT(number_after(state, "count"), ticks_during + 100) << "the physics stalled after the flood";
  EXPECT_GT(ticks_during, ticks_before) << "the physics stalled during the flood";
  // It still answers a hand (once the second of the flood, over the limit, has passed): the tool
  // comes back to where it picked.
  std::this_thread::sleep_for(1100ms);
  client.send(HandKind::target, point);
  state = state_when(client, [](const std::string& s) { return vector_after(s, "g_mm").norm() < 1e-9; });
  EXPECT_LT(vector_after(state, "g_mm").norm(), 1e-9) << state;
  client.close();
  const std::string log = server.stop_and_read_log();
  // The four bad messages and the flood's excess, summed in one line per second.
  EXPECT_TRUE(
      std::regex_search(log, std::regex("refused [0-9]+ message\\(s\\) in the last second \\(4 malformed, [1-9][0-9]* over the "
                                        "limit of 2000/s.*the last malformed: a target at a point that is not finite")))
      << log;
}

TEST(ServeServer, OneClientDrivesTheOtherWatchesAndDrivesOnceTheFirstLeavesMidDrag) {
  const auto scene = test::paper_scene();
  const Vec3 point = test::pickable_point(*scene);
  RunningServer server(*scene, {.hand_speed_mm_s = 200, .reach_mm = 20});
  Client driver(server.port());
  EXPECT_NE(driver.next("hello").find("\"role\":\"driver\""), std::string::npos);
  Client watcher(server.port());
  EXPECT_NE(watcher.next("hello").find("\"role\":\"watcher\""), std::string::npos);
  driver.send(HandKind::pick, point);
  driver.send(HandKind::target, point + Vec3(0, 0, 3));
  std::string state = state_when(watcher, [](const std::string& s) { return vector_after(s, "g_mm").z() > 2.99; });
  EXPECT_NEAR(vector_after(state, "g_mm").z(), 3.0, 1e-9) << state;  // the watcher sees the driver's grab
  watcher.send(HandKind::target, point + Vec3(0, 0, -3));            // refused: it watches
  // The driver leaves mid-drag: the tool eases back, and the watcher drives.
  driver.close();
  EXPECT_NE(watcher.next("role").find("\"role\":\"driver\""), std::string::npos);
  state = state_when(watcher, [](const std::string& s) { return vector_after(s, "g_mm").norm() < 1e-12; });
  EXPECT_LT(vector_after(state, "g_mm").norm(), 1e-12) << state;
  EXPECT_NE(state.find("\"holding\":false"), std::string::npos);
  watcher.send(HandKind::pick, point);
  state = state_when(watcher, [](const std::string& s) { return s.find("\"holding\":true") != std::string::npos; });
  EXPECT_NE(state.find("\"grab\":2"), std::string::npos) << state;
  watcher.close();
  const std::string log = server.stop_and_read_log();
  EXPECT_NE(log.find("1 from a watcher"), std::string::npos) << log;
  EXPECT_NE(log.find("(it drove: its grab is released)"), std::string::npos) << log;
}

TEST(ServeServer, ServesThePageAndAnswersEveryOtherPathWith404) {
  const auto scene = test::paper_scene();
  RunningServer server(*scene);
  EXPECT_EQ(http_status(server.port(), "/"), 200);
  EXPECT_EQ(http_status(server.port(), "/app.js"), 200);
  EXPECT_EQ(http_status(server.port(), "/three/build/three.module.js"), 200);
  for (const char* outside : {"/../../../../etc/passwd", "/%2e%2e/%2e%2e/etc/passwd", "/three/../../../etc/passwd",
                              "/three/..%2f..%2f..%2fetc/passwd", "/.git/config", "/ws", "/CMakeLists.txt"})
    EXPECT_EQ(http_status(server.port(), outside), 404) << outside;
  EXPECT_EQ(http_status(server.port(), "/", http::verb::post), 405);
  EXPECT_EQ(http_status(server.port(), "/", http::verb::head), 200);
  // A WebSocket opened by another site's page (its Origin) is refused.
  EXPECT_THROW(Client(server.port(), "http://evil.example"), beast::system_error);
  Client same(server.port(), "http://127.0.0.1:" + std::to_string(server.port()));
  EXPECT_NE(same.next("hello").find("hello"), std::string::npos);
}

// DNS rebinding: a page on another site that points its own name at 127.0.0.1 reaches the server
// with that name in Host (and, for a WebSocket, as its own Origin). Only the loopback's names and
// addresses (and the listening address) are answered, over plain HTTP as over the WebSocket.
TEST(ServeServer, AnswersOnlyForTheLoopbackAgainstDnsRebinding) {
  const auto scene = test::paper_scene({"static"});
  RunningServer server(*scene);
  const std::string port = std::to_string(server.port());
  for (const std::string& rebound : std::vector<std::string>{"evil.example", "evil.example:" + port, "127.0.0.1.evil.example",
                                                             "localhost.evil.example:" + port})
    EXPECT_EQ(http_status(server.port(), "/", http::verb::get, rebound), 403) << rebound;
  EXPECT_EQ(http_status(server.port(), "/app.js", http::verb::get, "evil.example"), 403);
  for (const std::string& own :
       std::vector<std::string>{"127.0.0.1:" + port, "localhost:" + port, "LOCALHOST", "127.0.0.2:" + port, "[::1]:" + port})
    EXPECT_EQ(http_status(server.port(), "/", http::verb::get, own), 200) << own;
  EXPECT_THROW(Client(server.port(), "http://evil.example", "evil.example"), beast::system_error);
  EXPECT_THROW(Client(server.port(), "http://evil.example:" + port, "evil.example:" + port), beast::system_error);
  Client own(server.port(), "http://localhost:" + port, "localhost:" + port);
  EXPECT_NE(own.next("hello").find("hello"), std::string::npos);
}

}  // namespace
}  // namespace roifem::serve
