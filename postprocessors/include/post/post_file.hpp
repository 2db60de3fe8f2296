#pragma once
// `subfeed post` as a library call: CL data file in, G-code file and its .map out, one pose
// and one block at a time (post/program_sink.hpp). Both files appear only when complete.

#include "base/error.hpp"
#include "post/machine_config.hpp"
#include "post/program_sink.hpp"

#include <filesystem>

namespace subfeed::post {

[[nodiscard]] Expected<PostFileSummary> post_file(const std::filesystem::path& cl_path,
                                                  const MachineConfig& machine,
                                                  const PostFileOptions& options,
                                                  const std::filesystem::path& out_path);

} // namespace subfeed::post
