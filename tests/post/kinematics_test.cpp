#include "post/kinematics.hpp"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <random>

using namespace subfeed::post;

namespace {

constexpr double deg = std::numbers::pi / 180.0;

MachineConfig trt(int p, int q, std::array<double, 3> pivot = {10, -20, -150}, double dy = 3.5,
                  double dz = 120.0, double tool = 0.0) {
  MachineConfig m;
  m.kinematics = KinematicsType::xyzac_trt;
  m.rotary = RotaryGeometry{.pivot = pivot,
                            .y_offset = dy,
                            .z_offset = dz,
                            .tool_length = tool,
                            .tilt_direction = p,
                            .c_direction = q};
  return m;
}

ToolPose random_pose(std::mt19937& rng, double max_tilt_deg = 120.0) {
  std::uniform_real_distribution<double> coordinate(-500.0, 500.0);
  std::uniform_real_distribution<double> tilt(0.0, max_tilt_deg * deg);
  std::uniform_real_distribution<double> turn(-std::numbers::pi, std::numbers::pi);
  const double a = tilt(rng), c = turn(rng);
  return {{coordinate(rng), coordinate(rng), coordinate(rng)},
          {std::sin(a) * std::cos(c), std::sin(a) * std::sin(c), std::cos(a)}};
}

double distance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

// docs/PROTOCOLS.md's xyzac-trt "joints from work position", typed in as written (one sign s).
std::array<double, 3> protocols_joints(const ToolPose& pose, double a_deg, double c_deg, double s,
                                       const RotaryGeometry& g) {
  const double cA = std::cos(a_deg * deg), sA = std::sin(a_deg * deg);
  const double cC = std::cos(c_deg * deg), sC = std::sin(c_deg * deg);
  const double Qx = pose.tip[0] - g.pivot[0], Qy = pose.tip[1] - g.pivot[1],
               Qz = pose.tip[2] - g.pivot[2];
  const double Dy = g.y_offset, Dz = g.z_offset + g.tool_length;
  const double xr = g.pivot[0], yr = g.pivot[1], zr = g.pivot[2];
  return {cC * Qx + s * sC * Qy + xr,
          -s * sC * cA * Qx + cC * cA * Qy + s * sA * Qz - cA * Dy - s * sA * Dz + Dy + yr,
          sC * sA * Qx - s * cC * sA * Qy + cA * Qz + s * sA * Dy - cA * Dz + Dz + zr};
}

} // namespace

TEST_CASE("joints agree with LinuxCNC's xyzac-trt formulas for both of its conventions") {
  std::mt19937 rng(1);
  for (const int s : {1, -1}) {
    const auto machine = trt(s, s);
    const auto kinematics = make_kinematics(machine);
    double worst = 0.0;
    for (int i = 0; i < 2000; ++i) {
      const ToolPose pose = random_pose(rng);
      for (const auto& j : kinematics->inverse(pose, {})) {
        const auto expected = protocols_joints(pose, j[3], j[5], s, *machine.rotary);
        worst = std::max(worst, distance({j[0], j[1], j[2]}, expected));
      }
    }
    CHECK(worst < 1e-9);
  }
}

TEST_CASE("the tool axis lands on the fixed spindle and the tip where the table carries it") {
  // An independent model with Eigen's rotations: machine = Rx(-p A) (Rz(-q C) Q - D) + D + pivot.
  std::mt19937 rng(2);
  for (const int p : {1, -1}) {
    for (const int q : {1, -1}) {
      const auto machine = trt(p, q);
      const auto& g = *machine.rotary;
      const auto kinematics = make_kinematics(machine);
      for (int i = 0; i < 500; ++i) {
        const ToolPose pose = random_pose(rng);
        for (const auto& j : kinematics->inverse(pose, {})) {
          const Eigen::Matrix3d table =
              (Eigen::AngleAxisd(-p * j[3] * deg, Eigen::Vector3d::UnitX()) *
               Eigen::AngleAxisd(-q * j[5] * deg, Eigen::Vector3d::UnitZ()))
                  .toRotationMatrix();
          const Eigen::Vector3d axis(pose.axis[0], pose.axis[1], pose.axis[2]);
          CHECK((table * axis - Eigen::Vector3d::UnitZ()).norm() < 1e-12);
          const Eigen::Vector3d pivot(g.pivot[0], g.pivot[1], g.pivot[2]);
          const Eigen::Vector3d d(0, g.y_offset, g.z_offset);
          const Eigen::Vector3d tip(pose.tip[0], pose.tip[1], pose.tip[2]);
          const Eigen::Vector3d expected =
              Eigen::AngleAxisd(-p * j[3] * deg, Eigen::Vector3d::UnitX()) *
                  (Eigen::AngleAxisd(-q * j[5] * deg, Eigen::Vector3d::UnitZ()) * (tip - pivot) -
                   d) +
              d + pivot;
          CHECK((Eigen::Vector3d(j[0], j[1], j[2]) - expected).norm() < 1e-9);
        }
      }
    }
  }
}

