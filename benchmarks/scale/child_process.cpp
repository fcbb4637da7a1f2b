// SPDX-License-Identifier: GPL-3.0-or-later
#include "scale/child_process.hpp"

#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <sstream>

namespace roifem::bench {

namespace {

void write_all(int fd, const std::string& text) {
  for (std::size_t done = 0; done < text.size();) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n <= 0) return;
    done += static_cast<std::size_t>(n);
  }
}

}  // namespace

ChildResult run_in_child(const std::function<std::string()>& work, double timeout_s) {
  int fds[2];
  if (::pipe(fds) != 0) return {false, std::string("pipe: ") + std::strerror(errno)};
  std::fflush(nullptr);  // a child that flushes stdio (Gmsh does) would print the parent's buffered text again
  const pid_t pid = ::fork();
  if (pid < 0) return {false, std::string("fork: ") + std::strerror(errno)};
  if (pid == 0) {
    ::close(fds[0]);
    std::string reply;
    try {
      reply = "ok\n" + work();
    } catch (const std::exception& e) {
      reply = std::string("error\n") + e.what();
    }
    write_all(fds[1], reply);
    ::close(fds[1]);
    std::_Exit(0);  // no atexit handlers: they belong to the parent's libraries
  }
  ::close(fds[1]);
  std::string received;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  bool timed_out = false;
  for (char buffer[4096];;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), 1000))) == 0) continue;
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n <= 0) break;
    received.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(fds[0]);
  if (timed_out) ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (timed_out) return {false, "stopped after " + std::to_string(static_cast<long>(timeout_s)) + " s"};
  if (WIFSIGNALED(status))
    return {false, std::string("killed by signal ") + std::to_string(WTERMSIG(status)) +
                       (WTERMSIG(status) == SIGKILL ? " (out of memory?)" : "")};
  if (received.rfind("ok\n", 0) == 0) return {true, received.substr(3)};
  if (received.rfind("error\n", 0) == 0) return {false, received.substr(6)};
  return {false, "the child exited without an answer"};
}

std::map<std::string, std::string> parse_key_values(const std::string& text) {
  std::map<std::string, std::string> fields;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (const auto eq = line.find('='); eq != std::string::npos) fields[line.substr(0, eq)] = line.substr(eq + 1);
  return fields;
}

}  // namespace roifem::bench
