// Pinocchio's CRBA + NLE and ABA on issue 10's spatial chain, the peer of
// lagrange-bench's `spatial` bench. Build and run with `run.sh` beside this file.
//
// n rods; rod k (k = 0 … n−1): mass 1 + 0.1k, length 1 − 0.02k, along its body
// x axis from its joint, centre of mass at l/2, slender cylinder of radius 0.05;
// joint k+1 at the tip of rod k; joint axes alternate z, y; gravity −9.81 z.
#include <pinocchio/multibody.hpp>
#include <pinocchio/algorithm/aba.hpp>
#include <pinocchio/algorithm/crba.hpp>
#include <pinocchio/algorithm/rnea.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>

namespace pin = pinocchio;

static pin::Model chain(int n) {
  pin::Model model;
  pin::JointIndex parent = 0;
  double previous_length = 0.0;
  for (int k = 0; k < n; ++k) {
    const double m = 1.0 + 0.1 * k, l = 1.0 - 0.02 * k, r = 0.05;
    pin::SE3 placement = pin::SE3::Identity();
    if (k > 0) placement.translation() << previous_length, 0.0, 0.0;
    pin::JointIndex j = (k % 2 == 0)
        ? model.addJoint(parent, pin::JointModelRZ(), placement, "j" + std::to_string(k))
        : model.addJoint(parent, pin::JointModelRY(), placement, "j" + std::to_string(k));
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
    inertia(0, 0) = m * r * r / 2.0;
    inertia(1, 1) = inertia(2, 2) = m * (3.0 * r * r + l * l) / 12.0;
    model.appendBodyToJoint(j, pin::Inertia(m, Eigen::Vector3d(l / 2.0, 0.0, 0.0), inertia));
    parent = j;
    previous_length = l;
  }
  return model;
}

#include "timing.hpp"

int main(int argc, char** argv) {
  std::printf("| n | Pinocchio CRBA + NLE (ns) | Pinocchio ABA (ns) | M[0][0] | (Q - h)[0] |\n");
  std::printf("|---|---|---|---|---|\n");
  for (int a = 1; a < argc; ++a) {
    const int n = std::atoi(argv[a]);
    pin::Model model = chain(n);
    pin::Data data(model);
    // The state the Rust bench uses: q_i = 0.3 + 0.01 i, v_i = 0.2 − 0.01 i.
    Eigen::VectorXd q(n), v(n), tau = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < n; ++i) {
      q[i] = 0.3 + 0.01 * i;
      v[i] = 0.2 - 0.01 * i;
    }
    const int calls = 200000 / n;
    double crba_nle = ns_per_call(
        [&] {
          pin::crba(model, data, q);
          pin::nonLinearEffects(model, data, q, v);
        },
        calls);
    double aba = ns_per_call([&] { pin::aba(model, data, q, v, tau); }, calls);
    pin::crba(model, data, q);
    data.M.triangularView<Eigen::StrictlyLower>() = data.M.transpose().triangularView<Eigen::StrictlyLower>();
    pin::nonLinearEffects(model, data, q, v);
    std::printf("| %d | %.0f | %.0f | %.15g | %.15g |\n", n, crba_nle, aba, data.M(0, 0), -data.nle[0]);
  }
  return 0;
}