namespace {

// Offsets and tool length all non-zero, so every term of the formulas is exercised.
MachineConfig ac_trt(int p, int q) {
  return trt(p, q, {37.5, -12.25, -150.0}, -4.0, 95.0, 42.0);
}

MachineConfig bc_trt(int p, int q) {
  MachineConfig m;
  m.kinematics = KinematicsType::xyzbc_trt;
  m.rotary = RotaryGeometry{.pivot = {-15, 25, -140},
                            .x_offset = 6.5,
                            .z_offset = 110.0,
                            .tool_length = 33.0,
                            .tilt_direction = p,
                            .c_direction = q};
  return m;
}

MachineConfig ac_head(int p, int q) {
  MachineConfig m;
  m.kinematics = KinematicsType::xyzac_head;
  m.rotary = RotaryGeometry{
      .pivot_length = 150.0, .tool_length = 60.0, .tilt_direction = p, .c_direction = q};
  return m;
}

} // namespace

TEST_CASE("forward after inverse returns the pose over the whole work volume: every type, every "
          "convention") {
  std::mt19937 rng(3);
  for (const auto make : {ac_trt, bc_trt, ac_head}) {
    for (const int p : {1, -1}) {
      for (const int q : {1, -1}) {
        const auto kinematics = make_kinematics(make(p, q));
        double worst_tip = 0.0, worst_axis = 0.0;
        for (int i = 0; i < 5000; ++i) {
          const ToolPose pose = random_pose(rng, 179.0);
          const auto solutions = kinematics->inverse(pose, {});
          REQUIRE(solutions.size() == 2);
          for (const auto& j : solutions) {
            const ToolPose back = kinematics->forward(j);
            worst_tip = std::max(worst_tip, distance(back.tip, pose.tip));
            worst_axis = std::max(worst_axis, distance(back.axis, pose.axis));
          }
        }
        CHECK(worst_tip < 1e-9);
        CHECK(worst_axis < 1e-12);
      }
    }
  }
}

TEST_CASE("the two solutions are (A, C) and (-A, C + 180)") {
  const auto kinematics = make_kinematics(trt(1, 1));
  const ToolPose pose{{1, 2, 3},
                      {std::sin(30 * deg) * std::cos(40 * deg),
                       std::sin(30 * deg) * std::sin(40 * deg), std::cos(30 * deg)}};
  const auto solutions = kinematics->inverse(pose, {});
  REQUIRE(solutions.size() == 2);
  CHECK(solutions[0][3] == Approx(30.0));
  CHECK(solutions[1][3] == Approx(-30.0));
  CHECK(std::remainder(solutions[1][5] - solutions[0][5] - 180.0, 360.0) ==
        Approx(0.0).margin(1e-9));
  CHECK(solutions[1][5] > -180.0);
  CHECK(solutions[1][5] <= 180.0);
}

TEST_CASE("standard signs: A = 90, C = 0 points the tool along -Y of the work") {
  // With +1 the tool moves relative to the work by the right-hand rule about +X: tilting it
  // from +Z by +90 deg about X brings it to -Y.
  const auto forward = make_kinematics(trt(1, 1))->forward({0, 0, 0, 90, 0, 0});
  CHECK(forward.axis[0] == Approx(0.0).margin(1e-15));
  CHECK(forward.axis[1] == Approx(-1.0));
  CHECK(forward.axis[2] == Approx(0.0).margin(1e-15));
  const auto linuxcnc = make_kinematics(trt(-1, -1))->forward({0, 0, 0, 90, 0, 0});
  CHECK(linuxcnc.axis[1] == Approx(1.0));
}

TEST_CASE("at the pole C is free and keeps its value") {
  const auto kinematics = make_kinematics(trt(1, 1));
  const ToolPose pose{{5, 6, 7}, {0, 0, 1}};
  const auto solutions = kinematics->inverse(pose, {0, 0, 0, 0, 0, 123.0});
  REQUIRE(solutions.size() == 1);
  CHECK(solutions[0][3] == 0.0);
  CHECK(solutions[0][5] == 123.0);
  CHECK(distance(kinematics->forward(solutions[0]).tip, pose.tip) < 1e-12);
}

TEST_CASE("tool length adds to the z offset") {
  const auto with_tool = make_kinematics(trt(1, 1, {0, 0, 0}, 0, 100, 25));
  const auto longer = make_kinematics(trt(1, 1, {0, 0, 0}, 0, 125, 0));
  const ToolPose pose{{10, 20, 30}, {0.6, 0.0, 0.8}};
  const auto a = with_tool->inverse(pose, {});
  const auto b = longer->inverse(pose, {});
  CHECK(distance({a[0][0], a[0][1], a[0][2]}, {b[0][0], b[0][1], b[0][2]}) < 1e-12);
}

