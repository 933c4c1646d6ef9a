#include "common/subprocess.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <stdexcept>

extern char** environ;

namespace mrsim {
namespace {

class SpawnActions {
 public:
  SpawnActions() { posix_spawn_file_actions_init(&actions_); }
  ~SpawnActions() { posix_spawn_file_actions_destroy(&actions_); }
  SpawnActions(const SpawnActions&) = delete;
  SpawnActions& operator=(const SpawnActions&) = delete;
  posix_spawn_file_actions_t* get() { return &actions_; }

 private:
  posix_spawn_file_actions_t actions_;
};

}  // namespace

Subprocess::Subprocess(const std::vector<std::string>& argv,
                       const SpawnOptions& options) {
  if (argv.empty()) throw std::invalid_argument("Subprocess: empty argv");
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);

  SpawnActions actions;
  int pipe_fds[2] = {-1, -1};
  using Output = SpawnOptions::Output;
  switch (options.output) {
    case Output::kInherit:
      break;
    case Output::kNull:
    case Output::kFile: {
      const std::string path =
          options.output == Output::kNull ? "/dev/null" : options.output_path;
      posix_spawn_file_actions_addopen(actions.get(), STDOUT_FILENO,
                                       path.c_str(),
                                       O_WRONLY | O_CREAT | O_TRUNC, 0644);
      posix_spawn_file_actions_adddup2(actions.get(), STDOUT_FILENO,
                                       STDERR_FILENO);
      break;
    }
    case Output::kPipe:
      if (pipe2(pipe_fds, O_CLOEXEC) != 0) {
        throw std::runtime_error("cannot start " + argv[0] +
                                 ": no pipe: " + std::strerror(errno));
      }
      posix_spawn_file_actions_adddup2(actions.get(), pipe_fds[1],
                                       STDOUT_FILENO);
      posix_spawn_file_actions_adddup2(actions.get(), pipe_fds[1],
                                       STDERR_FILENO);
      break;
  }
  posix_spawn_file_actions_addopen(actions.get(), STDIN_FILENO, "/dev/null",
                                   O_RDONLY, 0);
  if (!options.working_dir.empty()) {
    posix_spawn_file_actions_addchdir_np(actions.get(),
                                         options.working_dir.c_str());
  }
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  if (options.own_process_group) {
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&attributes, 0);
  }
  const int rc = posix_spawn(&pid_, args[0], actions.get(), &attributes,
                             args.data(), environ);
  posix_spawnattr_destroy(&attributes);
  if (pipe_fds[1] >= 0) close(pipe_fds[1]);
  if (rc != 0) {
    if (pipe_fds[0] >= 0) close(pipe_fds[0]);
    pid_ = -1;
    throw std::runtime_error("cannot start " + argv[0] + ": " +
                             std::strerror(rc));
  }
  if (pipe_fds[0] >= 0) {
    // Non-blocking: a reader must never wait on one child's silence.
    fcntl(pipe_fds[0], F_SETFL, fcntl(pipe_fds[0], F_GETFL) | O_NONBLOCK);
    out_fd_ = pipe_fds[0];
  }
  pid_fd_ = static_cast<int>(syscall(SYS_pidfd_open, pid_, 0));
}

Subprocess::~Subprocess() {
  if (pid_ > 0 && !reaped_) {
    kill(pid_, SIGKILL);
    Wait(10);
  }
  CloseOutput();
  if (pid_fd_ >= 0) close(pid_fd_);
}

void Subprocess::CloseOutput() {
  if (out_fd_ >= 0) close(out_fd_);
  out_fd_ = -1;
}

bool Subprocess::running() {
  if (reaped_ || pid_ <= 0) return false;
  int status = 0;
  rusage usage{};
  if (wait4(pid_, &status, WNOHANG, &usage) == pid_) {
    status_ = status;
    cpu_seconds_ = static_cast<double>(usage.ru_utime.tv_sec) +
                   1e-6 * static_cast<double>(usage.ru_utime.tv_usec) +
                   static_cast<double>(usage.ru_stime.tv_sec) +
                   1e-6 * static_cast<double>(usage.ru_stime.tv_usec);
    reaped_ = true;
  }
  return !reaped_;
}

void Subprocess::Signal(int sig) {
  if (running()) kill(pid_, sig);
}

int Subprocess::ExitCode() const {
  if (WIFEXITED(status_)) return WEXITSTATUS(status_);
  if (WIFSIGNALED(status_)) return 128 + WTERMSIG(status_);
  return -1;
}

int Subprocess::Wait(double timeout_s) {
  using Clock = std::chrono::steady_clock;
  const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                      std::chrono::duration<double>(timeout_s));
  while (running()) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                          end - Clock::now())
                          .count();
    if (left <= 0) return -1;
    if (pid_fd_ >= 0) {
      // Readable when the process ends.
      pollfd p{pid_fd_, POLLIN, 0};
      poll(&p, 1, static_cast<int>(left));
    } else {
      // No pidfd (old kernel): check again shortly.
      pollfd none{-1, 0, 0};
      poll(&none, 0, std::min<long long>(left, 10));
    }
  }
  return ExitCode();
}

int Subprocess::Stop(double grace_s) {
  if (!running()) return ExitCode();
  kill(pid_, SIGTERM);
  const int rc = Wait(grace_s);
  if (rc != -1) return rc;
  kill(pid_, SIGKILL);
  return Wait(10);
}

std::string DescribeExitStatus(int status) {
  if (WIFEXITED(status)) {
    return "exited with code " + std::to_string(WEXITSTATUS(status));
  }
  if (WIFSIGNALED(status)) {
    return std::string("killed by signal ") + strsignal(WTERMSIG(status));
  }
  return "ended";
}

}  // namespace mrsim
