#pragma once
// Where the simulated machine's axes physically are, kept in a file that outlives the
// controller process: a machine with absolute encoders (or one homed again before a resume)
// knows its position after its controller died, although the controller's queue is gone.
// The record has a fixed length and is rewritten in place with one pwrite, so a controller
// killed at any moment leaves either the old position or the new one, never a torn one.

#include "base/error.hpp"
#include "base/unique_fd.hpp"
#include "sim/gcode_interpreter.hpp"

#include <filesystem>
#include <optional>

namespace subfeed::sim {

class MachineStateFile {
public:
  // Opens (creating) the file; the position it holds, if any, is in stored().
  [[nodiscard]] static Expected<MachineStateFile> open(const std::filesystem::path& path);

  [[nodiscard]] const std::optional<AxisArray>& stored() const { return stored_; }
  // Records the position unless it is the one recorded last.
  void save(const AxisArray& position);

private:
  MachineStateFile(UniqueFd fd, std::optional<AxisArray> stored)
      : fd_(std::move(fd)), stored_(stored) {}
  UniqueFd fd_;
  std::optional<AxisArray> stored_;
  std::optional<AxisArray> saved_;
};

} // namespace subfeed::sim
