#pragma once
// Shared set-up of the room validation cases (room_cases.cpp, decay_cases.cpp): a shoebox room built in
// code from case parameters, its per-wall specular reflection factors for the image-lattice oracle
// (reference/image_lattice.h), and the Schroeder decay curve in dB that both the traced and the reference
// histograms are read through. Units: metres, seconds. Pure functions.
#include <array>
#include <string>
#include <vector>

#include "diffray/room/room.h"
#include "diffray/validate/case.h"

namespace diffray::validate {

struct ShoeboxSpec {
  std::array<double, 3> dims_m{10, 7, 3};
  std::array<double, 3> source_m{2, 3, 1.5};
  std::array<double, 3> listener_m{7, 4, 1.2};
  double radius_m = 0.3;
  std::vector<double> absorption;  ///< per band (octave 63 Hz–8 kHz); one value = every band
  double scattering = 0.0;
  double wall_spread = 0.0;  ///< wall w gets absorption × (1 + spread·w): walls differ, catching mix-ups
};

/// Reads dims/source/listener/radius/absorption/scattering from the case's parameters (names as given).
ShoeboxSpec shoeboxFromParams(const Params& p);
/// The room: octave bands, one material per wall, 20 °C / 50 % air, one source and one listener.
room::Room makeShoebox(const ShoeboxSpec& spec);
/// Specular energy reflection factor (1 − α)(1 − s) per wall (x−, x+, y−, y+, z−, z+) and band.
std::array<std::vector<double>, 6> specularFactors(const room::Room& room);
/// 10·log10(E(t)/E(0)) of a histogram, E the backward (Schroeder) integral, at each bin's start.
std::vector<double> schroederDb(const std::vector<double>& energy);
/// The common ParamSpecs of a shoebox case.
std::vector<ParamSpec> shoeboxParams(double absorption, double scattering, double radius_m);

}  // namespace diffray::validate
