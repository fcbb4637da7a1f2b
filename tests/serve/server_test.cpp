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
#include <limits>
#include <regex>
#include <sstream>
#include <thread>

#include "serve/hand_message.hpp"
#include "serve_test_support.hpp"
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
  explicit RunningServer(LiveScene& scene, PhysicsSettings hand = {})
      : physics_(scene, hand),
        server_(scene, physics_, AssetFiles({{"/", page_directory()}, {"/three/", three_directory()}}),
                ServeOptions{.host = "127.0.0.1", .port = 0, .record = {}, .display_hz = 60}, log_) {
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
  explicit Client(unsigned short port, const std::string& origin = "") : ws_(io_) {
    tcp::resolver resolver(io_);
    net::connect(ws_.next_layer(), resolver.resolve("127.0.0.1", std::to_string(port)));
    timeval timeout{.tv_sec = 10, .tv_usec = 0};
    setsockopt(ws_.next_layer().native_handle(), SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    if (!origin.empty())
      ws_.set_option(
          websocket::stream_base::decorator([origin](websocket::request_type& r) { r.set(http::field::origin, origin); }));
    ws_.handshake("127.0.0.1:" + std::to_string(port), "/ws");
  }
  void send(const std::string& bytes, bool binary = true) {
    ws_.binary(binary);
    ws_.write(net::buffer(bytes));
  }
  void send(HandKind kind, const Vec3& point_mm = Vec3::Zero(), std::uint32_t model = 0) {
    send(encode_hand_message({.kind = kind, .sequence = ++sequence_, .point_mm = point_mm, .model = model}));
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

int http_status(unsigned short port, const std::string& target, http::verb verb = http::verb::get) {
  net::io_context io;
  beast::tcp_stream stream(io);
  stream.connect(tcp::resolver(io).resolve("127.0.0.1", std::to_string(port)));
  http::request<http::string_body> request{verb, target, 11};
  request.set(http::field::host, "127.0.0.1");
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

}  // namespace
}  // namespace roifem::serve
