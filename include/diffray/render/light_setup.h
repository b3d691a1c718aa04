#pragma once
// A light scene made ready to trace: one transport::Scene (Embree, transport/scene.h) holding each occluder
// with its WBSDF tables and each diffuse rectangle as a one-bin transport::Screen (only its rectangle and
// frame are used: the light tracer scores through the camera, render/light_tracer.h), the camera, and each
// pixel's solid angle. Object ids of the transport scene map back through Scene::object(id): kind Screen,
// index i is LightScene::rects[i]; kind Occluder, index k is LightScene::occluders[k].
//
// Table resolution (wbsdf/table.h; one table per axis serves every wavelength, since W(x, u) in cycles per
// metre does not depend on λ, only where a shift sends the ray does). Per axis:
//  - shift range |u'| ≤ 1.02·Δ/λ_min, Δ the largest change of the direction cosine along that axis between
//    any incident direction (from the lights and the other objects) and any outgoing one (to the other
//    objects), capped at 2/λ_min (every propagating shift). Shifts beyond it would reach no object. Each
//    object's directions are bounded exactly over its whole rectangle (render/direction_bounds.h; corners
//    alone miss the middle of an edge), over 8 × 8 cells of the occluder.
//    A lens: Δ is taken with its geometric deflection −x/f, −y/f out, over the points of its opening (the
//    table holds only the diffraction around the geometric ray; light_setup.cpp, lensShiftBounds).
//  - du: a u-cell moves a landing point by up to λ_max·z·du (z the throw from the occluder to a diffuse
//    rectangle); du keeps that under 1/8 of the pixel footprint there (camera pixel pitch × distance), over
//    every rectangle. Gratings: their lines (wbsdf/table.h).
//  - dx: 1/8 of the smaller of the footprint and the feature size (slit width, period).
// Tables are limited to 8 million cells (coarser in u beyond that). Immutable once built; thread-safe.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "diffray/core/progress.h"
#include "diffray/render/camera.h"
#include "diffray/render/light_scene.h"
#include "diffray/transport/scene.h"
#include "diffray/wbsdf/table.h"

namespace diffray::render {

struct PreparedScene {
  const LightScene* spec = nullptr;  ///< not owned: must outlive this
  transport::Scene scene;
  Camera camera{CameraSpec{}};
  std::vector<double> pixel_solid_angle_sr;  ///< width × height, row-major, top row first
};

/// The table options of one occluder axis (see above): `delta_cos` is Δ, `footprint_m` and `throw_m` the
/// pixel footprint on and the distance to the diffuse rectangle that needs the finest cells.
wbsdf::TableOptions axisTableOptions(const wbsdf::Microstructure& m, double delta_cos, double lambda_min_m,
                                     double lambda_max_m, double footprint_m, double throw_m);

/// Builds tables and the Embree scene (brute_force: the test back end). Throws InputError for a table that
/// cannot be built. table_progress (optional; e.g. core::progressOfUnknownSize) makes one callback per table
/// (TableOptions::on_row), labelled by occluder and axis.
std::unique_ptr<PreparedScene> prepareScene(const LightScene& spec, bool brute_force = false,
                                            const core::ProgressFactory& table_progress = {});

}  // namespace diffray::render
