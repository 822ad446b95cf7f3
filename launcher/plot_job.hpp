// The plots of a run: tools/plot_run.py started beside the cluster, told to draw once the run
// succeeded, and what became of it.
#pragma once

#include <string>

namespace wsn::launcher {

/// What became of the plots of a run.
struct PlotOutcome {
  enum class Status { kDrawn, kSkipped, kFailed };
  Status status = Status::kSkipped;
  std::string message;  ///< one line: the files written, or why there are none
  double seconds = 0;
};

/// plot_run.py (located by install_layout) run by kPlotPython (the one with python3-matplotlib) on a run
/// directory, output to logs/plot.log. It is started before the cluster and waits on a pipe for the
/// word to go: python's start-up and matplotlib's import, most of the plotting time, overlap the
/// run instead of following it. A missing python, script or matplotlib gives kSkipped, any other
/// failure kFailed: neither undoes a run that succeeded.
class PlotJob {
 public:
  PlotJob(const std::string& plot_script, const std::string& run_dir, const std::string& format);
  PlotJob(const PlotJob&) = delete;
  PlotJob& operator=(const PlotJob&) = delete;
  /// A job never told to go is told to stop, and reaped.
  ~PlotJob();
  /// Lets the script draw (`go`) or tells it to stop, and waits for it.
  PlotOutcome finish(bool go);

 private:
  int pid_ = -1;
  int to_script_ = -1;  ///< write end of the script's stdin
  PlotOutcome outcome_;
  std::string log_;
  std::string files_;
};

}  // namespace wsn::launcher
