#include "geometry/obj_reader.hpp"

#include <catch2/catch.hpp>
#include <sstream>

using subfeed::geometry::BoundaryInterpolation;
using subfeed::geometry::parse_obj;

namespace {

auto parse(const std::string& text) {
  std::istringstream in(text);
  return parse_obj(in, "part.obj");
}

// Two quads sharing the edge 2-5, counter-clockwise seen from +Z.
const std::string two_quads = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\n"
                              "f 1 2 5 4\nf 2 3 6 5\n";

// Expects an error whose one-line description is exactly `line_and_message`.
void expect_error(const std::string& text, const std::string& description) {
  const auto cage = parse(text);
  REQUIRE_FALSE(cage);
  CHECK(cage.error().code == subfeed::ErrorCode::bad_input);
  CHECK(cage.error().describe() == description);
}

} // namespace

TEST_CASE("a valid cage is read with its faces, lines and tags") {
  const auto cage = parse("# two quads\r\nmtllib x.mtl\n" + two_quads +
                          "t crease 2/1/0 1 4 2.5\nt corner 1/1/0 0 10\n"
                          "t interpolateboundary 1/0/0 2\n");
  REQUIRE(cage);
  CHECK(cage->vertex_count() == 6);
  CHECK(cage->face_count() == 2);
  CHECK(cage->face_lines == std::vector<int>{9, 10});
  CHECK(std::vector<int>(cage->face(1).begin(), cage->face(1).end()) ==
        std::vector<int>{1, 2, 5, 4});
  REQUIRE(cage->creases.size() == 1);
  CHECK(cage->creases[0].v0 == 1);
  CHECK(cage->creases[0].v1 == 4);
  CHECK(cage->creases[0].sharpness == 2.5);
  CHECK(cage->creases[0].line == 11);
  REQUIRE(cage->corners.size() == 1);
  CHECK(cage->corners[0].sharpness == 10.0);
  CHECK(cage->boundary == BoundaryInterpolation::edge_and_corner);
}

TEST_CASE("face vertex forms and negative indices resolve to the same vertices") {
  const auto cage = parse("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf -4/1/1 2//3 3/2 -1\n");
  REQUIRE(cage);
  CHECK(std::vector<int>(cage->face(0).begin(), cage->face(0).end()) ==
        std::vector<int>{0, 1, 2, 3});
}

TEST_CASE("n-gons and triangles are accepted") {
  const auto cage = parse("v 0 0 0\nv 2 0 0\nv 3 1 0\nv 1 2 0\nv -1 1 0\nv 1 -2 0\n"
                          "f 1 2 3 4 5\nf 1 6 2\n");
  REQUIRE(cage);
  CHECK(cage->face_sizes == std::vector<int>{5, 3});
}

TEST_CASE("malformed OBJ statements are errors naming the line") {
  expect_error("", "part.obj: no faces: not a control cage");
  expect_error("v 0 0 0\nv 1 0 0\n", "part.obj: no faces: not a control cage");
  expect_error("v 0 0\n", "part.obj:1: a vertex needs 3 coordinates (x y z), got 2");
  expect_error("v 0 0 0\nv 1 x 0\n", "part.obj:2: 'x' is not a number");
  expect_error("v 0 nan 0\n", "part.obj:1: coordinate 'nan' is not finite");
  expect_error("v 0 0 inf\n", "part.obj:1: coordinate 'inf' is not finite");
  expect_error("v 0 0 0\nv 1 0 0\nf 1 2\n", "part.obj:3: a face needs at least 3 vertices, got 2");
  expect_error("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 0 1 2\n",
               "part.obj:4: vertex index 0 is out of range (3 vertices defined so far)");
  expect_error("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 4\n",
               "part.obj:4: vertex index 4 is out of range (3 vertices defined so far)");
  expect_error("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 -4\n",
               "part.obj:4: vertex index -4 is out of range (3 vertices defined so far)");
  expect_error("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 x\n", "part.obj:4: 'x' is not an integer");
  expect_error("v 0 0 0\nl 1 2\n", "part.obj:2: unsupported OBJ statement 'l'");
}

