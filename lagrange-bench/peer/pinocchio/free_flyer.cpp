// Pinocchio's CRBA + NLE and ABA on the floating base of lagrange-bench's
// `free` bench: a hub on a free flyer with a revolute-z joint at (0.3, 0.1,
// 0.2) and a revolute-y joint 0.4 further out, at the bench's state (the
// hub's velocity in Pinocchio's convention, R^T xdot). Build and run with
// `free_flyer.sh`.
#include <pinocchio/multibody.hpp>
#include <pinocchio/algorithm/aba.hpp>
#include <pinocchio/algorithm/crba.hpp>
#include <pinocchio/algorithm/rnea.hpp>

#include <chrono>
#include <cstdio>

namespace pin = pinocchio;

#include "timing.hpp"

int main() {
  pin::Model model;
  const auto diag = [](double a, double b, double c) { return Eigen::Vector3d(a, b, c).asDiagonal().toDenseMatrix(); };
  auto hub = model.addJoint(0, pin::JointModelFreeFlyer(), pin::SE3::Identity(), "hub");
  model.appendBodyToJoint(hub, pin::Inertia(5.0, Eigen::Vector3d::Zero(), diag(0.4, 0.5, 0.6)));
  auto j1 = model.addJoint(hub, pin::JointModelRZ(), pin::SE3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.3, 0.1, 0.2)), "j1");
  model.appendBodyToJoint(j1, pin::Inertia(1.5, Eigen::Vector3d(0.2, 0, 0), diag(0.01, 0.05, 0.05)));
  auto j2 = model.addJoint(j1, pin::JointModelRY(), pin::SE3(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.4, 0, 0)), "j2");
  model.appendBodyToJoint(j2, pin::Inertia(1.0, Eigen::Vector3d(0.15, 0, 0), diag(0.005, 0.02, 0.02)));
  pin::Data data(model);
  Eigen::Quaterniond quat(0.8, 0.2, -0.4, 0.3);
  quat.normalize();
  Eigen::VectorXd q(9), v(8), tau = Eigen::VectorXd::Zero(8);
  q << 0.1, -0.2, 0.3, quat.x(), quat.y(), quat.z(), quat.w(), 0.7, -0.4;
  const Eigen::Vector3d local = quat.toRotationMatrix().transpose() * Eigen::Vector3d(0.3, -0.1, 0.2);
  v << local, 0.4, -0.6, 0.9, 0.5, -0.8;
  const int calls = 500000;
  double crba_nle = ns_per_call([&] { pin::crba(model, data, q); pin::nonLinearEffects(model, data, q, v); }, calls);
  double aba = ns_per_call([&] { pin::aba(model, data, q, v, tau); }, calls);
  std::printf("| model | nv | Pinocchio CRBA + NLE (ns) | Pinocchio ABA (ns) |\n|---|---|---|---|\n");
  std::printf("| floating arm | %d | %.0f | %.0f |\n", model.nv, crba_nle, aba);
  return 0;
}
