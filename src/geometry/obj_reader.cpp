#include "geometry/obj_reader.hpp"

#include "base/number_text.hpp"

#include "geometry/cage_validation.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <string_view>
#include <vector>

namespace subfeed::geometry {

namespace {

std::vector<std::string_view> split_words(std::string_view text) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && (text[i] == ' ' || text[i] == '\t')) {
      ++i;
    }
    const std::size_t start = i;
    while (i < text.size() && text[i] != ' ' && text[i] != '\t') {
      ++i;
    }
    if (i > start) {
      words.push_back(text.substr(start, i - start));
    }
  }
  return words;
}

class ObjParser {
public:
  explicit ObjParser(std::string source) { cage_.source = std::move(source); }

  Expected<void> line(std::string_view text, int number) {
    line_ = number;
    if (const auto hash = text.find('#'); hash != std::string_view::npos) {
      text = text.substr(0, hash);
    }
    const auto words = split_words(text);
    if (words.empty()) {
      return {};
    }
    const std::string_view kind = words[0];
    if (kind == "v") {
      return vertex(words);
    }
    if (kind == "f") {
      return face(words);
    }
    if (kind == "t") {
      return tag(words);
    }
    if (kind == "vt" || kind == "vn" || kind == "vp" || kind == "o" || kind == "g" || kind == "s" ||
        kind == "mtllib" || kind == "usemtl") {
      return {};
    }
    return error("unsupported OBJ statement '" + std::string(kind) + "'");
  }

  Expected<Cage> finish() {
    if (cage_.face_sizes.empty()) {
      return fail(ErrorCode::bad_input, "no faces: not a control cage", {cage_.source, 0, {}});
    }
    if (auto valid = validate_cage(cage_); !valid) {
      return std::unexpected(valid.error());
    }
    return std::move(cage_);
  }

private:
  std::unexpected<Error> error(std::string message) const {
    return fail(ErrorCode::bad_input, std::move(message), {cage_.source, line_, {}});
  }

  Expected<double> number(std::string_view word) const {
    const auto value = parse_double(word);
    if (!value) {
      std::string lower(word.substr(word.starts_with('-') || word.starts_with('+') ? 1 : 0));
      std::ranges::transform(lower, lower.begin(), [](unsigned char c) { return std::tolower(c); });
      const bool infinite = lower.starts_with("nan") || lower.starts_with("inf");
      return error(infinite ? "coordinate '" + std::string(word) + "' is not finite"
                            : "'" + std::string(word) + "' is not a number");
    }
    return *value;
  }

  Expected<long> integer(std::string_view word) const {
    const auto value = parse_long(word);
    if (!value) {
      return error("'" + std::string(word) + "' is not an integer");
    }
    return *value;
  }

  Expected<void> vertex(const std::vector<std::string_view>& words) {
    if (words.size() != 4 && words.size() != 5) {
      return error("a vertex needs 3 coordinates (x y z), got " + std::to_string(words.size() - 1));
    }
    Eigen::Vector3d p;
    for (int i = 0; i < 3; ++i) {
      auto value = number(words[static_cast<std::size_t>(i) + 1]);
      if (!value) {
        return std::unexpected(value.error());
      }
      p[i] = *value;
    }
    cage_.positions.push_back(p);
    return {};
  }

  // OBJ indices are 1-based; negative ones count back from the last vertex read so far.
  Expected<int> face_vertex(std::string_view word) const {
    const auto index = integer(word.substr(0, word.find('/')));
    if (!index) {
      return std::unexpected(index.error());
    }
    const long count = static_cast<long>(cage_.positions.size());
    const long resolved = *index > 0 ? *index - 1 : count + *index;
    if (*index == 0 || resolved < 0 || resolved >= count) {
      return error("vertex index " + std::to_string(*index) + " is out of range (" +
                   std::to_string(count) + " vertices defined so far)");
    }
    return static_cast<int>(resolved);
  }

