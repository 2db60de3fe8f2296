#pragma once
// The modal state a Fanuc-style program has built up by a given block, and the blocks that
// restore it when drip feed restarts in the middle of the program (--from N): units, plane,
// distance mode, feed mode, work offset, tool, tool length offset or TCP (G43.4), spindle,
// coolant, feed and motion mode. None of the restore blocks moves an axis. Restarting
// inside cutter radius compensation (G41/G42) or G43.5 is refused: their state depends on
// the path and the tool vector, not on words.

#include "base/error.hpp"

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace subfeed::drivers {

class FanucModalState {
public:
  void apply(std::string_view block);
  [[nodiscard]] Expected<std::vector<std::string>> restore_blocks(const Where& restart) const;

private:
  std::map<int, std::string> groups_; // modal group -> G code as written, e.g. 1 -> "G01"
  std::optional<std::string> feed_, speed_, tool_, length_offset_, spindle_, coolant_;
  bool tool_changed_ = false;
};

} // namespace subfeed::drivers
