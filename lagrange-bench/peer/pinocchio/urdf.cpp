// Pinocchio's CRBA + NLE and ABA on the robots in `robots/` read from the same
// URDF files as lagrange-bench's `urdf` bench. Build and run with `urdf.sh`:
// `urdf_model.py` writes the models Pinocchio's own URDF parser reads (the
// PyPI wheel ships the parser's library but not urdfdom's headers) as C++.
// The state is the bench's: q_k = 0.3 − 0.17 k, q̇_k = 0.5 − 0.21 k (the
// Panda's two fingers, which Pinocchio reads as two joints where the URDF
// makes the second mimic the first, at 0.02 and at rest).
#include <pinocchio/multibody.hpp>
#include <pinocchio/algorithm/aba.hpp>
#include <pinocchio/algorithm/crba.hpp>
#include <pinocchio/algorithm/rnea.hpp>

#include <chrono>
#include <cstdio>
#include <string>

namespace pin = pinocchio;

#include URDF_MODELS

template <class F>
static double ns_per_call(F f, int calls) {
  for (int i = 0; i < calls / 10; ++i) f();  // warm up
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < calls; ++i) f();
  const auto end = std::chrono::steady_clock::now();
  return std::chrono::duration<double, std::nano>(end - start).count() / calls;
}

int main() {
  std::printf("| robot | nq | Pinocchio CRBA + NLE (ns) | Pinocchio ABA (ns) | Pinocchio RNEA (ns) | M[0][0] | (Q - h)[0] |\n|---|---|---|---|---|---|---|\n");
  for (pin::Model model : {ur5(), panda()}) {
    pin::Data data(model);
    Eigen::VectorXd q(model.nq), v(model.nv), tau = Eigen::VectorXd::Zero(model.nv);
    for (int k = 0; k < model.nq; ++k) {
      const bool arm = k < 7 || model.nq <= 7;
      q[k] = arm ? 0.3 - 0.17 * k : 0.02;
      v[k] = arm ? 0.5 - 0.21 * k : 0.0;
    }
    const int calls = 200000;
    double crba_nle = ns_per_call(
        [&] {
          pin::crba(model, data, q);
          pin::nonLinearEffects(model, data, q, v);
        },
        calls);
    double aba = ns_per_call([&] { pin::aba(model, data, q, v, tau); }, calls);
    Eigen::VectorXd a(model.nv);
    for (int k = 0; k < model.nv; ++k) a[k] = (k < 7 || model.nv <= 7) ? 0.1 + 0.05 * k : 0.0;
    double rnea = ns_per_call([&] { pin::rnea(model, data, q, v, a); }, calls);
    pin::crba(model, data, q);
    pin::nonLinearEffects(model, data, q, v);
    std::printf("| %s | %d | %.0f | %.0f | %.0f | %.15g | %.15g |\n", model.name.c_str(), model.nq,
                crba_nle, aba, rnea, data.M(0, 0), -data.nle[0]);
  }
  return 0;
}
