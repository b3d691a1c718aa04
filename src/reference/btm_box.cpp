// A rigid box's field to second order in edge diffraction, at one frequency and at many (see btm_box.h).
#include "diffray/reference/btm_box.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "btm_paths.h"
#include "diffray/core/error.h"

namespace diffray::reference {
namespace {

using namespace btm_detail;
using core::Vec3;
using Complex = std::complex<double>;

constexpr double kExterior = 1.5 * kPi;  // θ_w of every edge
constexpr double kNu = 2.0 / 3.0;        // π/θ_w

// A face of the box: axis 0–2 and side 0 (the min plane, outward normal −e_axis) or 1 (max, +e_axis),
// numbered 2·axis + side.
int faceAxis(int face) { return face / 2; }
double faceSign(int face) { return face % 2 == 1 ? 1.0 : -1.0; }

// An edge with its frame (btm_paths.h) and its faces: face A is the half-plane θ = 0 (along +x, outward
// normal +y), face B the half-plane θ = 3π/2 (along −y, outward normal −x).
struct BoxEdge {
  EdgeFrame frame;
  int face_a, face_b;
  // Whether p lies on the outer side (or in the plane) of face A or of face B: then it sees the edge.
  bool sees(const Vec3& p) const {
    const Vec3 d = p - frame.origin;
    return d.dot(frame.y) >= 0.0 || d.dot(frame.x) <= 0.0;
  }
  // p in the edge's frame, θ in [0, 3π/2] for a point that sees the edge (rounding clamped).
  CylindricalPoint of(const Vec3& p) const {
    CylindricalPoint c = frame.of(p);
    c.phi_rad = std::min(c.phi_rad, kExterior);
    return c;
  }
};

// The box's geometry for one source and one receiver, checked (btm_box.h's contract), with the paths of its
// geometric waves and the list of its diffracted terms (tasks): each edge's first-order term, then at order 2
// each ordered pair of edges that share a face.
class BoxPaths {
 public:
  BoxPaths(const BtmBox& box, const Vec3& source, const Vec3& receiver, int order)
      : box_(box), source_(source), receiver_(receiver) {
    const Vec3 extent = box.max_m - box.min_m;
    const Vec3 centre = 0.5 * (box.min_m + box.max_m);
    scale_ = 0.5 * extent.norm() + (source - centre).norm() + (receiver - centre).norm();
    for (int a = 0; a < 3; ++a) {
      const int b = (a + 1) % 3, c = (a + 2) % 3;  // e_b × e_c = e_a
      for (int side_b = 0; side_b < 2; ++side_b)
        for (int side_c = 0; side_c < 2; ++side_c) {
          BoxEdge e{{}, 2 * b + side_b, 2 * c + side_c};
          const Vec3 n_a = faceSign(e.face_a) * Vec3::Unit(b), n_b = faceSign(e.face_b) * Vec3::Unit(c);
          e.frame.x = -n_b;
          e.frame.y = n_a;
          e.frame.z = e.frame.x.cross(e.frame.y);  // ±e_a
          e.frame.length = extent[a];
          e.frame.origin[b] = side_b == 1 ? box.max_m[b] : box.min_m[b];
          e.frame.origin[c] = side_c == 1 ? box.max_m[c] : box.min_m[c];
          e.frame.origin[a] = e.frame.z[a] > 0.0 ? box.min_m[a] : box.max_m[a];
          edges_.push_back(e);
        }
    }
    for (int i = 0; i < 12; ++i) tasks_.push_back({i, -1, -1});
    if (order < 2) return;
    for (int i = 0; i < 12; ++i)
      for (int j = 0; j < 12; ++j) {
        const BoxEdge &ei = edges_[static_cast<std::size_t>(i)], &ej = edges_[static_cast<std::size_t>(j)];
        for (int f : {ei.face_a, ei.face_b})
          if (i != j && (f == ej.face_a || f == ej.face_b)) tasks_.push_back({i, j, f});
      }
  }

  std::size_t tasks() const { return tasks_.size(); }
  bool secondOrder(std::size_t t) const { return tasks_[t].j >= 0; }

