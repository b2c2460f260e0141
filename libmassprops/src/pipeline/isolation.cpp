// Isolated work (isolation.h): fork, a pipe per child, poll, waitpid.

#include "massprops/io/isolation.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <stdexcept>
#include <utility>
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

// Forks a child that runs `body(fd)` (it must not return) with the write end of a new pipe; returns
// its pid and the read end.
template <typename Body>
std::pair<pid_t, int> ForkWithPipe(const Body& body) {
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
    body(fds[1]);
    ::_exit(5);  // not reached: the bodies exit
  }
  ::close(fds[1]);
  return {pid, fds[0]};
}

Child Launch(const StreamingWork& work, std::size_t i, double limit) {
  const auto [pid, fd] = ForkWithPipe([&](int out) { RunChild(work, i, out); });
  const Clock::time_point now = Clock::now();
  return {i, pid, fd, now, now + std::chrono::milliseconds(static_cast<long long>(limit * 1000)), {}};
}

// Closes a child's pipe and waits for it, killing it first if asked; its wait status.
int EndProcess(pid_t pid, int fd, bool kill) {
  if (kill) ::kill(pid, SIGKILL);
  ::close(fd);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return status;
}

// How a child ended, from its wait status (or the time limit).
IsolatedEnd EndOf(int status, bool timed_out) {
  if (timed_out) return IsolatedEnd::kTimedOut;
  if (WIFSIGNALED(status)) return IsolatedEnd::kCrashed;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return IsolatedEnd::kFailed;
  return IsolatedEnd::kFinished;
}

IsolatedOutcome Reap(Child& c, bool timed_out) {
  const int status = EndProcess(c.pid, c.fd, timed_out);
  IsolatedOutcome out;
  out.seconds = std::chrono::duration<double>(Clock::now() - c.start).count();
  out.end = EndOf(status, timed_out);
  if (out.end == IsolatedEnd::kCrashed) out.signal = WTERMSIG(status);
  out.output = std::move(c.output);
  return out;
}

// Hands on, in order of item, the outcomes ready from `delivered` on.
void DeliverReady(std::map<std::size_t, IsolatedOutcome>& finished, std::size_t& delivered,
                  const std::function<void(std::size_t, IsolatedOutcome&&)>& done) {
  for (auto it = finished.find(delivered); it != finished.end(); it = finished.find(delivered)) {
    IsolatedOutcome outcome = std::move(it->second);
    finished.erase(it);
    done(delivered++, std::move(outcome));
  }
}

// Waits for output, an end of output or the nearest deadline of the running children (each with
// `fd` and `deadline`), then hands each child's new bytes to `on_bytes(child, bytes, n)` (false:
// stop it) and each child that ended — output closed, stopped, or past its deadline — to
// `on_end(child, timed_out)`, removing it from `running`.
template <typename C, typename OnBytes, typename OnEnd>
void PollChildren(std::vector<C>& running, const OnBytes& on_bytes, const OnEnd& on_end) {
  std::vector<pollfd> pfds;
  Clock::time_point nearest = Clock::time_point::max();
  for (const C& c : running) {
    pfds.push_back({c.fd, POLLIN, 0});
    nearest = std::min(nearest, c.deadline);
  }
  if (!pfds.empty()) {
    const auto wait_ms = std::chrono::duration_cast<std::chrono::milliseconds>(nearest - Clock::now()).count();
    const int r = ::poll(pfds.data(), pfds.size(), static_cast<int>(std::clamp<long long>(wait_ms + 1, 0, 1000)));
    if (r < 0 && errno != EINTR) throw std::runtime_error(std::string("poll: ") + std::strerror(errno));
  }
  char buf[65536];
  const Clock::time_point now = Clock::now();
  for (std::size_t k = 0; k < running.size();) {
    C& c = running[k];
    bool ended = false, timed_out = false;
    if (pfds[k].revents & (POLLIN | POLLHUP | POLLERR)) {
      const ssize_t n = ::read(c.fd, buf, sizeof buf);
      if (n > 0 && !on_bytes(c, buf, static_cast<std::size_t>(n))) ended = timed_out = true;
      ended = ended || n == 0 || (n < 0 && errno != EINTR && errno != EAGAIN);
    }
    if (!ended && now >= c.deadline) ended = timed_out = true;
    if (ended) {
      on_end(c, timed_out);
      running.erase(running.begin() + static_cast<std::ptrdiff_t>(k));
      pfds.erase(pfds.begin() + static_cast<std::ptrdiff_t>(k));
    } else {
      ++k;
    }
  }
}

