#include "interrupt.h"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <stdexcept>

namespace geohybrid::apps
{
namespace
{
// A lock-free atomic is what a signal handler may write and other threads read (C++17,
// [support.signal]); relaxed order is enough for a flag polled every step.
std::atomic<int> received_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "the interrupt flag must be lock-free to be set by a signal handler");

extern "C" void record_signal(int signal) { received_signal.store(signal, std::memory_order_relaxed); }
} // namespace

void install_interrupt_handlers()
{
  struct sigaction action;
  std::memset(&action, 0, sizeof action);
  action.sa_handler = record_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART | SA_RESETHAND;
  for (const int signal : {SIGINT, SIGTERM})
    if (sigaction(signal, &action, nullptr) != 0)
      throw std::runtime_error("cannot install the handler of " + signal_name(signal) + ": " + std::strerror(errno));
}

int interrupt_signal() { return received_signal.load(std::memory_order_relaxed); }

std::string signal_name(int signal)
{
  if (signal == SIGINT)
    return "SIGINT";
  if (signal == SIGTERM)
    return "SIGTERM";
  return "signal " + std::to_string(signal);
}

void throw_if_interrupted(const std::string &during)
{
  if (const int signal = interrupt_signal())
    throw Interrupted(signal, "while " + during + ": nothing to resume yet", false);
}
} // namespace geohybrid::apps
