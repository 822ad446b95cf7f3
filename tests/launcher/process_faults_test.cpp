// Which processes the launcher lets the cluster lose by hand and when it starts a restarted one
// (launcher/fault_signals.hpp), and how it tells a stopped child apart
// (launcher/stopped_processes.hpp), on a child process of its own.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <string>
#include <thread>

#include <catch2/catch.hpp>

#include "launcher/fault_signals.hpp"
#include "launcher/stopped_processes.hpp"

namespace wsn::launcher {
namespace {

common::Scenario withSupernodes(std::size_t count) {
  common::Scenario s;
  s.run.ticks = 50;
  s.supernodes.assign(count, common::Vec2{10, 10});
  return s;
}

TEST_CASE("node tiles may be lost by hand, supernodes while another stays, the machinery never", "[launcher][faults]") {
  HandLosses losses(withSupernodes(3));
  CHECK(losses.survivable("node", 0));
  CHECK(losses.survivable("node", 1));
  CHECK_FALSE(losses.survivable("network", 0));
  CHECK_FALSE(losses.survivable("aggregator", 0));
  CHECK(losses.survivable("supernode", 2));
  CHECK(losses.survivable("supernode", 0));
  CHECK_FALSE(losses.survivable("supernode", 1));  // the last one left
}

TEST_CASE("a supernode the scenario kills does not count as the one left", "[launcher][faults]") {
  auto scenario = withSupernodes(2);
  scenario.faults = {common::FaultSpec::kill(common::FaultRole::kSupernode, 1, 10)};
  HandLosses losses(scenario);
  CHECK_FALSE(losses.survivable("supernode", 0));
}

TEST_CASE("a restart is due once its supernode was killed and the sources near its tick, once", "[launcher][faults]") {
  using common::FaultRole;
  using common::FaultSpec;
  // Supernode 1 (slot 5) killed at 10, back at 20, killed at 30, back at 40; max 3 ticks in flight.
  const common::FaultPlan plan({FaultSpec::kill(FaultRole::kSupernode, 1, 10), FaultSpec::restart(FaultRole::kSupernode, 1, 40),
                                FaultSpec::kill(FaultRole::kSupernode, 1, 30), FaultSpec::restart(FaultRole::kSupernode, 1, 20)},
                               2, 2);
  RestartSchedule schedule(plan, {4, 5}, 3);
  CHECK(schedule.due(30).empty());  // not killed yet: nothing to start, whatever the tick
  schedule.killed(5);
  CHECK(schedule.due(15).empty());  // the sources may reach tick 19 from 16 on
  const auto first = schedule.due(16);
  REQUIRE(first.size() == 1);
  CHECK(first[0] == std::pair<std::size_t, std::int32_t>{5, 20});
  CHECK(schedule.due(17).empty());  // once
  schedule.killed(5);  // the second kill
  CHECK(schedule.due(35).empty());
  CHECK(schedule.due(36) == std::vector<std::pair<std::size_t, std::int32_t>>{{5, 40}});
  CHECK(schedule.due(100).empty());
}

TEST_CASE("a child stopped for a while is named with how long, a running one is not", "[launcher][faults]") {
  CHECK(processState(::getpid()) == 'R');
  CHECK(processState(-1) == '?');
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    ::pause();
    ::_exit(0);
  }
  StoppedProcesses stopped(StoppedProcesses::Clock::now());
  stopped.sample(child, "supernode 1", false);
  CHECK(stopped.diagnosis(std::chrono::milliseconds(0)).empty());
  ::kill(child, SIGSTOP);
  for (int i = 0; i < 100 && processState(child) != 'T'; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  REQUIRE(processState(child) == 'T');
  stopped.sample(child, "supernode 1", false);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  stopped.sample(child, "supernode 1", false);
  // A stop the scenario asked for is not a diagnosis.
  StoppedProcesses expected(StoppedProcesses::Clock::now());
  expected.sample(child, "supernode 1", true);
  expected.sample(child, "supernode 1", true);
  CHECK(expected.diagnosis(std::chrono::milliseconds(0)).empty());
  ::kill(child, SIGCONT);
  for (int i = 0; i < 100 && processState(child) == 'T'; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  stopped.sample(child, "supernode 1", false);
  ::kill(child, SIGKILL);
  ::waitpid(child, nullptr, 0);

  const auto text = stopped.diagnosis(std::chrono::milliseconds(200));
  const std::string head = "supernode 1 was stopped (SIGSTOP or a debugger) for about ";
  REQUIRE(text.rfind(head, 0) == 0);
  CHECK(std::stod(text.substr(head.size())) >= 0.25);  // the 300 ms between the samples, to 0.1 s
  CHECK(text.find(" s into the run") != std::string::npos);
  CHECK(stopped.diagnosis(std::chrono::milliseconds(5000)).empty());  // shorter than asked for
}

}  // namespace
}  // namespace wsn::launcher
