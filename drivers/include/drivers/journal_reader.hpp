#pragma once
// Reads a job's journal back (journal.hpp) for `resume`: the program and protocol of the
// job, the job record `run` left (if any), and how far the program got over all its runs:
// the last line sent and the last line the controller acknowledged (GRBL), with the bytes
// each was sent with, so that a rebuilt program can be checked against what was sent.
// Line numbers are the program file's throughout, so a resumed job appends to the same
// journal and can be resumed again.

#include "base/error.hpp"

#include <filesystem>
#include <optional>
#include <string>

namespace subfeed::drivers {

struct JournalSummary {
  std::string protocol; // grbl or fanuc
  std::string program;  // the G-code file
  std::string link;
  std::optional<std::string> job; // `run`'s job record (key=value ...)
  long last_sent = 0;
  long last_sent_bytes = 0;
  long last_acked = 0;   // answered ok
  bool finished = false; // the last run ended done
  std::string last_end;  // "done" or "failed <error>"
};

[[nodiscard]] Expected<JournalSummary> read_journal(const std::filesystem::path& path);

} // namespace subfeed::drivers
