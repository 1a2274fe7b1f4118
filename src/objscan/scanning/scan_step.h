#pragma once
// The kinds of step the scanner takes, behind one interface: the paper's object step (next best
// object and view), frontier exploration, and objscan's coverage views of completed objects. A
// guidance (scanner.guidance) is the order in which the kinds are tried: each step, the first kind
// that takes a step ends it; when none takes one, the run ends for the last reason a kind gave.
#include <optional>

#include "objscan/scanning/run_record.h"

namespace objscan::scanning {

struct StepOutcome {
  bool taken = false;              // the robot moved or sensed, or the step was spent otherwise
  std::optional<Termination> end;  // when not taken: why the run would end (none: no reason given)

  static StepOutcome Taken() { return {true, std::nullopt}; }
  static StepOutcome NotTaken(std::optional<Termination> why = std::nullopt) { return {false, why}; }
};

class ScanStep {
 public:
  virtual ~ScanStep() = default;
  virtual const char* name() const = 0;
  // Takes this kind of step if it has one to take, writing what it did into `step`.
  virtual StepOutcome Take(StepRecord* step) = 0;
};

}  // namespace objscan::scanning
