#pragma once
// One posted program on its way to disk: the post (kinematics, solution choice, splitting,
// feeds) and the dialect's writer wired to PROGRAM and PROGRAM.map, pose by pose. The map
// has one line per program line, "<nc line> <cl line> cut|link", so every line traces back
// to the CL line it serves (0 for the program frame). Both files appear only once
// commit() succeeds; a sink dropped before it leaves neither. `post` and `run` both post
// through this one sink; `run` also taps every block (its motion-time model) and every line
// (its stream).

#include "base/atomic_output_file.hpp"
#include "base/error.hpp"
#include "cl/cl_pose.hpp"
#include "post/kinematics.hpp"
#include "post/machine_config.hpp"
#include "post/post_processor.hpp"
#include "post/program_writer.hpp"

#include <filesystem>
#include <functional>
#include <memory>
#include <string_view>

namespace subfeed::cl {
class ClReader;
}

namespace subfeed::post {

struct PostFileOptions {
  PostOptions post;
  ProgramOptions program; // dialect, decimals, line length taken from here, not the machine
  bool look_ahead = true; // read the CL data twice to choose the starting solution
  // Called with every pose before it is posted; an error ends the post and nothing is
  // written (the motion gate, when the caller has the part).
  std::function<Expected<void>(const cl::ClPose&)> check;
  // Called with every block the post makes, its own moves included (approach, retract and
  // turn, unwinding), before it is written: an error ends the post there, so the block
  // reaches neither the file nor a stream (the whole tool's gate on what the machine does).
  std::function<Expected<void>(const MotionBlock&)> check_block;
};

struct PostFileSummary {
  PostStats stats;
  long lines = 0; // G-code lines written
};

// Program options from the machine's controller settings (dialect, line length, decimals,
// program number); callers override what the command line says.
[[nodiscard]] ProgramOptions program_options_for(const MachineConfig& machine);

[[nodiscard]] std::filesystem::path map_path_for(const std::filesystem::path& program);

struct ProgramTaps {
  std::function<void(const MotionBlock&)> block;   // each block, before it is written
  std::function<void(std::string_view line)> line; // each line, once it is written
};

class ProgramSink {
public:
  // Opens both files (as temporaries). A machine without tool-centre-point control refuses
  // a TCP post. `machine` must outlive the sink.
  [[nodiscard]] static Expected<std::unique_ptr<ProgramSink>>
  create(const MachineConfig& machine, const PostFileOptions& options,
         const std::filesystem::path& program, ProgramTaps taps = {});
  ProgramSink(const ProgramSink&) = delete;
  ProgramSink& operator=(const ProgramSink&) = delete;
  ~ProgramSink();

  // Reads the whole CL data once to choose the starting rotary solution.
  [[nodiscard]] Expected<void> choose_start(cl::ClReader& reader);
  [[nodiscard]] Expected<void> begin(); // the program's start: before the first pose
  [[nodiscard]] Expected<void> add(const cl::ClPose& pose);
  [[nodiscard]] Expected<void> finish(); // the program's end: after the last pose
  [[nodiscard]] Expected<void> commit(); // both files in place

  [[nodiscard]] PostFileSummary summary() const;

private:
  ProgramSink(const MachineConfig& machine, const PostFileOptions& options,
              AtomicOutputFile program, AtomicOutputFile map, ProgramTaps taps);
  void write_line(std::string_view line, long cl_line, bool link);

  AtomicOutputFile program_, map_;
  ProgramTaps taps_;
  std::function<Expected<void>(const MotionBlock&)> check_block_;
  std::unique_ptr<Kinematics> kinematics_;
  ProgramWriter writer_;
  PostProcessor post_;
  long lines_ = 0;
  std::string text_;
};

} // namespace subfeed::post
