// Pinocchio's computeABADerivatives (and ABA beside it) on the arms of
// robots/ (not the Panda, whose mimic finger Pinocchio reads as a second
// joint) and Solo 12 on a free flyer, as Pinocchio's URDF parser reads them
// (written out as C++ by urdf_model.py: the wheel has no urdfdom headers),
// at the state of the `derivatives` bench (`time_robot`). Build and run
// with `derivatives.sh`.
#include <pinocchio/multibody.hpp>
#include <pinocchio/algorithm/aba.hpp>
#include <pinocchio/algorithm/aba-derivatives.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

namespace pin = pinocchio;

#include URDF_MODELS

#include "timing.hpp"

/// Times ABA and computeABADerivatives at the bench's state: joint angles
/// 0.3 - 0.17 k over the joints' velocities k (a continuous joint's q is
/// their cos and sin), a free flyer's root at (0.1, -0.2, 0.3) turned by the
/// unit quaternion of (0.1, -0.15, 0.25, 0.95) (x, y, z, w), as
/// casadi_codegen.py's; qdot_k = 0.5 - 0.21 k, tau = 0.
static void time_robot(const Robot& robot) {
  const pin::Model model = robot.build();
  pin::Data data(model);
  Eigen::VectorXd q(model.nq), v(model.nv), tau = Eigen::VectorXd::Zero(model.nv);
  for (pin::JointIndex j = 1; j < (pin::JointIndex)model.njoints; ++j) {
    const auto& joint = model.joints[j];
    const double angle = 0.3 - 0.17 * joint.idx_v();
    if (joint.nq() == 7) {
      const Eigen::Vector4d quaternion = Eigen::Vector4d(0.1, -0.15, 0.25, 0.95).normalized();
      q.segment<3>(joint.idx_q()) << 0.1, -0.2, 0.3;
      q.segment<4>(joint.idx_q() + 3) = quaternion;
    } else if (joint.nq() == 2) {
      q[joint.idx_q()] = std::cos(angle);
      q[joint.idx_q() + 1] = std::sin(angle);
    } else {
      q[joint.idx_q()] = angle;
    }
  }
  for (int k = 0; k < model.nv; ++k) v[k] = 0.5 - 0.21 * k;
  const int calls = 200000;
  const double aba = ns_per_call([&] { pin::aba(model, data, q, v, tau); }, calls);
  const double derivatives =
      ns_per_call([&] { pin::computeABADerivatives(model, data, q, v, tau); }, calls);
  std::printf("| %s | %d | %.0f | %.0f |\n", robot.name, model.nv, aba, derivatives);
}

int main() {
  std::printf("| robot | nv | ABA (ns) | computeABADerivatives (ns) |\n|---|---|---|---|\n");
  for (const Robot& robot : ROBOTS) {
    if (std::string(robot.name) != "panda") time_robot(robot);
  }
  for (const Robot& robot : FLOATING) time_robot(robot);
  return 0;
}