  Expected<void> face(const std::vector<std::string_view>& words) {
    if (words.size() < 4) {
      return error("a face needs at least 3 vertices, got " + std::to_string(words.size() - 1));
    }
    cage_.face_offsets.push_back(static_cast<int>(cage_.face_indices.size()));
    for (std::size_t i = 1; i < words.size(); ++i) {
      auto v = face_vertex(words[i]);
      if (!v) {
        return std::unexpected(v.error());
      }
      cage_.face_indices.push_back(*v);
    }
    cage_.face_sizes.push_back(static_cast<int>(words.size() - 1));
    cage_.face_lines.push_back(line_);
    return {};
  }

  // OpenSubdiv shape tag: `t name nint/nfloat/nstring ints... floats... strings...`.
  Expected<void> tag(const std::vector<std::string_view>& words) {
    if (words.size() < 3) {
      return error("a tag needs a name and an argument count 'nint/nfloat/nstring'");
    }
    const std::string_view name = words[1];
    TagArguments args;
    if (auto parsed = tag_arguments(words, args); !parsed) {
      return parsed;
    }
    if (name == "crease") {
      return crease(args.ints, args.floats);
    }
    if (name == "corner") {
      return corner(args.ints, args.floats);
    }
    if (name == "interpolateboundary") {
      return interpolate_boundary(args.ints);
    }
    if (name == "hole") {
      return hole(args.ints);
    }
    if (name == "creasemethod") {
      return crease_method(args.strings);
    }
    if (name == "smoothtriangles") {
      return smooth_triangles(args.strings);
    }
    // Face-varying data (texture coordinates) does not change the shape, and the planner
    // reads none.
    if (name == "facevaryinginterpolateboundary" || name == "facevaryingpropagatecorners") {
      return {};
    }
    if (name == "vertexedit" || name == "edgeedit") {
      return error("tag '" + std::string(name) +
                   "' is a hierarchical edit, which OpenSubdiv 3 does not evaluate: apply it "
                   "in the modeller and export the edited cage");
    }
    return error("unsupported tag '" + std::string(name) +
                 "' (crease, corner, hole, interpolateboundary, creasemethod, smoothtriangles, "
                 "facevaryinginterpolateboundary, facevaryingpropagatecorners)");
  }

  struct TagArguments {
    std::vector<long> ints;
    std::vector<double> floats;
    std::vector<std::string_view> strings;
  };

  Expected<void> tag_arguments(const std::vector<std::string_view>& words,
                               TagArguments& args) const {
    const std::string_view counts = words[2];
    const auto slash1 = counts.find('/');
    const auto slash2 = counts.find('/', slash1 == std::string_view::npos ? slash1 : slash1 + 1);
    if (slash1 == std::string_view::npos || slash2 == std::string_view::npos) {
      return error("tag argument count '" + std::string(counts) + "' is not 'nint/nfloat/nstring'");
    }
    const auto n_int = parse_long(counts.substr(0, slash1));
    const auto n_float = parse_long(counts.substr(slash1 + 1, slash2 - slash1 - 1));
    const auto n_string = parse_long(counts.substr(slash2 + 1));
    if (!n_int || !n_float || !n_string || *n_int < 0 || *n_float < 0 || *n_string < 0) {
      return error("tag argument count '" + std::string(counts) +
                   "' must be three non-negative integers");
    }
    const long declared = *n_int + *n_float + *n_string;
    if (words.size() != 3 + static_cast<std::size_t>(declared)) {
      return error("tag declares " + std::to_string(declared) + " arguments but has " +
                   std::to_string(words.size() - 3));
    }
    std::size_t at = 3;
    for (long i = 0; i < *n_int; ++i, ++at) {
      auto value = integer(words[at]);
      if (!value) {
        return std::unexpected(value.error());
      }
      args.ints.push_back(*value);
    }
    for (long i = 0; i < *n_float; ++i, ++at) {
      auto value = number(words[at]);
      if (!value) {
        return std::unexpected(value.error());
      }
      args.floats.push_back(*value);
    }
    for (long i = 0; i < *n_string; ++i, ++at) {
      args.strings.push_back(words[at]);
    }
    return {};
  }