void Run(std::size_t count, int jobs, double seconds_limit, bool silence, const StreamingWork& work,
         const std::function<void(std::size_t, IsolatedOutcome&&)>& done) {
  jobs = std::max(jobs, 1);
  std::vector<Child> running;
  std::map<std::size_t, IsolatedOutcome> finished;  // waiting for the items before them
  std::size_t next = 0, delivered = 0;
  const std::size_t hold_limit = 64 * static_cast<std::size_t>(jobs);  // bounds the memory held back
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
    PollChildren(
        running,
        [&](Child& c, const char* bytes, std::size_t n) {
          c.output.append(bytes, n);
          if (silence)
            c.deadline = Clock::now() + std::chrono::milliseconds(static_cast<long long>(seconds_limit * 1000));
          return true;
        },
        [&](Child& c, bool timed_out) { finished.emplace(c.index, Reap(c, timed_out)); });
    DeliverReady(finished, delivered, done);
  }
}

// --- Runs of items in one child ---------------------------------------------------------------
// The child frames what it sends: 'B' + item (8 bytes) when it begins an item, then 'R' + length
// (8 bytes) + the output, or 'F' if the work threw.

struct ItemRun {
  std::size_t begin, end;  // items [begin, end)
  bool alone;              // a crashed item computed again by itself
};

struct RunWorker {
  pid_t pid = -1;
  int fd = -1;
  ItemRun run{0, 0, false};
  std::size_t current = 0;   // the item begun last (valid when `busy`)
  std::size_t reported = 0;  // the items before this one are reported
  bool busy = false;
  Clock::time_point item_start, deadline;
  std::string buffer;  // bytes not yet parsed
};

void PutU64(std::string& out, std::uint64_t v) {
  for (int k = 0; k < 8; ++k) out.push_back(static_cast<char>((v >> (8 * k)) & 0xFF));
}
std::uint64_t GetU64(const char* p) {
  std::uint64_t v = 0;
  for (int k = 7; k >= 0; --k) v = (v << 8) | static_cast<unsigned char>(p[k]);
  return v;
}

[[noreturn]] void ServeRun(const std::function<std::string(std::size_t)>& work, const ItemRun& run, int fd) {
  for (std::size_t i = run.begin; i < run.end; ++i) {
    std::string frame(1, 'B');
    PutU64(frame, i);
    if (!WriteAll(fd, frame.data(), frame.size())) ::_exit(3);
    std::string out;
    bool ok = true;
    try {
      out = work(i);
    } catch (...) {
      ok = false;
    }
    frame.assign(1, ok ? 'R' : 'F');
    if (ok) PutU64(frame, out.size());
    if (!WriteAll(fd, frame.data(), frame.size()) || !WriteAll(fd, out.data(), out.size())) ::_exit(3);
  }
  ::_exit(0);
}

RunWorker LaunchRun(const std::function<std::string(std::size_t)>& work, const ItemRun& run, double limit) {
  const auto [pid, fd] = ForkWithPipe([&](int out) { ServeRun(work, run, out); });
  RunWorker c;
  c.pid = pid;
  c.fd = fd;
  c.run = run;
  c.current = c.reported = run.begin;
  c.item_start = Clock::now();
  c.deadline = c.item_start + std::chrono::milliseconds(static_cast<long long>(limit * 1000));
  return c;
}

}  // namespace

