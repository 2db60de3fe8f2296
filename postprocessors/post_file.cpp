#include "post/post_file.hpp"

#include "cl/cl_reader.hpp"

namespace subfeed::post {

namespace {

Expected<void> post_all(cl::ClReader& reader, ProgramSink& sink, const PostFileOptions& options) {
  if (options.look_ahead) {
    SUBFEED_TRY(sink.choose_start(reader));
  }
  SUBFEED_TRY(sink.begin());
  while (true) {
    SUBFEED_TRY_ASSIGN(const auto pose, reader.next());
    if (!pose) {
      break;
    }
    if (options.check) {
      SUBFEED_TRY(options.check(*pose));
    }
    SUBFEED_TRY(sink.add(*pose));
  }
  return sink.finish();
}

} // namespace

Expected<PostFileSummary> post_file(const std::filesystem::path& cl_path,
                                    const MachineConfig& machine, const PostFileOptions& options,
                                    const std::filesystem::path& out_path) {
  SUBFEED_TRY_ASSIGN(auto reader, cl::ClReader::open(cl_path));
  SUBFEED_TRY_ASSIGN(auto sink, ProgramSink::create(machine, options, out_path));
  if (auto done = post_all(reader, *sink, options); !done) {
    return std::unexpected(cl::in_cl_file(std::move(done).error(), reader.file()));
  }
  SUBFEED_TRY(sink->commit());
  return sink->summary();
}

} // namespace subfeed::post