TEST_CASE("a 3-axis machine reaches vertical tools only") {
  MachineConfig m;
  const auto kinematics = make_kinematics(m);
  const auto vertical = kinematics->inverse({{1, 2, 3}, {0, 0, 1}}, {});
  REQUIRE(vertical.size() == 1);
  CHECK(vertical[0] == JointPosition{1, 2, 3, 0, 0, 0});
  CHECK(kinematics->inverse({{1, 2, 3}, {0.1, 0, 0.995}}, {}).empty());
  CHECK(kinematics->inverse({{1, 2, 3}, {0, 0, -1}}, {}).empty());
  CHECK(kinematics->forward({4, 5, 6, 0, 0, 0}).tip == std::array<double, 3>{4, 5, 6});
}

TEST_CASE("the shipped A/C configs give working kinematics") {
  for (const char* name : {"/configs/grblhal-xyzac-trt.toml", "/configs/fanuc-xyzac-trt.toml"}) {
    const auto config = load_machine_config(std::string(SUBFEED_SOURCE_DIR) + name);
    REQUIRE(config);
    const auto kinematics = make_kinematics(*config);
    const ToolPose pose{{12, -7, 4}, {0.0, -0.6, 0.8}};
    for (const auto& j : kinematics->inverse(pose, {})) {
      CHECK(distance(kinematics->forward(j).tip, pose.tip) < 1e-9);
    }
  }
}

TEST_CASE("xyzbc-trt: the tool axis lands on the spindle and the tip where the table carries it") {
  // machine = Ry(-p B) (Rz(-q C) Q - D) + D + pivot, D = (Dx, 0, Dz + tool length).
  std::mt19937 rng(5);
  for (const int p : {1, -1}) {
    for (const int q : {1, -1}) {
      const auto machine = bc_trt(p, q);
      const auto& g = *machine.rotary;
      const auto kinematics = make_kinematics(machine);
      for (int i = 0; i < 500; ++i) {
        const ToolPose pose = random_pose(rng);
        for (const auto& j : kinematics->inverse(pose, {})) {
          const Eigen::Matrix3d rb(Eigen::AngleAxisd(-p * j[4] * deg, Eigen::Vector3d::UnitY()));
          const Eigen::Matrix3d rc(Eigen::AngleAxisd(-q * j[5] * deg, Eigen::Vector3d::UnitZ()));
          const Eigen::Vector3d axis(pose.axis[0], pose.axis[1], pose.axis[2]);
          CHECK((rb * rc * axis - Eigen::Vector3d::UnitZ()).norm() < 1e-12);
          const Eigen::Vector3d pivot(g.pivot[0], g.pivot[1], g.pivot[2]);
          const Eigen::Vector3d d(g.x_offset, 0, g.z_offset + g.tool_length);
          const Eigen::Vector3d tip(pose.tip[0], pose.tip[1], pose.tip[2]);
          const Eigen::Vector3d expected = rb * (rc * (tip - pivot) - d) + d + pivot;
          CHECK((Eigen::Vector3d(j[0], j[1], j[2]) - expected).norm() < 1e-9);
          CHECK(j[3] == 0.0);
        }
      }
    }
  }
}

TEST_CASE("xyzac-head: the pivot sits the pivot and tool lengths up the tool axis") {
  std::mt19937 rng(6);
  for (const int p : {1, -1}) {
    for (const int q : {1, -1}) {
      const auto kinematics = make_kinematics(ac_head(p, q));
      for (int i = 0; i < 500; ++i) {
        const ToolPose pose = random_pose(rng);
        for (const auto& j : kinematics->inverse(pose, {})) {
          // The head turns the spindle direction (0, 0, 1) by Rz(q C) Rx(p A).
          const Eigen::Vector3d spindle =
              Eigen::AngleAxisd(q * j[5] * deg, Eigen::Vector3d::UnitZ()) *
              (Eigen::AngleAxisd(p * j[3] * deg, Eigen::Vector3d::UnitX()) *
               Eigen::Vector3d::UnitZ());
          const Eigen::Vector3d axis(pose.axis[0], pose.axis[1], pose.axis[2]);
          CHECK((spindle - axis).norm() < 1e-12);
          const Eigen::Vector3d tip(pose.tip[0], pose.tip[1], pose.tip[2]);
          CHECK((Eigen::Vector3d(j[0], j[1], j[2]) - (tip + 210.0 * axis)).norm() < 1e-9);
        }
      }
    }
  }
}
