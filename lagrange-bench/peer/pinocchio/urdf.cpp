// Pinocchio's CRBA + NLE, ABA, RNEA, the tool frame's Jacobian and the centre
// of mass Jacobian on the robots in `robots/` read from the same URDF files as
// lagrange-bench's `urdf` bench. Build and run with `urdf.sh`:
// `urdf_model.py` writes the models Pinocchio's own URDF parser reads (the
// PyPI wheel ships the parser's library but not urdfdom's headers) as C++.
// The state is the bench's: q_k = 0.3 − 0.17 k, q̇_k = 0.5 − 0.21 k (the
// Panda's two fingers, which Pinocchio reads as two joints where the URDF
// makes the second mimic the first, at 0.02 and at rest; a continuous joint's
// angle is written as its cosine and sine).
#include <pinocchio/multibody.hpp>
#include <pinocchio/algorithm/aba.hpp>
#include <pinocchio/algorithm/center-of-mass.hpp>
#include <pinocchio/algorithm/crba.hpp>
#include <pinocchio/algorithm/frames.hpp>
#include <pinocchio/algorithm/rnea.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

namespace pin = pinocchio;

#include URDF_MODELS

#include "timing.hpp"

// The bench's state, by velocity index: q_k = 0.3 − 0.17 k, q̇_k = 0.5 − 0.21 k
// on the arm's `arm` coordinates, the rest (fingers) at 0.02 and at rest.
static void state(const pin::Model& model, int arm, Eigen::VectorXd& q, Eigen::VectorXd& v) {
  q.resize(model.nq);
  v.resize(model.nv);
  for (pin::JointIndex j = 1; j < model.joints.size(); ++j) {
    const int k = model.joints[j].idx_v(), at = model.joints[j].idx_q();
    const double angle = k < arm ? 0.3 - 0.17 * k : 0.02;
    v[k] = k < arm ? 0.5 - 0.21 * k : 0.0;
    if (model.joints[j].nq() == 2) {
      q[at] = std::cos(angle);
      q[at + 1] = std::sin(angle);
    } else {
      q[at] = angle;
    }
  }
}

int main() {
  std::printf(
      "| robot | nq / nv | CRBA + NLE (ns) | ABA (ns) | RNEA (ns) | frame Jacobian (ns) | CoM Jacobian (ns) | "
      "M[0][0] | (Q - h)[0] | J[0][0] | Jcom[0][0] |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Robot& robot : ROBOTS) {
    pin::Model model = robot.build();
    pin::Data data(model);
    Eigen::VectorXd q, v, tau = Eigen::VectorXd::Zero(model.nv);
    state(model, robot.arm, q, v);
    const int calls = 200000;
    double crba_nle = ns_per_call(
        [&] {
          pin::crba(model, data, q);
          pin::nonLinearEffects(model, data, q, v);
        },
        calls);
    double aba = ns_per_call([&] { pin::aba(model, data, q, v, tau); }, calls);
    Eigen::VectorXd a(model.nv);
    for (int k = 0; k < model.nv; ++k) a[k] = k < robot.arm ? 0.1 + 0.05 * k : 0.0;
    double rnea = ns_per_call([&] { pin::rnea(model, data, q, v, a); }, calls);
    const pin::FrameIndex tool = model.getFrameId(robot.tool);
    pin::Data::Matrix6x J = pin::Data::Matrix6x::Zero(6, model.nv);
    double frame = ns_per_call(
        [&] { pin::computeFrameJacobian(model, data, q, tool, pin::LOCAL_WORLD_ALIGNED, J); }, calls);
    double com = ns_per_call([&] { pin::jacobianCenterOfMass(model, data, q); }, calls);
    pin::crba(model, data, q);
    pin::nonLinearEffects(model, data, q, v);
    pin::computeFrameJacobian(model, data, q, tool, pin::LOCAL_WORLD_ALIGNED, J);
    const double jcom = pin::jacobianCenterOfMass(model, data, q)(0, 0);
    std::printf("| %s | %d / %d | %.0f | %.0f | %.0f | %.0f | %.0f | %.15g | %.15g | %.15g | %.15g |\n", robot.name,
                model.nq, model.nv, crba_nle, aba, rnea, frame, com, data.M(0, 0), -data.nle[0], J(0, 0), jcom);
  }
  return 0;
}
