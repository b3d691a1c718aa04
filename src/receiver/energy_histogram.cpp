#include "diffray/receiver/energy_histogram.h"

#include <cmath>

#include "diffray/core/error.h"

namespace diffray::receiver {

void EnergyHistogram::closeChunk(int batch, int batches, double weight) {
  std::vector<double>* to = nullptr;
  if (batch >= 0) {
    DIFFRAY_CHECK(batch < batches);
    if (batch_.size() < static_cast<std::size_t>(batches)) {
      batch_.resize(static_cast<std::size_t>(batches));
      batch_weight_.resize(static_cast<std::size_t>(batches), 0.0);
    }
    to = &batch_[static_cast<std::size_t>(batch)];
    if (to->empty()) to->assign(chunk_.size(), 0.0);
    batch_weight_[static_cast<std::size_t>(batch)] += weight;
  }
  for (std::size_t i = 0; i < chunk_.size(); ++i) {
    sum_[i] += chunk_[i];
    sum_sq_[i] += chunk_[i] * chunk_[i];
    if (to) (*to)[i] += chunk_[i];
    chunk_[i] = 0.0;
  }
  ++chunks_;
}

void EnergyHistogram::merge(const EnergyHistogram& o) {
  for (std::size_t i = 0; i < sum_.size(); ++i) {
    sum_[i] += o.sum_[i];
    sum_sq_[i] += o.sum_sq_[i];
    exact_[i] += o.exact_[i];
  }
  chunks_ += o.chunks_;
  if (batch_.size() < o.batch_.size()) {
    batch_.resize(o.batch_.size());
    batch_weight_.resize(o.batch_.size(), 0.0);
  }
  for (std::size_t k = 0; k < o.batch_.size(); ++k) {
    batch_weight_[k] += o.batch_weight_[k];
    const std::vector<double>& from = o.batch_[k];
    if (from.empty()) continue;
    std::vector<double>& to = batch_[k];
    if (to.empty()) {
      to = from;
    } else {
      for (std::size_t i = 0; i < to.size(); ++i) to[i] += from[i];
    }
  }
}

void EnergyHistogram::scale(double factor) {
  for (std::size_t i = 0; i < sum_.size(); ++i) {
    sum_[i] *= factor;
    sum_sq_[i] *= factor * factor;
    exact_[i] *= factor;
  }
  for (auto& b : batch_)
    for (double& v : b) v *= factor;
}

double EnergyHistogram::standardError(int band, int bin) const {
  if (chunks_ < 2) return 0.0;
  const std::size_t i = index(band, bin);
  const double n = static_cast<double>(chunks_);
  const double mean = sum_[i] / n;
  const double var = (sum_sq_[i] / n - mean * mean) * n / (n - 1.0);  // of one chunk total
  return var > 0.0 ? std::sqrt(var * n) : 0.0;                          // of the sum of n chunks
}

}  // namespace diffray::receiver
