#pragma once
// `subfeed post` as a library call: CL data file in, G-code file out, one pose and one
// block at a time. Beside the program it writes PROGRAM.map, one line per G-code line:
// "<nc line> <cl line> cut|link", so every output line traces back to the CL line it
// serves (0 for the program frame). Both files appear only when complete.

#include "base/error.hpp"
#include "post/machine_config.hpp"
#include "post/post_processor.hpp"
#include "post/program_writer.hpp"

#include <filesystem>
#include <functional>

namespace subfeed::post {

struct PostFileOptions {
  PostOptions post;
  ProgramOptions program; // dialect, decimals, line length taken from here, not the machine
  bool look_ahead = true; // read the CL data twice to choose the starting solution
  // Called with every pose before it is posted; an error ends the post and nothing is
  // written (the motion gate, when the caller has the part).
  std::function<Expected<void>(const cl::ClPose&)> check;
};

struct PostFileSummary {
  PostStats stats;
  long lines = 0; // G-code lines written
};

// Program options from the machine's controller settings (dialect, line length, decimals,
// program number); callers override what the command line says.
[[nodiscard]] ProgramOptions program_options_for(const MachineConfig& machine);

[[nodiscard]] std::filesystem::path map_path_for(const std::filesystem::path& program);

[[nodiscard]] Expected<PostFileSummary> post_file(const std::filesystem::path& cl_path,
                                                  const MachineConfig& machine,
                                                  const PostFileOptions& options,
                                                  const std::filesystem::path& out_path);

} // namespace subfeed::post