TEST_CASE("degenerate and repeated faces are errors naming the face's line") {
  expect_error("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 2\n",
               "part.obj:4: degenerate face: a vertex appears twice");
  expect_error("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n", "part.obj:4: degenerate face: zero area");
  expect_error("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf 2 3 4 1\n",
               "part.obj:6: repeated face: same vertices as the face on line 5");
}

TEST_CASE("non-manifold and inconsistently oriented cages are errors") {
  // A third quad on the shared edge 2-5.
  expect_error(two_quads + "v 1 0 1\nv 1 1 1\nf 2 5 8 7\n",
               "part.obj:11: non-manifold edge 2-5: a third face uses it");
  // The second quad wound the other way.
  expect_error("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\nf 1 2 5 4\nf 2 5 6 3\n",
               "part.obj:8: inconsistent orientation across edge 2-5 with the face on line 7");
  // Two triangles touching only at vertex 1 (a bow tie).
  expect_error("v 0 0 0\nv 1 0 0\nv 1 1 0\nv -1 0 0\nv -1 -1 0\nf 1 2 3\nf 1 4 5\n",
               "part.obj:6: non-manifold vertex 1: faces meet there in more than one fan");
}

TEST_CASE("bad tags are errors naming the tag's line") {
  expect_error(two_quads + "t crease 2/1/0 0 2 1\n",
               "part.obj:9: crease 0-2 is not an edge of the cage");
  expect_error(two_quads + "t crease 2/1/0 0 9 1\n",
               "part.obj:9: crease vertex out of range (0-based, 6 vertices)");
  expect_error(two_quads + "t crease 2/1/0 1 4 -1\n",
               "part.obj:9: sharpness -1.000000 is negative");
  expect_error(two_quads + "t crease 3/1/0 1 4 5 1\n",
               "part.obj:9: crease needs vertex pairs and one sharpness, or one per pair");
  expect_error(two_quads + "t crease 2/1/0 1 4\n",
               "part.obj:9: tag declares 3 arguments but has 2");
  expect_error(two_quads + "t corner 1/1/0 6 1\n",
               "part.obj:9: corner vertex out of range (0-based, 6 vertices)");
  expect_error(
      two_quads + "t interpolateboundary 1/0/0 3\n",
      "part.obj:9: interpolateboundary takes one integer: 0 none, 1 edge only, 2 edge and corner");
  expect_error(two_quads + "t holes 1/0/0 0\n",
               "part.obj:9: unsupported tag 'holes' (crease, corner, hole, interpolateboundary, "
               "creasemethod, smoothtriangles, facevaryinginterpolateboundary, "
               "facevaryingpropagatecorners)");
  expect_error(two_quads + "t hole 1/0/0 2\n",
               "part.obj:9: hole face 2 out of range (0-based, 2 faces)");
  expect_error(two_quads + "t hole 0/0/0\n",
               "part.obj:9: hole needs at least one face index (0-based)");
  expect_error(two_quads + "t creasemethod 0/0/1 sharp\n",
               "part.obj:9: creasemethod takes one string: normal or chaikin");
  expect_error(two_quads + "t smoothtriangles 1/0/0 1\n",
               "part.obj:9: smoothtriangles takes one string: catmark or smooth");
  expect_error(two_quads + "t vertexedit 0/0/1 x\n",
               "part.obj:9: tag 'vertexedit' is a hierarchical edit, which OpenSubdiv 3 does not "
               "evaluate: apply it in the modeller and export the edited cage");
  expect_error(two_quads + "t hole 1/0/-1 0\n",
               "part.obj:9: tag argument count '1/0/-1' must be three non-negative integers");
  expect_error(two_quads + "t crease 2-1-0 1 4 1\n",
               "part.obj:9: tag argument count '2-1-0' is not 'nint/nfloat/nstring'");
}

TEST_CASE("a missing file is a bad-input error naming it") {
  const auto cage = subfeed::geometry::read_obj("/nonexistent/part.obj");
  REQUIRE_FALSE(cage);
  CHECK(cage.error().describe() == "/nonexistent/part.obj: cannot open cage file");
  CHECK(cage.error().code == subfeed::ErrorCode::bad_input);
}
