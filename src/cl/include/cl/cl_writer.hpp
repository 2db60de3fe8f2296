#pragma once
// Writes APT-style CL data one pose at a time into an AtomicOutputFile: the file appears
// under its name only after finish(). Writes only records ClReader accepts; a FEDRAT only
// when the feed changes. Positions with 6 decimals (1 nm), axis components with 9.

#include "base/atomic_output_file.hpp"
#include "cl/cl_pose.hpp"

#include <filesystem>
#include <string>

namespace subfeed::cl {

class ClWriter {
public:
  [[nodiscard]] static Expected<ClWriter> create(const std::filesystem::path& path,
                                                 const ClHeader& header);
  // Returns the line of the file the pose's GOTO is on (for trace maps).
  long write(const ClPose& pose);
  // The line write(pose) would put the pose's GOTO on, writing nothing (to name a pose
  // that was refused before it was written).
  [[nodiscard]] long line_of(const ClPose& pose) const;
  // Writes FINI and moves the file into place.
  [[nodiscard]] Expected<void> finish();

private:
  explicit ClWriter(AtomicOutputFile out, bool multiaxis);

  AtomicOutputFile out_;
  bool multiaxis_;
  double feed_ = -1.0;
  long line_ = 0; // lines written so far
  std::string buffer_;
};

} // namespace subfeed::cl
