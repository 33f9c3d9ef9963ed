#include <lme_mpm/base/interrupt.h>

#include <csignal>

namespace lme_mpm
{
namespace interrupt
{
namespace
{
volatile std::sig_atomic_t signal_seen = 0;

extern "C" void record(const int signal)
{
  if (signal_seen != 0)
  {
    // The second one: the user does not want to wait for the step to finish.
    std::signal(signal, SIG_DFL);
    std::raise(signal);
    return;
  }
  signal_seen = signal;
}
} // namespace

void install()
{
  std::signal(SIGINT, record);
  std::signal(SIGTERM, record);
  // Past the file-size limit (ulimit -f) a write fails with EFBIG, which the writers
  // report with the file's name, instead of the kernel ending the process.
  std::signal(SIGXFSZ, SIG_IGN);
}

int received()
{
  return signal_seen;
}

const char *name(const int signal)
{
  return signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "a signal";
}
} // namespace interrupt
} // namespace lme_mpm
