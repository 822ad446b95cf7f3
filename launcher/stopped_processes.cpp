#include "launcher/stopped_processes.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>

namespace wsn::launcher {

char processState(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // "PID (COMM) S ...": the command may hold spaces and parentheses, so the state follows the last ')'.
  const auto close = text.rfind(')');
  return close == std::string::npos || close + 2 >= text.size() ? '?' : text[close + 2];
}

void StoppedProcesses::sample(pid_t pid, const std::string& name, bool expected) {
  const auto now = Clock::now();
  const char state = processState(pid);
  if ((state == 'T' || state == 't') && !expected) {
    auto [it, fresh] = current_.try_emplace(pid, Span{name, now, now});
    it->second.last = now;
    return;
  }
  const auto it = current_.find(pid);
  if (it == current_.end()) return;
  auto& longest = spans_[pid];
  if (longest.name.empty() || it->second.last - it->second.first > longest.last - longest.first) longest = it->second;
  current_.erase(it);
}

std::string StoppedProcesses::diagnosis(std::chrono::milliseconds at_least) const {
  std::map<pid_t, Span> all = spans_;
  for (const auto& [pid, span] : current_) {
    auto& longest = all[pid];
    if (longest.name.empty() || span.last - span.first > longest.last - longest.first) longest = span;
  }
  std::ostringstream out;
  for (const auto& [pid, span] : all) {
    if (span.last - span.first < at_least) continue;
    const auto seconds = [](Clock::duration d) { return std::chrono::duration<double>(d).count(); };
    char text[200];
    std::snprintf(text, sizeof text, "%s was stopped (SIGSTOP or a debugger) for about %.1f s, from %.1f s into the run",
                  span.name.c_str(), seconds(span.last - span.first), seconds(span.first - started_));
    out << (out.tellp() > 0 ? "; " : "") << text;
  }
  return out.str();
}

}  // namespace wsn::launcher
