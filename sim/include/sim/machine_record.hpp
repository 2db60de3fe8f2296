#pragma once
// What a simulated machine leaves for whoever comes after its controller: the lines it
// carried out (ExecutionLog) and where its axes stand (MachineStateFile), each optional.
// Both simulators keep one, fed from their planner queue.

#include "sim/execution_log.hpp"
#include "sim/machine_state_file.hpp"
#include "sim/motion_planner.hpp"

#include <cstddef>
#include <memory>
#include <string>

namespace subfeed::sim {

struct MachineRecordOptions {
  std::string executed_log;                        // empty: no log
  std::shared_ptr<MachineStateFile> machine_state; // null: the position dies with the controller
};

class MachineRecord {
public:
  explicit MachineRecord(const MachineRecordOptions& options);

  // The planner starts where the machine was left, when that is known.
  void restore(MotionPlanner& planner) const;
  // A line accepted; `queued_move`: it put a block in the planner queue.
  void accepted(std::string line, bool queued_move) { log_.accepted(std::move(line), queued_move); }
  // The planner ran `finished` more blocks and stands at its position.
  void advanced(const MotionPlanner& planner, std::size_t finished);
  // The planner queue was dropped (reset, alarm).
  void dropped() { log_.dropped(); }

private:
  ExecutionLog log_;
  std::shared_ptr<MachineStateFile> state_;
};

} // namespace subfeed::sim