  // Task t's nodes, panels sized for `wavelength_m`: emit(path_m, amplitude) for each.
  template <class Emit>
  void run(std::size_t t, double wavelength_m, Emit&& emit) const {
    const Task& task = tasks_[t];
    const BoxEdge& ei = edges_[static_cast<std::size_t>(task.i)];
    const double tiny = 1e-12 * scale_;
    if (!ei.sees(source_) || ei.of(source_).rho_m <= tiny) return;  // hidden, or on the edge's line: 0
    if (task.j < 0) {
      if (!ei.sees(receiver_) || ei.of(receiver_).rho_m <= tiny) return;
      BtmWedge wedge;
      wedge.exterior_angle_rad = kExterior;
      wedge.z_start_m = 0.0;
      wedge.z_end_m = ei.frame.length;
      std::vector<BtmNode> nodes;
      btmEdgeNodes(wedge, ei.of(source_), ei.of(receiver_), wavelength_m, &nodes);
      for (const BtmNode& q : nodes) emit(q.path_m, q.amplitude);
      return;
    }
    const BoxEdge& ej = edges_[static_cast<std::size_t>(task.j)];
    if (!ej.sees(receiver_) || ej.of(receiver_).rho_m <= tiny) return;
    // The shared face in each edge's frame: face A at θ = 0 across +x, face B at θ = 3π/2 across −y.
    PairFaces faces;
    faces.nu = kNu;
    faces.count = 1;
    faces.every_feature = true;
    faces.across_i = task.face == ei.face_a ? ei.frame.x : Vec3(-ei.frame.y);
    faces.theta_i[0] = task.face == ei.face_a ? 0.0 : kExterior;
    faces.theta_j[0] = task.face == ej.face_a ? 0.0 : kExterior;
    edgePairNodes(ei.frame, ej.frame, faces, source_, receiver_, scale_, wavelength_m, emit);
  }

  // The path lengths of the direct wave (if the segment does not enter the box) and of the faces' images.
  GeometricWaves geometric() const {
    GeometricWaves w;
    if (!segmentEntersBox(source_, receiver_)) w.direct.push_back({(receiver_ - source_).norm(), 1.0});
    for (int f = 0; f < 6; ++f) {
      const int a = faceAxis(f);
      const double plane = faceSign(f) > 0.0 ? box_.max_m[a] : box_.min_m[a];
      const double ds = faceSign(f) * (source_[a] - plane), dr = faceSign(f) * (receiver_[a] - plane);
      if (!(ds > 0.0 && dr > 0.0)) continue;
      Vec3 image = source_;
      image[a] = 2.0 * plane - source_[a];
      const Vec3 at = image + (receiver_ - image) * (ds / (ds + dr));  // the reflection point
      bool on_face = true;
      for (int c = 0; c < 3; ++c)
        if (c != a && (at[c] < box_.min_m[c] || at[c] > box_.max_m[c])) on_face = false;
      if (on_face) w.specular.push_back({(receiver_ - image).norm(), 1.0});
    }
    return w;
  }

  // The shortest and longest path of any diffracted term: at least the straight distance, at most the
  // farthest corner from the source, the box's diagonal and the farthest corner from the receiver.
  void pathRange(double* lo_m, double* hi_m) const {
    double to_s = 0.0, to_r = 0.0;
    for (int v = 0; v < 8; ++v) {
      const Vec3 corner(v & 1 ? box_.max_m.x() : box_.min_m.x(), v & 2 ? box_.max_m.y() : box_.min_m.y(),
                        v & 4 ? box_.max_m.z() : box_.min_m.z());
      to_s = std::max(to_s, (corner - source_).norm());
      to_r = std::max(to_r, (corner - receiver_).norm());
    }
    *lo_m = std::min(*lo_m, (receiver_ - source_).norm());
    *hi_m = std::max(*hi_m, to_s + (box_.max_m - box_.min_m).norm() + to_r);
  }

 private:
  struct Task {
    int i, j, face;  // first order of edge i (j < 0), or the pair (i, j) along `face`
  };

  // Whether the segment from p to q passes through the box's open interior (slabs; touching a face, an edge
  // or a corner does not count).
  bool segmentEntersBox(const Vec3& p, const Vec3& q) const {
    double t0 = 0.0, t1 = 1.0;
    for (int a = 0; a < 3; ++a) {
      const double d = q[a] - p[a];
      if (d == 0.0) {
        if (!(p[a] > box_.min_m[a] && p[a] < box_.max_m[a])) return false;
        continue;
      }
      const double ta = (box_.min_m[a] - p[a]) / d, tb = (box_.max_m[a] - p[a]) / d;
      t0 = std::max(t0, std::min(ta, tb));
      t1 = std::min(t1, std::max(ta, tb));
    }
    return t0 < t1;
  }

