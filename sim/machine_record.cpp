#include "sim/machine_record.hpp"

namespace subfeed::sim {

MachineRecord::MachineRecord(const MachineRecordOptions& options)
    : log_(options.executed_log.empty() ? ExecutionLog() : ExecutionLog(options.executed_log)),
      state_(options.machine_state) {}

void MachineRecord::restore(MotionPlanner& planner) const {
  if (state_ && state_->stored()) {
    planner.set_position(*state_->stored());
  }
}

void MachineRecord::advanced(const MotionPlanner& planner, std::size_t finished) {
  log_.finished(finished);
  if (state_) {
    state_->save(planner.position());
  }
}

} // namespace subfeed::sim
