#include "diffray/compare/wave_model.h"

#include <utility>

namespace diffray::compare {

ListenerHistograms waveHistograms(const room::Room& room, const reference::WaveResult& result) {
  ListenerHistograms h;
  h.bin_s = result.plan.bin_s;
  h.energy.assign(room.listeners.size(), std::vector<std::vector<double>>(static_cast<std::size_t>(room.bands.size())));
  for (std::size_t l = 0; l < room.listeners.size() && l < result.listeners.size(); ++l)
    for (std::size_t k = 0; k < result.plan.bands.size(); ++k)
      h.energy[l][static_cast<std::size_t>(result.plan.bands[k].band)] = result.listeners[l].energy[k];
  return h;
}

HistogramModel waveModel(reference::WaveOptions options) {
  return [options = std::move(options)](const room::Room& room) {
    return waveHistograms(room, reference::simulateWave(room, options));
  };
}

}  // namespace diffray::compare
