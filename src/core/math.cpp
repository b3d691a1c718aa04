#include "diffray/core/math.h"

#include <Eigen/Eigenvalues>
#include <atomic>
#include <map>
#include <memory>
#include <mutex>

#include "diffray/core/error.h"

namespace diffray::core {

namespace {
GaussLegendre computeGaussLegendre(int n) {
  // Golub–Welsch: the nodes are the eigenvalues of the Jacobi matrix of the Legendre recurrence,
  // beta_k = k / sqrt(4k^2 - 1); the weights are 2·(first eigenvector component)^2.
  Eigen::MatrixXd jacobi = Eigen::MatrixXd::Zero(n, n);
  for (int k = 1; k < n; ++k) {
    const double beta = k / std::sqrt(4.0 * k * k - 1.0);
    jacobi(k, k - 1) = beta;
    jacobi(k - 1, k) = beta;
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(jacobi);
  GaussLegendre rule;
  rule.nodes.resize(n);
  rule.weights.resize(n);
  for (int i = 0; i < n; ++i) {
    rule.nodes[i] = solver.eigenvalues()(i);
    const double v0 = solver.eigenvectors()(0, i);
    rule.weights[i] = 2.0 * v0 * v0;
  }
  return rule;
}
}  // namespace

const GaussLegendre& gaussLegendre(int n) {
  DIFFRAY_CHECK(n >= 1 && n <= 512);
  // Lock-free once a rule exists: table builds call this once per cell from every thread, and the lock
  // alone took 17 % of a lens scene's set-up. (The atomics start null: constant initialisation.)
  static std::atomic<const GaussLegendre*> ready[513] = {};
  if (const GaussLegendre* rule = ready[n].load(std::memory_order_acquire)) return *rule;
  static std::mutex mutex;
  static std::map<int, std::unique_ptr<GaussLegendre>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = cache[n];
  if (!slot) slot = std::make_unique<GaussLegendre>(computeGaussLegendre(n));
  ready[n].store(slot.get(), std::memory_order_release);
  return *slot;
}

}  // namespace diffray::core
