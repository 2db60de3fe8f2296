#pragma once
// Three linear axes: joints are the tool tip, and the tool axis is always +Z.

#include "post/kinematics.hpp"

namespace subfeed::post {

class XyzKinematics final : public Kinematics {
public:
  [[nodiscard]] std::vector<JointPosition> inverse(const ToolPose& pose,
                                                   const JointPosition& near) const override;
  [[nodiscard]] ToolPose forward(const JointPosition& joints) const override;
};

} // namespace subfeed::post
