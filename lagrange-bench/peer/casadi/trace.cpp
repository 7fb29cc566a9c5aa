// Pinocchio's algorithms traced symbolically with CasADi (scalar casadi::SX,
// pinocchio/autodiff/casadi.hpp: the templates that the Python module
// `pinocchio.casadi` wraps, which no PyPI wheel of `pin` ships) and emitted
// as C by CasADi's CodeGenerator, common subexpressions eliminated
// (Function option `cse`). Per arm of robots/ (the models as
// ../pinocchio/urdf_model.py writes them; not the Panda, whose mimic finger
// Pinocchio reads as a second joint) and per robot on a free-flyer root
// (its FLOATING: Solo 12), the functions
//   <arm>_crba_nle(q, v)             -> M (CRBA, both triangles), h (NLE)
//   <arm>_rnea(q, v, a)              -> tau
//   <arm>_aba(q, v, tau)             -> ddq
//   <arm>_chol(q, v, tau)            -> ddq = M^-1 (tau - h), M by CRBA, h by
//                                       NLE, M = L L^T traced in SX
//   <arm>_chol_qr(q, v, tau)         -> the same by SX::solve(M, b), CasADi's
//                                       QR solve on SX (the "symbolicqr"
//                                       plugin is not defined for SX)
//   <arm>_aba_derivatives(q, v, tau) -> ddq_dq, ddq_dv, Minv
//   <arm>_rnea_derivatives(q, v, a)  -> dtau_dq, dtau_dv
// (chol_qr not on a floating root) in OUT/casadi_gen.c (with its header),
// and OUT/casadi_registry.h: the table harness.c walks, each row naming its
// robot's state arrays <robot>_q, _v, _a, which casadi_codegen.py writes
// into casadi_states.h.
// Built and run by casadi_codegen.py.
#include <pinocchio/autodiff/casadi.hpp>
#include <pinocchio/multibody.hpp>
#include <pinocchio/algorithm/aba.hpp>
#include <pinocchio/algorithm/aba-derivatives.hpp>
#include <pinocchio/algorithm/crba.hpp>
#include <pinocchio/algorithm/rnea.hpp>
#include <pinocchio/algorithm/rnea-derivatives.hpp>
#include <casadi/casadi.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace pin = pinocchio;

#include URDF_MODELS

using SX = casadi::SX;
using ADModel = pin::ModelTpl<SX>;
using ADData = pin::DataTpl<SX>;
using VecX = Eigen::Matrix<SX, Eigen::Dynamic, 1>;
using MatX = Eigen::Matrix<SX, Eigen::Dynamic, Eigen::Dynamic>;

static SX to_sx(const MatX& m) {
  SX out(m.rows(), m.cols());
  pin::casadi::copy(m, out);
  return SX::densify(out);
}

static VecX from_sx(const SX& s) {
  VecX out(s.size1());
  for (casadi_int i = 0; i < s.size1(); ++i) out[i] = s(i);
  return out;
}

// Both triangles of a matrix Pinocchio fills above the diagonal only.
static MatX symmetric(MatX m) {
  m.triangularView<Eigen::StrictlyLower>() = m.transpose().triangularView<Eigen::StrictlyLower>();
  return m;
}

// x = M^-1 b by M = L L^T, traced in SX.
static SX cholesky_solve(const SX& M, const SX& b) {
  const casadi_int n = M.size1();
  std::vector<std::vector<SX>> L(n, std::vector<SX>(n, SX(0)));
  std::vector<SX> inv(n);
  for (casadi_int j = 0; j < n; ++j) {
    SX d = M(j, j);
    for (casadi_int k = 0; k < j; ++k) d -= L[j][k] * L[j][k];
    const SX l = sqrt(d);
    L[j][j] = l;
    inv[j] = 1 / l;
    for (casadi_int i = j + 1; i < n; ++i) {
      SX s = M(i, j);
      for (casadi_int k = 0; k < j; ++k) s -= L[i][k] * L[j][k];
      L[i][j] = s * inv[j];
    }
  }
  std::vector<SX> y(n), x(n);
  for (casadi_int i = 0; i < n; ++i) {
    SX s = b(i);
    for (casadi_int k = 0; k < i; ++k) s -= L[i][k] * y[k];
    y[i] = s * inv[i];
  }
  for (casadi_int i = n - 1; i >= 0; --i) {
    SX s = y[i];
    for (casadi_int k = i + 1; k < n; ++k) s -= L[k][i] * x[k];
    x[i] = s * inv[i];
  }
  return SX::vertcat(x);
}

