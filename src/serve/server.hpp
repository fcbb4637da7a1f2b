// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// `roifem serve`'s network side: HTTP for the page's files and a WebSocket (/ws) for the live
/// model, on one port, in one thread (Boost.Beast over Asio). The physics runs in its own thread
/// (physics_loop.hpp) and never waits on this one.
///
/// Clients: the first to connect drives (its hand messages reach the physics); the others watch
/// (they see every frame; their hand messages are refused, with a notice). When the driver leaves,
/// mid-drag or not, its grab is released (the tool eases back to where it picked) and the longest
/// connected watcher drives.
/// Refused, each said in the log (summed per client and second, so that a flood does not flood
/// the log): malformed or text frames, non-finite points, messages beyond 2,000 per second per
/// client, frames over 1 KiB (the connection is closed), a WebSocket from another page's origin
/// (403), any URL that is not one of the page's files (404: assets in asset_files.hpp).
#include <filesystem>
#include <iosfwd>
#include <memory>
#include <string>

#include "serve/asset_files.hpp"
#include "serve/live_scene.hpp"
#include "serve/physics_loop.hpp"

namespace roifem::serve {

struct ServeOptions {
  std::string host = "127.0.0.1";
  unsigned short port = 8080;    ///< 0: any free port (port() says which)
  std::filesystem::path record;  ///< where grabs are written for replay (empty: only on request, refused)
  double display_hz = 60;
};

class Server {
 public:
  /// Binds the port (InputError naming host and port when it cannot).
  Server(LiveScene& scene, PhysicsLoop& physics, AssetFiles assets, ServeOptions options, std::ostream& log);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  unsigned short port() const;
  /// Serves until stop() or SIGINT / SIGTERM; returns the signal (0 after stop()). Closes every
  /// connection and writes the grab in progress (with `record`) before it returns.
  int run();
  /// From any thread.
  void stop();

  class Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace roifem::serve