  BtmBox box_;
  Vec3 source_, receiver_;
  double scale_ = 0.0;  // the box's half diagonal plus the points' distances from its centre
  std::vector<BoxEdge> edges_;
  std::vector<Task> tasks_;
};

// Checks a box (finite, extent in every axis above 1e-9 of the largest) and a point (finite, outside the
// closed box by more than 1e-12 of the box's size).
void checkBox(const BtmBox& box) {
  for (int c = 0; c < 3; ++c) {
    core::requireFinite("box min", box.min_m[c]);
    core::requireFinite("box max", box.max_m[c]);
  }
  const Vec3 extent = box.max_m - box.min_m;
  if (!(extent.minCoeff() > 1e-9 * extent.maxCoeff()))
    throw core::InputError("box", "must have max above min in every axis (a thin plate is btm_plate.h's)");
}

void checkPoint(const std::string& where, const BtmBox& box, const Vec3& p) {
  for (int c = 0; c < 3; ++c) core::requireFinite(where, p[c]);
  const double margin = 1e-12 * (box.max_m - box.min_m).maxCoeff();
  bool inside = true;
  for (int c = 0; c < 3; ++c)
    if (p[c] < box.min_m[c] - margin || p[c] > box.max_m[c] + margin) inside = false;
  if (inside) throw core::InputError(where, "lies inside or on the box");
}

void checkWavenumber(double k, int order) {
  if (order != 1 && order != 2) throw core::InputError("order", "must be 1 or 2, got " + std::to_string(order));
  core::requireFinite("wavenumber", k);
  if (!(k > 0.0)) throw core::InputError("wavenumber", "must be > 0, got " + std::to_string(k));
}

// The scenes whose fields add up to the answer: the box with the source, or on a ground the union of the
// box and its mirror with the source and with its image (btm_box.h). Checks the input.
std::vector<BoxPaths> scenes(const BtmBox& box, double ground_z_m, const Vec3& source, const Vec3& receiver,
                             int order) {
  checkBox(box);
  if (std::isnan(ground_z_m)) {
    checkPoint("source", box, source);
    checkPoint("receiver", box, receiver);
    return {BoxPaths(box, source, receiver, order)};
  }
  core::requireFinite("ground height", ground_z_m);
  const double tol = 1e-9 * std::max(1.0, (box.max_m - box.min_m).maxCoeff() + std::abs(ground_z_m));
  if (std::abs(box.min_m.z() - ground_z_m) > tol)
    throw core::InputError("box", "must stand on the ground (its min z equal to " + std::to_string(ground_z_m) + ")");
  checkPoint("source", box, source);
  checkPoint("receiver", box, receiver);
  if (!(source.z() > ground_z_m + tol) || !(receiver.z() > ground_z_m + tol))
    throw core::InputError("ground", "the source and the receiver must lie above it");
  BtmBox both = box;
  both.min_m.z() = 2.0 * ground_z_m - box.max_m.z();
  const Vec3 image(source.x(), source.y(), 2.0 * ground_z_m - source.z());
  return {BoxPaths(both, source, receiver, order), BoxPaths(both, image, receiver, order)};
}

BtmBoxField fieldAt(double k, const BtmBox& box, double ground_z_m, const Vec3& source, const Vec3& receiver,
                    int order) {
  checkWavenumber(k, order);
  BtmBoxField u;
  const double wavelength = 2.0 * kPi / k;
  for (const BoxPaths& sc : scenes(box, ground_z_m, source, receiver, order)) {
    const GeometricWaves w = sc.geometric();
    for (const GeometricWave& g : w.direct) u.direct += std::polar(g.weight / g.path_m, -k * g.path_m);
    for (const GeometricWave& g : w.specular) u.specular += std::polar(g.weight / g.path_m, -k * g.path_m);
    for (std::size_t t = 0; t < sc.tasks(); ++t) {
      Complex& sum = sc.secondOrder(t) ? u.second_order : u.diffracted;
      sc.run(t, wavelength, [&](double path, double amplitude) { sum += std::polar(amplitude, -k * path); });
    }
  }
  return u;
}

}  // namespace

BtmBoxField btmBoxField(double wavenumber_rad_m, const BtmBox& box, const Vec3& source, const Vec3& receiver,
                        int order) {
  return fieldAt(wavenumber_rad_m, box, std::nan(""), source, receiver, order);
}

BtmBoxField btmBoxOnGroundField(double wavenumber_rad_m, const BtmBox& box, double ground_z_m, const Vec3& source,
                                const Vec3& receiver, int order) {
  core::requireFinite("ground height", ground_z_m);
  return fieldAt(wavenumber_rad_m, box, ground_z_m, source, receiver, order);
}

std::vector<BtmBoxField> btmBoxSpectrum(const std::vector<double>& wavenumbers_rad_m, const BtmBox& box,
                                        double ground_z_m, const Vec3& source, const Vec3& receiver, int order) {
  const SpectrumAxis axis(wavenumbers_rad_m, order);
  const std::vector<BoxPaths> all = scenes(box, ground_z_m, source, receiver, order);
  GeometricWaves waves;
  double lo = 1e300, hi = 0.0;
  // One task per scene's term, in scene order.
  std::vector<std::pair<std::size_t, std::size_t>> tasks;
  std::vector<bool> second;
  for (std::size_t s = 0; s < all.size(); ++s) {
    const GeometricWaves w = all[s].geometric();
    waves.direct.insert(waves.direct.end(), w.direct.begin(), w.direct.end());
    waves.specular.insert(waves.specular.end(), w.specular.begin(), w.specular.end());
    all[s].pathRange(&lo, &hi);
    for (std::size_t t = 0; t < all[s].tasks(); ++t) tasks.emplace_back(s, t), second.push_back(all[s].secondOrder(t));
  }
  const auto grids = gridTasks(second, lo, hi, axis.step_m, [&](std::size_t t, const auto& add) {
    all[tasks[t].first].run(tasks[t].second, axis.panel_wavelength_m, add);
  });
  return spectrumFields(wavenumbers_rad_m, waves, grids.first, order >= 2 ? &grids.second : nullptr);
}

}  // namespace diffray::reference
