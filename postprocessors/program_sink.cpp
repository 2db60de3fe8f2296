#include "post/program_sink.hpp"

#include "cl/cl_reader.hpp"

#include <string>

namespace subfeed::post {

namespace {

PostOptions with_program_decimals(PostOptions post, const ProgramOptions& program) {
  post.decimals = program.decimals;
  return post;
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

Expected<std::unique_ptr<ProgramSink>> ProgramSink::create(const MachineConfig& machine,
                                                           const PostFileOptions& options,
                                                           const std::filesystem::path& program,
                                                           ProgramTaps taps) {
  if (options.post.tcp != TcpMode::off && !machine.controller.tcp) {
    return fail(ErrorCode::bad_input, "the machine has no tool-centre-point control",
                {machine.source, 0, "controller.tcp"});
  }
  SUBFEED_TRY_ASSIGN(auto program_file, AtomicOutputFile::create(program));
  SUBFEED_TRY_ASSIGN(auto map_file, AtomicOutputFile::create(map_path_for(program)));
  map_file.write("# subfeed map: nc_line cl_line cut|link\n");
  return std::unique_ptr<ProgramSink>(new ProgramSink(machine, options, std::move(program_file),
                                                      std::move(map_file), std::move(taps)));
}

ProgramSink::ProgramSink(const MachineConfig& machine, const PostFileOptions& options,
                         AtomicOutputFile program, AtomicOutputFile map, ProgramTaps taps)
    : program_(std::move(program)), map_(std::move(map)), taps_(std::move(taps)),
      check_block_(options.check_block), kinematics_(make_kinematics(machine)),
      writer_(options.program, machine.axes,
              [this](std::string_view line, long cl_line, bool link) {
                write_line(line, cl_line, link);
              }),
      post_(machine, *kinematics_, with_program_decimals(options.post, options.program),
            [this](const MotionBlock& block) -> Expected<void> {
              if (check_block_) {
                SUBFEED_TRY(check_block_(block));
              }
              if (taps_.block) {
                taps_.block(block);
              }
              return writer_.write(block);
            }) {}

ProgramSink::~ProgramSink() = default;

void ProgramSink::write_line(std::string_view line, long cl_line, bool link) {
  ++lines_;
  text_.assign(line);
  text_ += '\n';
  program_.write(text_);
  text_ = std::to_string(lines_) + ' ' + std::to_string(cl_line) + (link ? " link\n" : " cut\n");
  map_.write(text_);
  if (taps_.line) {
    taps_.line(line);
  }
}

Expected<void> ProgramSink::choose_start(cl::ClReader& reader) {
  return post_.choose_start(reader);
}

Expected<void> ProgramSink::begin() {
  return writer_.begin();
}

Expected<void> ProgramSink::add(const cl::ClPose& pose) {
  return post_.add(pose);
}

Expected<void> ProgramSink::finish() {
  SUBFEED_TRY(post_.finish());
  return writer_.end();
}

Expected<void> ProgramSink::commit() {
  SUBFEED_TRY(program_.commit());
  return map_.commit();
}

PostFileSummary ProgramSink::summary() const {
  return PostFileSummary{post_.stats(), writer_.lines()};
}

} // namespace subfeed::post
