#include "post/kinematics.hpp"

#include "xyz_kinematics.hpp"
#include "xyzac_trt_kinematics.hpp"

namespace subfeed::post {

std::unique_ptr<Kinematics> make_kinematics(const MachineConfig& machine) {
  switch (machine.kinematics) {
  case KinematicsType::xyzac_trt:
    return std::make_unique<XyzacTrtKinematics>(*machine.table_table);
  case KinematicsType::xyz:
    break;
  }
  return std::make_unique<XyzKinematics>();
}

} // namespace subfeed::post
