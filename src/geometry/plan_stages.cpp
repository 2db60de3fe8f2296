#include "geometry/plan_stages.hpp"

#include <numeric>

namespace subfeed::geometry {

std::string_view stage_name(PlanStage stage) {
  switch (stage) {
  case PlanStage::meshing:
    return "meshing the limit surface";
  case PlanStage::gate_mesh:
    return "meshing for the motion gate";
  case PlanStage::reach:
    return "finding what the tool reaches";
  case PlanStage::directions:
    return "pricing feed directions";
  case PlanStage::deformation:
    return "deformation solves";
  case PlanStage::clearing:
    return "clearing the ball";
  case PlanStage::slicing:
    return "slicing and linking";
  }
  return "?";
}

double PlanTimes::total_s() const {
  return std::accumulate(stage_s.begin(), stage_s.end(), 0.0);
}

} // namespace subfeed::geometry
