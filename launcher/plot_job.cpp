#include "launcher/plot_job.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <ctime>
#include <fstream>
#include <vector>

#include "launcher/install_layout.hpp"

extern char** environ;

namespace wsn::launcher {
namespace {

/// The last non-empty line of a (small) log file, for a one-line report.
std::string lastLine(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::string last;
  while (std::getline(in, line))
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  return last;
}

}  // namespace

PlotJob::PlotJob(const std::string& plot_script, const std::string& run_dir, const std::string& format)
    : log_(run_dir + "/logs/plot.log"), files_(run_dir + "/plots/{tracks,cardinality,ospa}." + format) {
  const std::string python = kPlotPython;
  const std::string& script = plot_script;
  if (::access(python.c_str(), X_OK) != 0) {
    outcome_.message = python + " not found (plots need Debian's python3-matplotlib)";
    return;
  }
  if (::access(script.c_str(), R_OK) != 0) {
    outcome_.message = script + " not found (the build copies it beside wsntrack; an install puts it in share/wsntrack/tools)";
    return;
  }
  // Close-on-exec, so that no process of the cluster holds the pipe open.
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) {
    outcome_.status = PlotOutcome::Status::kFailed;
    outcome_.message = std::string("cannot create a pipe: ") + std::strerror(errno);
    return;
  }
  std::vector<std::string> args{python, script, run_dir, "--format", format, "--wait"};
  std::vector<char*> argv;
  for (auto& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[0], STDIN_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = 0;
  const int spawned = ::posix_spawn(&pid, python.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(pipe_fds[0]);
  if (spawned != 0) {
    ::close(pipe_fds[1]);
    outcome_.status = PlotOutcome::Status::kFailed;
    outcome_.message = "cannot start " + python + ": " + std::strerror(spawned);
    return;
  }
  pid_ = pid;
  to_script_ = pipe_fds[1];
}

PlotJob::~PlotJob() {
  if (pid_ > 0) finish(false);
}

PlotOutcome PlotJob::finish(bool go) {
  if (pid_ <= 0) return outcome_;
  // The script may be gone (killed): block SIGPIPE for the write and swallow it if it came.
  sigset_t pipe_signal;
  sigset_t previous;
  sigemptyset(&pipe_signal);
  sigaddset(&pipe_signal, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_signal, &previous);
  const auto start = std::chrono::steady_clock::now();
  if (go && ::write(to_script_, "go\n", 3) < 0 && errno == EPIPE) {
    const timespec no_wait{};
    sigtimedwait(&pipe_signal, nullptr, &no_wait);
  }
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  ::close(to_script_);
  to_script_ = -1;

  int status = 0;
  pid_t reaped;
  while ((reaped = ::waitpid(pid_, &status, 0)) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  outcome_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // The exit status plot_run.py gives when matplotlib cannot be imported.
  constexpr int kNoMatplotlib = 3;
  if (reaped < 0) {
    // The cluster's supervisor reaps every child it sees exit: the script ended during the run.
    outcome_.status = PlotOutcome::Status::kFailed;
    outcome_.message = "plot_run.py ended during the run (see " + log_ + ")";
  } else if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    outcome_.status = go ? PlotOutcome::Status::kDrawn : PlotOutcome::Status::kSkipped;
    outcome_.message = go ? files_ : "not drawn";
  } else if (WIFEXITED(status) && WEXITSTATUS(status) == kNoMatplotlib) {
    outcome_.status = PlotOutcome::Status::kSkipped;
    outcome_.message = "matplotlib is not available to /usr/bin/python3 (apt-get install python3-matplotlib)";
  } else {
    outcome_.status = PlotOutcome::Status::kFailed;
    const std::string why = lastLine(log_);
    outcome_.message = (WIFSIGNALED(status) ? "plot_run.py killed by signal " + std::to_string(WTERMSIG(status))
                                            : "plot_run.py exit " + std::to_string(WEXITSTATUS(status))) +
                       (why.empty() ? "" : ": " + why) + " (see " + log_ + ")";
  }
  return outcome_;
}

}  // namespace wsn::launcher
