#include "post/post_file.hpp"

#include "base/atomic_output_file.hpp"
#include "cl/cl_reader.hpp"

namespace subfeed::post {

namespace {

// Errors from the post and the writer know the CL line; the file is the CL file.
Error in_file(Error error, const std::string& file) {
  if (error.where.file.empty() && error.where.line > 0) {
    error.where.file = file;
  }
  return error;
}

} // namespace

ProgramOptions program_options_for(const MachineConfig& machine) {
  ProgramOptions options;
  const auto& c = machine.controller;
  options.dialect = c.dialect;
  options.decimals = c.decimals;
  options.line_length = c.line_length;
  options.program_number = c.program_number;
  options.title = machine.name;
  return options;
}

std::filesystem::path map_path_for(const std::filesystem::path& program) {
  auto map = program;
  map += ".map";
  return map;
}

Expected<PostFileSummary> post_file(const std::filesystem::path& cl_path,
                                    const MachineConfig& machine, const PostFileOptions& options,
                                    const std::filesystem::path& out_path) {
  SUBFEED_TRY_ASSIGN(auto reader, cl::ClReader::open(cl_path));
  if (options.post.tcp != TcpMode::off && !machine.controller.tcp) {
    return fail(ErrorCode::bad_input, "the machine has no tool-centre-point control",
                {machine.source, 0, "controller.tcp"});
  }
  SUBFEED_TRY_ASSIGN(auto program, AtomicOutputFile::create(out_path));
  SUBFEED_TRY_ASSIGN(auto map, AtomicOutputFile::create(map_path_for(out_path)));
  map.write("# subfeed map: nc_line cl_line cut|link\n");
  const auto kinematics = make_kinematics(machine);
  PostOptions post_options = options.post;
  post_options.decimals = options.program.decimals;
  std::string text;
  long nc_line = 0;
  ProgramWriter writer(options.program, machine.axes,
                       [&](std::string_view line, long cl_line, bool link) {
                         ++nc_line;
                         text.assign(line);
                         text += '\n';
                         program.write(text);
                         text = std::to_string(nc_line) + ' ' + std::to_string(cl_line) +
                                (link ? " link\n" : " cut\n");
                         map.write(text);
                       });
  PostProcessor post(machine, *kinematics, post_options,
                     [&writer](const MotionBlock& block) { return writer.write(block); });
  const auto run = [&]() -> Expected<void> {
    if (options.look_ahead) {
      SUBFEED_TRY(post.choose_start(reader));
    }
    SUBFEED_TRY(writer.begin());
    while (true) {
      SUBFEED_TRY_ASSIGN(const auto pose, reader.next());
      if (!pose) {
        break;
      }
      if (options.check) {
        SUBFEED_TRY(options.check(*pose));
      }
      SUBFEED_TRY(post.add(*pose));
    }
    SUBFEED_TRY(post.finish());
    return writer.end();
  };
  if (auto done = run(); !done) {
    return std::unexpected(in_file(std::move(done).error(), reader.file()));
  }
  SUBFEED_TRY(program.commit());
  SUBFEED_TRY(map.commit());
  return PostFileSummary{post.stats(), writer.lines()};
}

} // namespace subfeed::post
