#pragma once
// The modal state a program has built up by a given block (Fanuc M-series modal groups,
// which GRBL shares), and the blocks that restore it when a program restarts in the middle
// (`send --from N`, `resume`): units, plane,
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

namespace subfeed::gcode {

class ModalState {
public:
  // An error naming `where` when the block is not words (gcode/words.hpp): a restart from
  // a state that could not be read would be a guess.
  [[nodiscard]] Expected<void> apply(std::string_view block, const Where& where = {});
  [[nodiscard]] Expected<std::vector<std::string>> restore_blocks(const Where& restart) const;

private:
  std::map<int, std::string> groups_; // modal group -> G code as written, e.g. 1 -> "G01"
  std::optional<std::string> feed_, speed_, tool_, length_offset_, spindle_, coolant_;
  bool tool_changed_ = false;
};

} // namespace subfeed::gcode