void RunIsolatedInRuns(std::size_t count, int jobs, double seconds_limit, std::size_t items_per_child,
                       const std::function<std::string(std::size_t)>& work,
                       const std::function<void(std::size_t, IsolatedOutcome&&)>& done) {
  jobs = std::max(jobs, 1);
  items_per_child = std::max<std::size_t>(items_per_child, 1);
  const auto limit = std::chrono::milliseconds(static_cast<long long>(seconds_limit * 1000));
  std::vector<RunWorker> running;
  std::vector<ItemRun> pending;  // runs to start before new ones: remainders and crashed items, last first
  std::map<std::size_t, IsolatedOutcome> finished;
  std::size_t next = 0, delivered = 0;
  const std::size_t hold_limit = (64 + items_per_child) * static_cast<std::size_t>(jobs);
  struct KillOnExit {
    std::vector<RunWorker>& running;
    ~KillOnExit() {
      for (RunWorker& c : running) EndProcess(c.pid, c.fd, true);
    }
  } guard{running};
  // Parses the frames a child sent; false if they are malformed.
  auto parse = [&](RunWorker& c) {
    for (;;) {
      if (c.buffer.empty()) return true;
      const char tag = c.buffer[0];
      if (tag == 'B') {
        if (c.buffer.size() < 9) return true;
        c.current = GetU64(c.buffer.data() + 1);
        if (c.current < c.run.begin || c.current >= c.run.end) return false;
        c.busy = true;
        c.item_start = Clock::now();
        c.deadline = c.item_start + limit;
        c.buffer.erase(0, 9);
      } else if (tag == 'R' || tag == 'F') {
        std::size_t used = 1;
        IsolatedOutcome o;
        if (tag == 'R') {
          if (c.buffer.size() < 9) return true;
          const std::uint64_t n = GetU64(c.buffer.data() + 1);
          if (c.buffer.size() - 9 < n) return true;
          o.output = c.buffer.substr(9, n);
          used = 9 + n;
        } else {
          o.end = IsolatedEnd::kFailed;
        }
        if (!c.busy) return false;
        o.seconds = std::chrono::duration<double>(Clock::now() - c.item_start).count();
        finished.emplace(c.current, std::move(o));
        c.busy = false;
        c.reported = c.current + 1;
        c.buffer.erase(0, used);
      } else {
        return false;
      }
    }
  };
  // A child ended (its output closed, or stopped): the item it was on, and the rest of its run.
  auto end_child = [&](RunWorker& c, bool timed_out) {
    const int status = EndProcess(c.pid, c.fd, timed_out);
    std::size_t resume = c.busy ? c.current + 1 : c.run.end;
    if (!c.busy && c.reported < c.run.end) {
      // Between items (or before the first): the next item is the one it failed on.
      c.current = c.reported;
      c.busy = true;
      resume = c.current + 1;
    }
    if (c.busy) {
      IsolatedOutcome o;
      o.seconds = std::chrono::duration<double>(Clock::now() - c.item_start).count();
      o.end = EndOf(status, timed_out);
      if (o.end == IsolatedEnd::kCrashed) o.signal = WTERMSIG(status);
      if (o.end == IsolatedEnd::kFinished) o.end = IsolatedEnd::kFailed;  // it exited without reporting the item
      if (o.end == IsolatedEnd::kCrashed && !c.run.alone) {
        pending.push_back({c.current, c.current + 1, true});  // computed again, alone
      } else {
        finished.emplace(c.current, std::move(o));
      }
    }
    if (resume < c.run.end) pending.push_back({resume, c.run.end, c.run.alone});
  };
  while (delivered < count) {
    while (running.size() < static_cast<std::size_t>(jobs) && finished.size() < hold_limit &&
           (!pending.empty() || next < count)) {
      ItemRun run;
      if (!pending.empty()) {
        run = pending.back();
        pending.pop_back();
      } else {
        // Runs shrink near the end, so the last children finish together.
        const std::size_t left = count - next;
        const std::size_t size =
            std::clamp<std::size_t>(left / (2 * static_cast<std::size_t>(jobs)), 1, items_per_child);
        run = {next, next + size, false};
        next += size;
      }
      running.push_back(LaunchRun(work, run, seconds_limit));
    }
    PollChildren(
        running,
        [&](RunWorker& c, const char* bytes, std::size_t n) {
          c.buffer.append(bytes, n);
          return parse(c);  // not our frames (cannot happen): stopped
        },
        end_child);
    DeliverReady(finished, delivered, done);
  }
}

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
