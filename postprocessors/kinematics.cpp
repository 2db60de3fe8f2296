#include "post/kinematics.hpp"

#include "xyz_kinematics.hpp"
#include "xyzac_head_kinematics.hpp"
#include "xyzac_trt_kinematics.hpp"
#include "xyzbc_trt_kinematics.hpp"

namespace subfeed::post {

std::unique_ptr<Kinematics> make_kinematics(const MachineConfig& machine) {
  switch (machine.kinematics) {
  case KinematicsType::xyzac_trt:
    return std::make_unique<XyzacTrtKinematics>(*machine.rotary);
  case KinematicsType::xyzbc_trt:
    return std::make_unique<XyzbcTrtKinematics>(*machine.rotary);
  case KinematicsType::xyzac_head:
    return std::make_unique<XyzacHeadKinematics>(*machine.rotary);
  case KinematicsType::xyz:
    break;
  }
  return std::make_unique<XyzKinematics>();
}

} // namespace subfeed::post
