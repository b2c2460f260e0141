// Isolated work (isolation.h): fork, a pipe per child, poll, waitpid.

#include "massprops/isolation.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <map>
#include <stdexcept>
#include <vector>

#include <fcntl.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

namespace massprops {
namespace {

using Clock = std::chrono::steady_clock;

struct Child {
  std::size_t index;
  pid_t pid;
  int fd;
  Clock::time_point start, deadline;
  std::string output;
};

bool WriteAll(int fd, const char* p, std::size_t n) {
  while (n > 0) {
    const ssize_t w = ::write(fd, p, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return false;
    p += w;
    n -= static_cast<std::size_t>(w);
  }
  return true;
}

using StreamingWork = std::function<void(std::size_t, const IsolatedSend&)>;

[[noreturn]] void RunChild(const StreamingWork& work, std::size_t i, int fd) {
  int code = 0;
  try {
    bool ok = true;
    work(i, [&](const std::string& bytes) { ok = ok && WriteAll(fd, bytes.data(), bytes.size()); });
    code = ok ? 0 : 3;
  } catch (...) {
    code = 4;
  }
  ::_exit(code);
}

Child Launch(const StreamingWork& work, std::size_t i, double limit) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    throw std::runtime_error(std::string("cannot create a pipe: ") + std::strerror(errno));
  std::fflush(nullptr);  // nothing buffered is written twice
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw std::runtime_error(std::string("cannot start a process: ") + std::strerror(errno));
  }
  if (pid == 0) {
    ::close(fds[0]);
    RunChild(work, i, fds[1]);
  }
  ::close(fds[1]);
  const Clock::time_point now = Clock::now();
  return {i, pid, fds[0], now, now + std::chrono::milliseconds(static_cast<long long>(limit * 1000)), {}};
}

IsolatedOutcome Reap(Child& c, bool timed_out) {
  if (timed_out) ::kill(c.pid, SIGKILL);
  ::close(c.fd);
  int status = 0;
  while (::waitpid(c.pid, &status, 0) < 0 && errno == EINTR) {
  }
  IsolatedOutcome out;
  out.seconds = std::chrono::duration<double>(Clock::now() - c.start).count();
  if (timed_out) {
    out.end = IsolatedEnd::kTimedOut;
  } else if (WIFSIGNALED(status)) {
    out.end = IsolatedEnd::kCrashed;
    out.signal = WTERMSIG(status);
  } else if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    out.end = IsolatedEnd::kFailed;
  }
  out.output = std::move(c.output);
  return out;
}

void Run(std::size_t count, int jobs, double seconds_limit, bool silence, const StreamingWork& work,
         const std::function<void(std::size_t, IsolatedOutcome&&)>& done) {
  jobs = std::max(jobs, 1);
  std::vector<Child> running;
  std::map<std::size_t, IsolatedOutcome> finished;  // waiting for the items before them
  std::size_t next = 0, delivered = 0;
  const std::size_t hold_limit = 64 * static_cast<std::size_t>(jobs);  // bounds the memory held back
  char buf[65536];
  struct KillOnExit {  // if `done` or a launch throws, no child outlives the call
    std::vector<Child>& running;
    ~KillOnExit() {
      for (Child& c : running) Reap(c, true);
    }
  } guard{running};
  while (delivered < count) {
    while (running.size() < static_cast<std::size_t>(jobs) && next < count && finished.size() < hold_limit) {
      running.push_back(Launch(work, next++, seconds_limit));
    }
    // Wait for output, an end of output, or the nearest deadline.
    std::vector<pollfd> pfds;
    Clock::time_point nearest = Clock::time_point::max();
    for (const Child& c : running) {
      pfds.push_back({c.fd, POLLIN, 0});
      nearest = std::min(nearest, c.deadline);
    }
    const auto wait_ms = std::chrono::duration_cast<std::chrono::milliseconds>(nearest - Clock::now()).count();
    if (!pfds.empty()) {
      const int r = ::poll(pfds.data(), pfds.size(), static_cast<int>(std::clamp<long long>(wait_ms + 1, 0, 1000)));
      if (r < 0 && errno != EINTR) throw std::runtime_error(std::string("poll: ") + std::strerror(errno));
    }
    const Clock::time_point now = Clock::now();
    for (std::size_t k = 0; k < running.size();) {
      Child& c = running[k];
      bool ended = false, timed_out = false;
      if (pfds[k].revents & (POLLIN | POLLHUP | POLLERR)) {
        const ssize_t n = ::read(c.fd, buf, sizeof buf);
        if (n > 0) {
          c.output.append(buf, static_cast<std::size_t>(n));
          if (silence)
            c.deadline = Clock::now() + std::chrono::milliseconds(static_cast<long long>(seconds_limit * 1000));
        }
        ended = n == 0 || (n < 0 && errno != EINTR && errno != EAGAIN);
      }
      if (!ended && now >= c.deadline) ended = timed_out = true;
      if (ended) {
        finished.emplace(c.index, Reap(c, timed_out));
        running.erase(running.begin() + static_cast<std::ptrdiff_t>(k));
        pfds.erase(pfds.begin() + static_cast<std::ptrdiff_t>(k));
      } else {
        ++k;
      }
    }
    for (auto it = finished.find(delivered); it != finished.end(); it = finished.find(delivered)) {
      IsolatedOutcome outcome = std::move(it->second);
      finished.erase(it);
      done(delivered++, std::move(outcome));
    }
  }
}

}  // namespace

void RunIsolated(std::size_t count, int jobs, double seconds_limit, const std::function<std::string(std::size_t)>& work,
                 const std::function<void(std::size_t, IsolatedOutcome&&)>& done) {
  Run(
      count, jobs, seconds_limit, false, [&](std::size_t i, const IsolatedSend& send) { send(work(i)); }, done);
}

void RunIsolatedStreaming(std::size_t count, int jobs, double seconds_silent,
                          const std::function<void(std::size_t, const IsolatedSend&)>& work,
                          const std::function<void(std::size_t, IsolatedOutcome&&)>& done) {
  Run(count, jobs, seconds_silent, true, work, done);
}

}  // namespace massprops
