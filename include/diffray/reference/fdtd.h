#pragma once
// A wave-based reference for rooms: 3D finite-difference time-domain (FDTD) simulation of the linear
// acoustic wave equation on any scene diffray loads, one run per octave band, giving per listener and band
// an energy histogram, its ISO 3382-1 metrics and the strength G. It shares no code with the ray tracers
// (transport, wbsdf, utd): the scheme, walls and source are in fdtd_scheme.h, the voxel grid in
// fdtd_grid.h, the band analysis in fdtd_analysis.h.
//
// Per band b (nominal centre f_b, edges f_lo, f_hi from room.bands):
//  - Grid: spacing h = min(c/(ppw·f_hi), max_h) (default 10 points per wavelength at the band's upper edge,
//    h ≤ 0.1 m), Courant number λ = factor/√3 (factor ≤ 1), dt = λh/c, c = room::speedOfSound(room.air).
//    Axial phase-velocity error at f_hi (fdtd_scheme.h's dispersion relation): −1.1 % at 10 ppw and λ = 1/√3 (tested).
//  - Walls: each material's α in band b mapped to a real admittance β by the Paris formula
//    (admittanceForAbsorption); a material that transmits part of the energy is a wall whose α counts the
//    transmitted part as lost; openings (room::Room::isOpening) are transparent. No air absorption.
//  - Source: each room source in turn (omnidirectional: a directivity pattern is ignored with a warning),
//    the Ricker pulse peaking at f_b injected at the air node nearest to it whose segment to the source
//    crosses no wall; energies of several sources add (incoherent, as in the ray tracers).
//  - Receivers: the air nodes inside each listener's sphere (a regular subset of at most max_points, in
//    index order), each recording band-passed to [f_lo, f_hi] by a zero-phase FFT filter with
//    smooth power-complementary edges (fdtd_analysis.h),
//    squared and averaged over the points, binned at room.output.histogram_bin_s from the source's emission
//    (the pulse's peak) on.
//  - Units: histograms are scaled so that the free-field energy at distance r of a source of power P is
//    P/r² (J/m²-like, the ray tracers' receiver convention: a 1 W omnidirectional source gives 1/r²), from
//    the free-field response of the injection (freeFieldFactor): E_ff(r) = (F/r)²·Σ_n (BP s)_n²·dt with the
//    same filter on the pulse. The strength is G_b = 10·log10(E_b/E_b,ff(10 m)) = 10·log10(100·E_b/P)
//    (ISO 3382-1 Annex A, sound strength: the level re the same source's free field at 10 m).
//  - Length: WaveOptions::length_s, else room.output.ir_length_s, else 1.5 × the longest Eyring T60 of the
//    simulated bands (room volume and enclosure, area-weighted α), capped at room.output.max_length_s; for a
//    scene without a closed volume, 4 × the domain's diagonal / c.
// Metrics come from ir::metricsFromHistograms over the simulated bands (one time zero for them all).
//
// Bad input throws core::InputError before any time step: a band that is not one of the room's, a grid
// that needs more than half the machine's memory (estimated before allocation), a source inside a wall or
// a closed part of the scene (its air holds less than half the room's volume) or outside a closed room (its
// air reaches the domain's edge), a listener whose sphere holds no air node. Thread-safety: simulateWave
// uses every TBB thread (or a core::ThreadLimit's); concurrent calls are safe but share the cores.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "diffray/ir/metrics.h"
#include "diffray/room/room.h"

namespace diffray::reference {

struct WaveOptions {
  std::vector<double> bands_hz;  ///< nominal centres to simulate; empty: every room band up to 500 Hz that fits
  double ppw = 10.0;             ///< points per wavelength at each band's upper edge
  double max_h_m = 0.1;          ///< the grid is never coarser than this (geometry detail)
  double length_s = 0.0;         ///< 0: the room's, or the Eyring estimate (header)
  double courant_factor = 1.0;   ///< λ = factor/√3, in (0, 1]
  int margin_cells = 3;          ///< free cells around the mesh's bounding box
  int max_points = 64;           ///< recording nodes per listener at most
  std::function<void(std::uint64_t)> on_progress;  ///< time steps done (called every few steps)
  /// Called once every check has passed, just before the first time step (e.g. to state the plan).
  std::function<void()> on_start;
};

/// What one band's run needs, known before any allocation.
struct WaveBandPlan {
  int band = 0;  ///< index in room.bands
  double h_m = 0, dt_s = 0, courant = 0;
  int nx = 0, ny = 0, nz = 0;
  double bytes = 0;             ///< memory estimate of the run
  long steps = 0;               ///< time steps per source
  double phase_error_top = 0;   ///< axial phase velocity / c − 1 at the band's upper edge
};

struct WavePlan {
  std::vector<WaveBandPlan> bands;
  double speed_of_sound_m_s = 0, length_s = 0, bin_s = 0;
  double physical_bytes = 0;
  std::uint64_t total_steps = 0;  ///< Σ over bands of steps × sources
  std::vector<std::string> warnings;
};

/// Checks the options and plans every band (no grid built). Throws core::InputError as in the header.
WavePlan planWave(const room::Room& room, const WaveOptions& options);

struct WaveListenerResult {
  std::vector<std::vector<double>> energy;  ///< [k][bin], k over WavePlan::bands
  std::vector<double> g_db;                 ///< [k]
  std::vector<ir::BandMetrics> metrics;     ///< [k]
  std::vector<int> points;                  ///< recording nodes used, [k]
};

struct WaveResult {
  WavePlan plan;
  std::vector<WaveListenerResult> listeners;  ///< parallel to room.listeners
  std::vector<long> air_nodes;                ///< [k]
  std::vector<double> seconds;                ///< wall time of each band's runs, [k]
  std::vector<std::string> warnings;
};

/// Runs the reference. Every check (planWave's, then each band's grid: sources and listeners) is made
/// before the first time step.
WaveResult simulateWave(const room::Room& room, const WaveOptions& options);

}  // namespace diffray::reference
