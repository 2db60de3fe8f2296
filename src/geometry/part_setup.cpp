#include "geometry/part_setup.hpp"

#include "base/number_text.hpp"
#include "geometry/limit_surface.hpp"
#include "geometry/obj_reader.hpp"
#include "geometry/surface_summary.hpp"

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <utility>

namespace subfeed::geometry {

namespace {

struct UpName {
  UpAxis up;
  std::string_view word;
};
constexpr std::array<UpName, 6> up_names{{{UpAxis::x, "x"},
                                          {UpAxis::y, "y"},
                                          {UpAxis::z, "z"},
                                          {UpAxis::neg_x, "-x"},
                                          {UpAxis::neg_y, "-y"},
                                          {UpAxis::neg_z, "-z"}}};

struct UnitName {
  std::string_view word;
  double mm;
};
constexpr std::array<UnitName, 4> unit_names{
    {{"mm", 1.0}, {"cm", 10.0}, {"m", 1000.0}, {"in", 25.4}}};

struct OriginName {
  OriginKind kind;
  std::string_view word;
  std::string_view phrase;
};
constexpr std::array<OriginName, 4> origin_names{
    {{OriginKind::model, "model", "the model's zero"},
     {OriginKind::top_centre, "top-centre", "the top centre"},
     {OriginKind::bottom_centre, "bottom-centre", "the bottom centre"},
     {OriginKind::min_corner, "min-corner", "the lowest corner"}}};

std::string_view up_word(UpAxis up) {
  for (const auto& n : up_names) {
    if (n.up == up) {
      return n.word;
    }
  }
  return "z";
}

// A proper rotation (determinant +1, so face loops keep their winding) taking the model's
// `up` direction to +Z.
Eigen::Matrix3d up_rotation(UpAxis up) {
  Eigen::Matrix3d r;
  switch (up) {
  case UpAxis::x: // about Y by -90 degrees: +X to +Z
    r << 0, 0, -1, 0, 1, 0, 1, 0, 0;
    break;
  case UpAxis::y: // about X by +90 degrees: +Y to +Z
    r << 1, 0, 0, 0, 0, -1, 0, 1, 0;
    break;
  case UpAxis::z:
    r.setIdentity();
    break;
  case UpAxis::neg_x: // about Y by +90 degrees: -X to +Z
    r << 0, 0, 1, 0, 1, 0, -1, 0, 0;
    break;
  case UpAxis::neg_y: // about X by -90 degrees: -Y to +Z
    r << 1, 0, 0, 0, 0, 1, 0, -1, 0;
    break;
  case UpAxis::neg_z: // about X by 180 degrees
    r << 1, 0, 0, 0, -1, 0, 0, 0, -1;
    break;
  }
  return r;
}

std::unexpected<Error> bad(std::string message) {
  return fail(ErrorCode::bad_input, std::move(message));
}

Expected<Eigen::Vector3d> parse_point(std::string_view word) {
  Eigen::Vector3d p;
  std::string_view rest = word;
  for (int i = 0; i < 3; ++i) {
    const auto comma = rest.find(',');
    const auto part = rest.substr(0, comma);
    const auto value = parse_double(part);
    if (!value || (i < 2) == (comma == std::string_view::npos)) {
      return bad(fmt::format("origin '{}' is not top-centre, bottom-centre, min-corner, model "
                             "or X,Y,Z in mm",
                             word));
    }
    p[i] = *value;
    rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
  }
  return p;
}

std::string origin_word(const PartSetup& s) {
  if (s.origin == OriginKind::point) {
    return fmt::format("{},{},{}", s.origin_point.x(), s.origin_point.y(), s.origin_point.z());
  }
  for (const auto& n : origin_names) {
    if (n.kind == s.origin) {
      return std::string(n.word);
    }
  }
  return "model";
}

Eigen::Vector3d zero_for(const PartSetup& s, const Eigen::Vector3d& min,
                         const Eigen::Vector3d& max) {
  const Eigen::Vector3d centre = (min + max) / 2;
  switch (s.origin) {
  case OriginKind::model:
    return Eigen::Vector3d::Zero();
  case OriginKind::top_centre:
    return {centre.x(), centre.y(), max.z()};
  case OriginKind::bottom_centre:
    return {centre.x(), centre.y(), min.z()};
  case OriginKind::min_corner:
    return min;
  case OriginKind::point:
    return s.origin_point;
  }
  return Eigen::Vector3d::Zero();
}

} // namespace

Expected<UpAxis> parse_up_axis(std::string_view word) {
  for (const auto& n : up_names) {
    if (n.word == word) {
      return n.up;
    }
  }
  return bad(fmt::format("up axis '{}' is not x, y, z, -x, -y or -z", word));
}

Expected<double> parse_units(std::string_view word) {
  for (const auto& n : unit_names) {
    if (n.word == word) {
      return n.mm;
    }
  }
  return bad(fmt::format("units '{}' are not mm, cm, m or in", word));
}

Expected<void> parse_origin(std::string_view word, PartSetup& setup) {
  for (const auto& n : origin_names) {
    if (n.word == word) {
      setup.origin = n.kind;
      setup.origin_point.setZero();
      return {};
    }
  }
  SUBFEED_TRY_ASSIGN(setup.origin_point, parse_point(word));
  setup.origin = OriginKind::point;
  return {};
}

std::string setup_text(const PartSetup& s) {
  return fmt::format("up={} scale={} origin={}", up_word(s.up), s.scale, origin_word(s));
}

Expected<PartSetup> parse_setup_text(std::string_view text) {
  PartSetup s;
  bool seen_up = false, seen_scale = false, seen_origin = false;
  while (!text.empty()) {
    const auto end = std::min(text.find(' '), text.size());
    const auto field = text.substr(0, end);
    text = end < text.size() ? text.substr(end + 1) : std::string_view{};
    if (field.empty()) {
      continue;
    }
    const auto eq = field.find('=');
    const auto key = field.substr(0, eq);
    const auto value = eq == std::string_view::npos ? std::string_view{} : field.substr(eq + 1);
    if (key == "up" && !seen_up) {
      SUBFEED_TRY_ASSIGN(s.up, parse_up_axis(value));
      seen_up = true;
    } else if (key == "scale" && !seen_scale) {
      const auto scale = parse_double(value);
      if (!scale || !(*scale > 0.0)) {
        return bad(fmt::format("setup scale '{}' is not a number above 0", value));
      }
      s.scale = *scale;
      seen_scale = true;
    } else if (key == "origin" && !seen_origin) {
      SUBFEED_TRY(parse_origin(value, s));
      seen_origin = true;
    } else {
      return bad(fmt::format("setup field '{}' is not up=, scale= or origin= (each once)", field));
    }
  }
  if (!seen_up || !seen_scale || !seen_origin) {
    return bad("setup needs up=, scale= and origin=");
  }
  return s;
}

std::string describe_setup(const PartSetup& s) {
  std::string origin;
  if (s.origin == OriginKind::point) {
    origin = fmt::format("the model point {}", origin_word(s));
  } else {
    for (const auto& n : origin_names) {
      if (n.kind == s.origin) {
        origin = n.phrase;
      }
    }
  }
  return fmt::format("up {}, {} mm per model unit, zero at {}", up_word(s.up), s.scale, origin);
}

Expected<SetupResult> set_up_part(Cage& cage, const PartSetup& setup) {
  if (!(setup.scale > 0.0) || !std::isfinite(setup.scale)) {
    return fail(ErrorCode::bad_input, fmt::format("scale {} is not a number above 0", setup.scale),
                {cage.source, 0, {}});
  }
  const Eigen::Matrix3d turn = up_rotation(setup.up) * setup.scale;
  for (auto& p : cage.positions) {
    p = turn * p;
  }
  SetupResult result;
  if (setup.origin == OriginKind::model || setup.origin == OriginKind::point) {
    result.zero_in_model = zero_for(setup, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  } else { // the extent is the limit surface's, which lies inside the cage's hull
    SUBFEED_TRY_ASSIGN(const auto surface, LimitSurface::build(cage));
    SUBFEED_TRY_ASSIGN(const auto summary, summarize(cage, surface));
    result.zero_in_model = zero_for(setup, summary.min, summary.max);
  }
  for (auto& p : cage.positions) {
    p -= result.zero_in_model;
  }
  return result;
}

Expected<Cage> read_part(const std::filesystem::path& path, const PartSetup& setup) {
  SUBFEED_TRY_ASSIGN(auto cage, read_obj(path));
  SUBFEED_TRY(set_up_part(cage, setup));
  return cage;
}

} // namespace subfeed::geometry
