#pragma once
// SIGINT and SIGTERM as a request to stop cleanly (`geohybrid dem` and `geohybrid pullout`): the
// handler only records which signal came; the time-step loops look at it once a step (one atomic
// load), finish the step, save what lets --resume continue bit for bit (a checkpoint, the curve
// files so far) and throw Interrupted, which main() turns into one line naming the command that
// continues the run and the exit status a shell gives a process the signal killed (130, 143).
// summary.json is not written: a directory without it is not a finished run.
//
// The recorded signal is the program's one piece of global mutable state: a signal handler can
// reach nothing else. It lives here and is read only through interrupt_signal().
#include <exception>
#include <string>
#include <utility>

namespace geohybrid::apps
{
/// Installs the handlers of SIGINT and SIGTERM. Each handler is reset by its first signal, so a
/// second one while the run is finishing (writing its checkpoint) ends the process at once.
/// System calls interrupted by the signal are restarted (file writes go on).
void install_interrupt_handlers();

/// The signal received since the handlers were installed (SIGINT or SIGTERM), 0 if none.
int interrupt_signal();

/// "SIGINT", "SIGTERM", or "signal N".
std::string signal_name(int signal);

/// What a run throws once it has stopped for a signal and saved what it could. `what()` says
/// where it stopped and what it saved; `resumable()` whether --resume continues it (false: run
/// it again, as when the signal came before anything resumable was written).
class Interrupted : public std::exception
{
public:
  Interrupted(int signal, std::string what_happened, bool resumable)
    : signal_(signal), what_(std::move(what_happened)), resumable_(resumable)
  {}
  int signal() const { return signal_; }
  /// 128 + the signal: 130 for SIGINT, 143 for SIGTERM.
  int exit_status() const { return 128 + signal_; }
  bool resumable() const { return resumable_; }
  const char *what() const noexcept override { return what_.c_str(); }

private:
  int signal_;
  std::string what_;
  bool resumable_;
};

/// Throws Interrupted (not resumable, saying "while `during`: nothing to resume yet") if a signal
/// came: for loops with no state to save, such as a tank's filling, called from their progress
/// callbacks.
void throw_if_interrupted(const std::string &during);
} // namespace geohybrid::apps
