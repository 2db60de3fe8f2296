#pragma once
// Reads APT-style CL data one pose at a time from a file, so memory does not depend on its
// length. The grammar is exactly what ClWriter writes (README "CL data"): header records
// PARTNO, UNITS/MM, CUTTER/d[,r,...], MULTAX[/ON|/OFF], PPRINT text (PPRINT SETUP keeps the
// part's setup); motion records RAPID, PLUNGE and
// RETRACT (each for the next GOTO only), FEDRAT/f[,MMPM] (modal), GOTO/x,y,z[,i,j,k]; FINI
// last; `$$` comments and blank lines anywhere. Anything else, a missing FINI (a truncated
// file), a tool axis that is not a unit vector or a feed move before any FEDRAT is an error
// naming file:line.

#include "base/error.hpp"
#include "cl/cl_pose.hpp"

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

namespace subfeed::cl {

class ClReader {
public:
  // Opens the file and reads its header (up to the first motion record).
  [[nodiscard]] static Expected<ClReader> open(const std::filesystem::path& path);

  [[nodiscard]] const ClHeader& header() const { return header_; }
  [[nodiscard]] const std::string& file() const { return file_; }

  // The next pose; nullopt once FINI has been read.
  [[nodiscard]] Expected<std::optional<ClPose>> next();

  // Bytes of the file consumed so far (a system call: for progress, now and then).
  [[nodiscard]] long long offset() { return static_cast<long long>(in_.tellg()); }

  // Back to the first pose, for a second pass over the same file.
  [[nodiscard]] Expected<void> rewind();

private:
  ClReader(std::string file, std::ifstream in);
  [[nodiscard]] Expected<void> read_header();
  [[nodiscard]] Expected<bool> header_record(std::string_view record);
  [[nodiscard]] Expected<std::optional<ClPose>> motion_record(std::string_view record);
  [[nodiscard]] Expected<std::optional<ClPose>> goto_record(std::string_view args);
  [[nodiscard]] std::unexpected<Error> error(std::string message) const;

  struct Modal {
    MoveKind next_kind = MoveKind::feed;
    double feed = 0.0;
  };

  std::string file_;
  std::ifstream in_;
  std::string text_;
  long line_ = 0;
  bool finished_ = false;
  bool units_seen_ = false;
  ClHeader header_;
  Modal modal_;
  std::streampos data_start_{};
  long data_start_line_ = 0;
};

// An error that knows its CL line but not the file (the post's, the motion gate's), named in
// `file`; any other error as it is.
[[nodiscard]] Error in_cl_file(Error error, const std::filesystem::path& file);

} // namespace subfeed::cl
