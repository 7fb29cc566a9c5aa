// Pinocchio's computeABADerivatives (and ABA beside it) on the UR5 of robots/,
// as Pinocchio's URDF parser reads it (written out as C++ by urdf_model.py:
// the wheel has no urdfdom headers), at the state of the `derivatives`
// bench: q_k = 0.3 - 0.17 k, qdot_k = 0.5 - 0.21 k, tau = 0. Build and run
// with `derivatives.sh`.
#include <pinocchio/multibody.hpp>
#include <pinocchio/algorithm/aba.hpp>
#include <pinocchio/algorithm/aba-derivatives.hpp>

#include <chrono>
#include <cstdio>
#include <string>

namespace pin = pinocchio;

#include URDF_MODELS

#include "timing.hpp"

int main() {
  const pin::Model model = ur5();
  pin::Data data(model);
  Eigen::VectorXd q(model.nq), v(model.nv), tau = Eigen::VectorXd::Zero(model.nv);
  for (int k = 0; k < model.nq; ++k) q[k] = 0.3 - 0.17 * k;
  for (int k = 0; k < model.nv; ++k) v[k] = 0.5 - 0.21 * k;
  const int calls = 200000;
  const double aba = ns_per_call([&] { pin::aba(model, data, q, v, tau); }, calls);
  const double derivatives = ns_per_call([&] { pin::computeABADerivatives(model, data, q, v, tau); }, calls);
  std::printf("| robot | nv | ABA (ns) | computeABADerivatives (ns) |\n|---|---|---|---|\n");
  std::printf("| ur5 | %d | %.0f | %.0f |\n", model.nv, aba, derivatives);
  return 0;
}
