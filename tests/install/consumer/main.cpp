// A program outside diffray's tree that uses the installed library through the facade: loads a scene,
// simulates it with few rays, prints the T30 of every band of the first listener, and convolves a click
// with the synthesized impulse response (which must give the response back). Exit status 0 on success.
#include <cmath>
#include <iostream>

#include <diffray/diffray.h>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: consumer SCENE.json\n";
    return 2;
  }
  try {
    const diffray::room::Room room = diffray::loadScene(argv[1]);
    const auto sim = diffray::simulate(room, 2000, 7);
    const auto figures = diffray::metrics(sim, 0);
    for (int b = 0; b < room.bands.size(); ++b)
      std::cout << "T30 " << room.bands.nominalHz(b) << " Hz: " << figures[static_cast<std::size_t>(b)].t30 << " s\n";
    const diffray::audio::AudioBuffer ir = diffray::impulseResponse(room, sim, 0);
    diffray::audio::AudioBuffer click;
    click.sample_rate_hz = ir.sample_rate_hz;
    click.samples = {1.0};
    const diffray::audio::AudioBuffer wet = diffray::convolve(click, ir);
    double worst = 0.0;
    for (long i = 0; i < ir.frames(); ++i) worst = std::fmax(worst, std::fabs(wet.samples[i] - ir.samples[i]));
    std::cout << "convolved a click: " << wet.frames() << " frames, largest difference " << worst << "\n";
    return wet.frames() == ir.frames() && worst < 1e-4 ? 0 : 1;
  } catch (const diffray::core::InputError& e) {
    std::cerr << "consumer: " << e.what() << "\n";
    return 1;
  }
}
