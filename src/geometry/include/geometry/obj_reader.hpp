#pragma once
// Reads a control cage from Wavefront OBJ. Accepted: `v x y z [w]`, `f` with any number of
// vertices (`i`, `i/t`, `i//n`, `i/t/n`, negative indices relative to the end), OpenSubdiv
// shape tags `t crease 2/1/0 v0 v1 s`, `t corner 1/1/0 v s`, `t interpolateboundary 1/0/0 m`
// (tag vertex indices are 0-based, as in OpenSubdiv's shapes), and the statements that do
// not change the shape (`vt vn vp o g s mtllib usemtl`, comments). Everything else, and
// every topological defect that would make the limit surface or a tool path wrong, is an
// error naming the file and line.

#include "base/error.hpp"
#include "geometry/cage.hpp"

#include <filesystem>
#include <istream>

namespace subfeed::geometry {

[[nodiscard]] Expected<Cage> read_obj(const std::filesystem::path& path);

// `source` names the stream in error messages.
[[nodiscard]] Expected<Cage> parse_obj(std::istream& in, const std::string& source);

} // namespace subfeed::geometry