  Expected<double> sharpness(const std::vector<double>& floats, std::size_t i) const {
    const double s = floats.size() == 1 ? floats[0] : floats[i];
    if (s < 0.0) {
      return error("sharpness " + std::to_string(s) + " is negative");
    }
    return s;
  }

  // Vertex indices of tags are 0-based and checked against the cage once all is read.
  Expected<void> crease(const std::vector<long>& ints, const std::vector<double>& floats) {
    const std::size_t edges = ints.size() / 2;
    if (ints.empty() || ints.size() % 2 != 0 || (floats.size() != 1 && floats.size() != edges)) {
      return error("crease needs vertex pairs and one sharpness, or one per pair");
    }
    for (std::size_t e = 0; e < edges; ++e) {
      auto s = sharpness(floats, e);
      if (!s) {
        return std::unexpected(s.error());
      }
      cage_.creases.push_back(
          {static_cast<int>(ints[2 * e]), static_cast<int>(ints[2 * e + 1]), *s, line_});
    }
    return {};
  }

  Expected<void> corner(const std::vector<long>& ints, const std::vector<double>& floats) {
    if (ints.empty() || (floats.size() != 1 && floats.size() != ints.size())) {
      return error("corner needs vertices and one sharpness, or one per vertex");
    }
    for (std::size_t i = 0; i < ints.size(); ++i) {
      auto s = sharpness(floats, i);
      if (!s) {
        return std::unexpected(s.error());
      }
      cage_.corners.push_back({static_cast<int>(ints[i]), *s, line_});
    }
    return {};
  }

  Expected<void> interpolate_boundary(const std::vector<long>& ints) {
    if (ints.size() != 1 || ints[0] < 0 || ints[0] > 2) {
      return error("interpolateboundary takes one integer: 0 none, 1 edge only, 2 edge and corner");
    }
    cage_.boundary = static_cast<BoundaryInterpolation>(ints[0]);
    return {};
  }

  // Face indices are 0-based, as crease and corner vertices are.
  Expected<void> hole(const std::vector<long>& ints) {
    if (ints.empty()) {
      return error("hole needs at least one face index (0-based)");
    }
    for (const long face : ints) {
      cage_.holes.push_back({static_cast<int>(face), line_});
    }
    return {};
  }

  Expected<void> crease_method(const std::vector<std::string_view>& strings) {
    if (strings.size() == 1 && strings[0] == "normal") {
      cage_.creasing = CreasingMethod::uniform;
    } else if (strings.size() == 1 && strings[0] == "chaikin") {
      cage_.creasing = CreasingMethod::chaikin;
    } else {
      return error("creasemethod takes one string: normal or chaikin");
    }
    return {};
  }

  Expected<void> smooth_triangles(const std::vector<std::string_view>& strings) {
    if (strings.size() == 1 && strings[0] == "catmark") {
      cage_.triangles = TriangleRule::catmark;
    } else if (strings.size() == 1 && strings[0] == "smooth") {
      cage_.triangles = TriangleRule::smooth;
    } else {
      return error("smoothtriangles takes one string: catmark or smooth");
    }
    return {};
  }

  Cage cage_;
  int line_ = 0;
};

} // namespace

Expected<Cage> parse_obj(std::istream& in, const std::string& source) {
  ObjParser parser(source);
  std::string text;
  int number = 0;
  while (std::getline(in, text)) {
    ++number;
    if (!text.empty() && text.back() == '\r') {
      text.pop_back();
    }
    if (auto ok = parser.line(text, number); !ok) {
      return std::unexpected(ok.error());
    }
  }
  if (in.bad()) {
    return fail(ErrorCode::bad_input, "read error after line " + std::to_string(number),
                {source, 0, {}});
  }
  return parser.finish();
}

Expected<Cage> read_obj(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) {
    return fail(ErrorCode::bad_input, "cannot open cage file", {path.string(), 0, {}});
  }
  return parse_obj(in, path.string());
}

} // namespace subfeed::geometry
