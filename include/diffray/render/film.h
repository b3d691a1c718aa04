#pragma once
// From a RenderResult (render/light_tracer.h) to images: XYZ per pixel to linear sRGB (color::xyzToLinearSrgb,
// IEC 61966-2-1, D65), in the render's radiance units (W m⁻² sr⁻¹ weighted by the CIE 1931 functions), and the
// automatic exposure of the PNG. Pure functions; thread-safe.
#include <ostream>

#include "diffray/image/image.h"
#include "diffray/render/light_tracer.h"

namespace diffray::render {

/// Linear sRGB of every pixel (may hold negative values where a pixel's radiance is negative or out of gamut).
image::Image linearSrgb(const RenderResult& r);

/// The exposure that maps the 99th percentile of the pixels' largest linear sRGB component (over pixels where it
/// is > 0) to 1, so that saturated colours (a red laser) do not clip; 1 when no pixel is positive.
/// `linear_rgb`: linearSrgb() of the render.
double autoExposure(const image::Image& linear_rgb);

/// Every pixel as a CSV row, top row first: `ix,iy,radiance_w_m2_sr,std_error_w_m2_sr,X,Y,Z,r,g,b` — the
/// spectrally integrated mean radiance and its standard error (from the chunks' scatter), CIE XYZ and linear
/// sRGB, all unscaled (no exposure), after a header line. Values to 9 significant digits.
/// `linear_rgb`: linearSrgb(r).
void writePixelCsv(std::ostream& out, const RenderResult& r, const image::Image& linear_rgb);

}  // namespace diffray::render
