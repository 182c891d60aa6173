// shadowref/outputs/interruption.hpp — SIGINT and SIGTERM stop a run without leaving half a result.
//
// The command line installs the handlers once (install_interrupt_handlers); a handler only records
// the signal in an atomic flag, which is all a handler may safely do. The work polls the flag at its
// commit points — StagedFolder::commit and write_file_atomically, just before the rename that would
// publish a result — between units of work (conform: between references and between cases) and at
// cheap points inside every long one (a reference's tiles, the renderer's passes and bands of rows,
// the judge's probes, windows and causes), so that a run ends within about 2 s; it stops by
// throwing Interrupted: the unwinding removes what was in flight (staging folders, temporary
// files) and leaves the complete results already in place, so a rerun resumes from the complete
// reference cache entries. The command exits 128 + the signal (130 SIGINT, 143 SIGTERM) with one line.
// A second signal while the first is honoured ends the process at once (the default action): a
// person pressing Ctrl-C twice means it. Without installed handlers (a library used by a test) the
// flag is never set and every check is one relaxed atomic load.
#pragma once

#include <string>

namespace shadowref::outputs {

// Deliberately not a std::exception: the handlers that turn a failure into a case's ERROR or a
// bad-input line (`catch (const std::exception&)`) must not swallow a stop.
class Interrupted {
 public:
  explicit Interrupted(int signal) : signal_(signal) {}
  int signal() const { return signal_; }
  // The one line the command prints: "interrupted by SIGINT: …".
  std::string message() const;

 private:
  int signal_;
};

// SIGINT and SIGTERM set the flag (SA_RESTART: an interrupted write goes on, so a file in flight is
// finished or removed by its writer, never cut short by the signal).
void install_interrupt_handlers();

// The signal received, 0 when none.
int interrupt_signal();

// Throws Interrupted when a signal was received.
void throw_if_interrupted();

}  // namespace shadowref::outputs
