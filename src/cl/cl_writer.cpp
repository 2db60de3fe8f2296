#include "cl/cl_writer.hpp"

#include "base/decimal_text.hpp"

#include <algorithm>
#include <utility>

namespace subfeed::cl {

Expected<ClWriter> ClWriter::create(const std::filesystem::path& path, const ClHeader& header) {
  SUBFEED_TRY_ASSIGN(auto out, AtomicOutputFile::create(path));
  ClWriter writer(std::move(out), header.multiaxis);
  std::string text = "PARTNO " + header.part_name + "\nUNITS/MM\nCUTTER/";
  append_decimal(text, header.cutter.diameter, 6);
  text += ',';
  append_decimal(text, header.cutter.corner_radius, 6);
  text += header.multiaxis ? "\nMULTAX/ON\n" : "\n";
  if (!header.setup.empty()) {
    text += "PPRINT SETUP " + header.setup + "\n";
  }
  if (!header.whole_tool.tool.empty()) {
    text += "PPRINT TOOL " + header.whole_tool.tool + "\n";
  }
  if (!header.whole_tool.fixture.empty()) {
    text += "PPRINT FIXTURE " + header.whole_tool.fixture + "\n";
  }
  writer.out_.write(text);
  writer.line_ = static_cast<long>(std::ranges::count(text, '\n'));
  return writer;
}

ClWriter::ClWriter(AtomicOutputFile out, bool multiaxis)
    : out_(std::move(out)), multiaxis_(multiaxis) {}

long ClWriter::write(const ClPose& pose) {
  buffer_.clear();
  if (pose.kind == MoveKind::rapid) {
    buffer_ += "RAPID\n";
  } else {
    if (pose.feed != feed_) {
      buffer_ += "FEDRAT/";
      append_decimal(buffer_, pose.feed, 3);
      buffer_ += '\n';
      feed_ = pose.feed;
    }
    if (pose.kind == MoveKind::plunge) {
      buffer_ += "PLUNGE\n";
    } else if (pose.kind == MoveKind::retract) {
      buffer_ += "RETRACT\n";
    }
  }
  buffer_ += "GOTO/";
  for (std::size_t i = 0; i < 3; ++i) {
    append_fixed(buffer_, pose.tip[i], 6);
    buffer_ += ',';
  }
  if (multiaxis_) {
    for (std::size_t i = 0; i < 3; ++i) {
      append_fixed(buffer_, pose.axis[i], 9);
      buffer_ += ',';
    }
  }
  buffer_.back() = '\n';
  out_.write(buffer_);
  line_ += std::count(buffer_.begin(), buffer_.end(), '\n');
  return line_;
}

long ClWriter::line_of(const ClPose& pose) const {
  if (pose.kind == MoveKind::rapid) {
    return line_ + 2;
  }
  const bool kind_line = pose.kind == MoveKind::plunge || pose.kind == MoveKind::retract;
  return line_ + 1 + (pose.feed != feed_ ? 1 : 0) + (kind_line ? 1 : 0);
}

Expected<void> ClWriter::finish() {
  out_.write("FINI\n");
  return out_.commit();
}

} // namespace subfeed::cl
