// Pinocchio's CRBA + NLE, ABA, RNEA and computeABADerivatives on the
// floating-base trees of lagrange-bench's `free` bench (the quadruped and the
// satellite of examples/catalog/floating.rs, the models of floating.py), at
// state 0 of tests/data/floating_pinocchio.txt, which both sides read.
// Build and run with `free_flyer.sh`.
#include <pinocchio/multibody.hpp>
#include <pinocchio/algorithm/aba.hpp>
#include <pinocchio/algorithm/aba-derivatives.hpp>
#include <pinocchio/algorithm/crba.hpp>
#include <pinocchio/algorithm/rnea.hpp>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace pin = pinocchio;

#include "timing.hpp"

static Eigen::Matrix3d diag(double a, double b, double c) { return Eigen::Vector3d(a, b, c).asDiagonal().toDenseMatrix(); }

static pin::JointIndex add(pin::Model& m, pin::JointIndex parent, const pin::JointModel& joint, const Eigen::Matrix3d& rot,
                           Eigen::Vector3d offset, const char* name, double mass, Eigen::Vector3d com, Eigen::Matrix3d inertia) {
  auto j = m.addJoint(parent, joint, pin::SE3(rot, offset), name);
  m.appendBodyToJoint(j, pin::Inertia(mass, com, inertia));
  return j;
}

static pin::Model quadruped() {
  pin::Model m;
  auto root = m.addJoint(0, pin::JointModelFreeFlyer(), pin::SE3::Identity(), "trunk");
  m.appendBodyToJoint(root, pin::Inertia(12.0, Eigen::Vector3d::Zero(), diag(0.12, 0.35, 0.40)));
  const Eigen::Matrix3d eye = Eigen::Matrix3d::Identity();
  const double legs[4][2] = {{0.25, 0.12}, {0.25, -0.12}, {-0.25, 0.12}, {-0.25, -0.12}};
  for (auto& l : legs) {
    const double side = l[1] > 0 ? 0.03 : -0.03;
    auto a = add(m, root, pin::JointModelRX(), eye, {l[0], l[1], 0}, "a", 0.6, {0, side, 0}, diag(0.0008, 0.0012, 0.0010));
    auto h = add(m, a, pin::JointModelRY(), eye, {0, 0, 0}, "h", 1.0, {0, 0, -0.1}, diag(0.010, 0.011, 0.002));
    add(m, h, pin::JointModelRY(), eye, {0, 0, -0.2}, "k", 0.3, {0, 0, -0.1}, diag(0.004, 0.004, 0.0004));
  }
  return m;
}

static pin::Model satellite() {
  pin::Model m;
  auto root = m.addJoint(0, pin::JointModelFreeFlyer(), pin::SE3::Identity(), "bus");
  m.appendBodyToJoint(root, pin::Inertia(100.0, Eigen::Vector3d::Zero(), diag(10.0, 12.0, 9.0)));
  const Eigen::Matrix3d eye = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d tilt = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()).toRotationMatrix();
  auto j = add(m, root, pin::JointModelRZ(), tilt, {0.6, 0, 0.4}, "j1", 4.0, {0, 0, 0.1}, diag(0.05, 0.05, 0.02));
  j = add(m, j, pin::JointModelRY(), eye, {0, 0, 0.2}, "j2", 3.0, {0.25, 0, 0}, diag(0.01, 0.08, 0.08));
  j = add(m, j, pin::JointModelRY(), eye, {0.5, 0, 0}, "j3", 2.0, {0.2, 0, 0}, diag(0.005, 0.05, 0.05));
  j = add(m, j, pin::JointModelRX(), eye, {0.4, 0, 0}, "j4", 0.8, {0.05, 0, 0}, diag(0.002, 0.003, 0.003));
  j = add(m, j, pin::JointModelRY(), eye, {0.1, 0, 0}, "j5", 0.5, {0.03, 0, 0}, diag(0.001, 0.0012, 0.0011));
  add(m, j, pin::JointModelRX(), eye, {0.06, 0, 0}, "j6", 0.3, {0.05, 0.01, 0}, diag(0.0008, 0.001, 0.0009));
  return m;
}

// The numbers after "<model> 0 <key> " in the reference file.
static Eigen::VectorXd reference(const std::string& path, const std::string& model, const std::string& key) {
  std::ifstream in(path);
  const std::string head = model + " 0 " + key + " ";
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(head, 0) != 0) continue;
    std::istringstream s(line.substr(head.size()));
    std::vector<double> xs;
    for (double x; s >> x;) xs.push_back(x);
    return Eigen::Map<Eigen::VectorXd>(xs.data(), xs.size());
  }
  std::fprintf(stderr, "no %s in %s\n", head.c_str(), path.c_str());
  std::exit(1);
}

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : "tests/data/floating_pinocchio.txt";
  std::printf("| model | nv | CRBA + NLE (ns) | ABA (ns) | RNEA (ns) | computeABADerivatives (ns) |\n|---|---|---|---|---|---|\n");
  for (const char* name : {"quadruped", "satellite"}) {
    const pin::Model model = std::string(name) == "quadruped" ? quadruped() : satellite();
    pin::Data data(model);
    const Eigen::VectorXd q = reference(path, name, "q_pin"), v = reference(path, name, "v_pin");
    const Eigen::VectorXd a = Eigen::VectorXd::Constant(model.nv, 0.1), tau = Eigen::VectorXd::Zero(model.nv);
    const int calls = 200000;
    const double crba_nle = ns_per_call([&] { pin::crba(model, data, q); pin::nonLinearEffects(model, data, q, v); }, calls);
    const double aba = ns_per_call([&] { pin::aba(model, data, q, v, tau); }, calls);
    const double rnea = ns_per_call([&] { pin::rnea(model, data, q, v, a); }, calls);
    const double derivatives = ns_per_call([&] { pin::computeABADerivatives(model, data, q, v, tau); }, calls / 4);
    std::printf("| %s | %d | %.0f | %.0f | %.0f | %.0f |\n", name, model.nv, crba_nle, aba, rnea, derivatives);
  }
  return 0;
}