// Traces one robot's functions into `gen`, one registry row each. `full`
// adds chol_qr (CasADi's symbolic QR solve, which on Solo 12's 18 × 18 M is
// too large to be worth tracing).
static void trace(const Robot& robot, bool full, casadi::CodeGenerator& gen,
                  std::vector<std::string>& rows) {
  const std::string name = robot.name;
  casadi::Dict fopts{{"cse", true}};
  const pin::Model model = robot.build();
  const ADModel ad = model.cast<SX>();
  const int nq = model.nq, nv = model.nv;
  const SX cq = SX::sym("q", nq), cv = SX::sym("v", nv), ca = SX::sym("a", nv);
  const VecX q_ad = from_sx(cq), v_ad = from_sx(cv), a_ad = from_sx(ca);

  auto add = [&](const std::string& quantity, const std::vector<SX>& in,
                 const std::vector<std::string>& in_names, const std::vector<SX>& outs,
                 const std::vector<std::string>& out_names) {
    const std::string fn = name + "_" + quantity;
    casadi::Function f(fn, in, outs, in_names, out_names, fopts);
    gen.add(f);
    std::ostringstream row;
    row << "  {\"" << name << "\", \"" << quantity << "\", " << fn << ", " << fn << "_work, "
        << name << "_q, " << name << "_v, " << name << "_a, " << in.size() << ", " << outs.size()
        << ", {";
    for (size_t i = 0; i < outs.size(); ++i)
      row << (i ? ", " : "") << "{\"" << out_names[i] << "\", " << outs[i].size1() << ", "
          << outs[i].size2() << "}";
    row << "}}";
    rows.push_back(row.str());
  };

  {
    ADData data(ad);
    pin::crba(ad, data, q_ad);
    const MatX M = symmetric(data.M);
    const VecX h = pin::nonLinearEffects(ad, data, q_ad, v_ad);
    add("crba_nle", {cq, cv}, {"q", "v"}, {to_sx(M), to_sx(h)}, {"M", "h"});
    const SX b = ca - to_sx(h);
    add("chol", {cq, cv, ca}, {"q", "v", "tau"}, {cholesky_solve(to_sx(M), b)}, {"ddq"});
    if (full)
      add("chol_qr", {cq, cv, ca}, {"q", "v", "tau"}, {SX::densify(SX::solve(to_sx(M), b))},
          {"ddq"});
  }
  {
    ADData data(ad);
    const VecX tau = pin::rnea(ad, data, q_ad, v_ad, a_ad);
    add("rnea", {cq, cv, ca}, {"q", "v", "a"}, {to_sx(tau)}, {"tau"});
  }
  {
    ADData data(ad);
    const VecX ddq = pin::aba(ad, data, q_ad, v_ad, a_ad);
    add("aba", {cq, cv, ca}, {"q", "v", "tau"}, {to_sx(ddq)}, {"ddq"});
  }
  {
    ADData data(ad);
    pin::computeABADerivatives(ad, data, q_ad, v_ad, a_ad);
    add("aba_derivatives", {cq, cv, ca}, {"q", "v", "tau"},
        {to_sx(data.ddq_dq), to_sx(data.ddq_dv), to_sx(symmetric(data.Minv))},
        {"ddq_dq", "ddq_dv", "Minv"});
  }
  {
    ADData data(ad);
    pin::computeRNEADerivatives(ad, data, q_ad, v_ad, a_ad);
    add("rnea_derivatives", {cq, cv, ca}, {"q", "v", "a"},
        {to_sx(data.dtau_dq), to_sx(data.dtau_dv)}, {"dtau_dq", "dtau_dv"});
  }
  std::fprintf(stderr, "traced %s (nq %d, nv %d)\n", name.c_str(), nq, nv);
}

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: trace OUT_DIR\n");
    return 2;
  }
  const std::string out = argv[1];
  casadi::CodeGenerator gen("casadi_gen.c", casadi::Dict{{"with_header", true}});
  std::vector<std::string> rows;
  for (const Robot& robot : ROBOTS)
    if (std::string(robot.name) != "panda") trace(robot, true, gen, rows);
  for (const Robot& robot : FLOATING) trace(robot, false, gen, rows);
  gen.generate(out + "/");
  std::ofstream reg(out + "/casadi_registry.h");
  reg << "// Written by trace.cpp: one row per generated function (the states'\n"
      << "// arrays are casadi_codegen.py's, in casadi_states.h).\n"
      << "static const Entry ENTRIES[] = {\n";
  for (size_t i = 0; i < rows.size(); ++i) reg << rows[i] << (i + 1 < rows.size() ? ",\n" : "\n");
  reg << "};\n";
  return 0;
}
