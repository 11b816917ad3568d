#include "sim/outlines.h"

#include "core/errors.h"
#include "sim/surface_of_revolution.h"

namespace scanstation::sim {

Polygon2 resample_closed(const Polygon2& polygon, int samples) {
  if (samples < 3 || polygon.size() < 3) throw InvalidInput("resample_closed: at least 3 vertices");
  Eigen::MatrixX2d open(polygon.size() + 1, 2);
  open << polygon.vertices, polygon.vertices.row(0);
  Polygon2 out;
  out.vertices = resample_polyline(open, samples + 1).topRows(samples);  // drop the repeated start
  return out;
}

Polygon2 chalice_outline(int samples) {
  if (samples < 8) throw InvalidInput("chalice outline: at least 8 samples");
  // The profile runs from the foot's centre out and up to the rim, then down
  // the inner wall to the bowl's floor; the right half walked that way and the
  // left half mirrored back give a counter-clockwise silhouette.
  const Eigen::MatrixX2d profile = chalice_profile(samples / 2 + 1);
  const Eigen::Index n = profile.rows();
  Polygon2 outline;
  outline.vertices.resize(2 * n - 2, 2);
  Eigen::Index k = 0;
  for (Eigen::Index i = 0; i < n; ++i) outline.vertices.row(k++) << profile(i, 0), profile(i, 1);
  for (Eigen::Index i = n - 2; i >= 1; --i) outline.vertices.row(k++) << -profile(i, 0), profile(i, 1);
  return outline;
}

Polygon2 face_profile_outline(int samples) {
  if (samples < 16) throw InvalidInput("face profile outline: at least 16 samples");
  // Key points (x forward, y up) counter-clockwise from the nape, facing +x.
  Eigen::MatrixX2d key(26, 2);
  key << -0.50, -0.50,  // nape of the neck
      -0.38, -1.10,     // back of the neck, bottom
      0.22, -1.10,      // front of the neck, bottom
      0.26, -0.70,      // throat
      0.50, -0.60,      // under the chin
      0.64, -0.52,      // chin
      0.60, -0.36,      // chin crease (concave)
      0.70, -0.26,      // lower lip
      0.62, -0.20,      // mouth (concave)
      0.70, -0.13,      // upper lip
      0.66, -0.04,      // under the nose (concave)
      0.92, 0.02,       // nose tip
      0.86, 0.10,       // nose
      0.70, 0.30,       // nose bridge
      0.64, 0.36,       // between the eyes (concave)
      0.72, 0.44,       // brow
      0.68, 0.60,       // forehead
      0.60, 0.80,       // hairline
      0.30, 1.00,       // crown front
      -0.10, 1.04,      // crown
      -0.45, 0.92,      // back of the head, top
      -0.68, 0.60,      // back of the head
      -0.74, 0.20,      // occiput
      -0.66, -0.12,     // above the nape
      -0.56, -0.30,     // nape, upper
      -0.52, -0.42;
  // One round of corner cutting (Chaikin) rounds the key polygon; the
  // concavities survive, only the corners soften.
  const Eigen::Index n = key.rows();
  Eigen::MatrixX2d cut(2 * n, 2);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::RowVector2d a = key.row(i), b = key.row((i + 1) % n);
    cut.row(2 * i) = 0.75 * a + 0.25 * b;
    cut.row(2 * i + 1) = 0.25 * a + 0.75 * b;
  }
  return resample_closed(Polygon2{cut}, samples);
}

}  // namespace scanstation::sim
