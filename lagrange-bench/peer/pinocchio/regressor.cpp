// Pinocchio's `computeJointTorqueRegressor` beside its `rnea` on the arms in
// `robots/`, read from the same URDF files as lagrange-bench's `regressor`
// bench, at the bench's state (see `urdf.cpp`: q_k = 0.3 − 0.17 k,
// q̇_k = 0.5 − 0.21 k, q̈_k = 0.1 + 0.05 k on the arm). Build and run with
// `regressor.sh`. The bar: Y against this regressor at least as fast as the
// library's inverse dynamics is against `rnea`, so both are timed in the same
// process. τ[0] is printed, as the bench prints it, to show the two sides
// run the same model at the same state; Y itself is checked against this
// function column by column in `tests/regressor_pinocchio.rs`.
#include <pinocchio/multibody.hpp>
#include <pinocchio/algorithm/regressor.hpp>
#include <pinocchio/algorithm/rnea.hpp>

#include <cmath>
#include <cstdio>
#include <string>

namespace pin = pinocchio;

#include URDF_MODELS

#include "timing.hpp"

int main() {
  std::printf(
      "| robot | nv | regressor (ns) | RNEA (ns) | regressor / RNEA | tau[0] |\n"
      "|---|---|---|---|---|---|\n");
  for (const Robot& robot : ROBOTS) {
    // The Panda is left out, as in `urdf_regressor.py`: Pinocchio reads its
    // mimic finger as a second joint, so the two regressors differ in shape.
    if (std::string(robot.name) == "panda") continue;
    pin::Model model = robot.build();
    pin::Data data(model);
    Eigen::VectorXd q(model.nq), v(model.nv), a(model.nv);
    for (pin::JointIndex j = 1; j < model.joints.size(); ++j) {
      const int k = model.joints[j].idx_v(), at = model.joints[j].idx_q();
      const double angle = 0.3 - 0.17 * k;
      v[k] = 0.5 - 0.21 * k;
      a[k] = 0.1 + 0.05 * k;
      if (model.joints[j].nq() == 2) {  // a continuous joint: (cos, sin)
        q[at] = std::cos(angle);
        q[at + 1] = std::sin(angle);
      } else {
        q[at] = angle;
      }
    }
    const int calls = 200000;
    const double y = ns_per_call([&] { pin::computeJointTorqueRegressor(model, data, q, v, a); }, calls);
    const double tau = ns_per_call([&] { pin::rnea(model, data, q, v, a); }, calls);
    pin::rnea(model, data, q, v, a);
    std::printf("| %s | %d | %.0f | %.0f | %.2f | %.15g |\n", robot.name, model.nv, y, tau, y / tau, data.tau[0]);
  }
  return 0;
}
