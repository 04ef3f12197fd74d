// Orthographic camera: chooses the view direction (automatic or from
// azimuth/elevation) and frames the projected mesh in the image.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "intrinsic/mesh.h"
#include "render/rasterizer.h"

namespace intrinsic::render {

struct Camera {
  Eigen::Vector3d right, up, forward;  // orthonormal; forward points into the screen
  Eigen::Vector3d centre;              // of the bounding sphere, already divided by radius
  double radius = 1;
  double scale = 1;           // samples per unit of (position / radius)
  double cx = 0, cy = 0;      // image centre in samples

  ScreenVertex project(const Eigen::Vector3d& p) const {
    // Divide before subtracting so huge coordinates cannot overflow.
    const Eigen::Vector3d q = p / radius - centre;
    return {cx + scale * q.dot(right), cy - scale * q.dot(up), q.dot(forward)};
  }
};

// Camera on the side the area-weighted mean normal points to, looking back
// along it; when the normals cancel (closed surfaces) a fixed oblique view.
struct ViewDirection {
  Eigen::Vector3d forward;  // where the camera looks
  Eigen::Vector3d right;    // screen x axis, perpendicular to forward
};

// World z is "up" unless the view is close to vertical; there z says nothing
// about the roll, so world y is "up" instead to keep the picture steady.
ViewDirection auto_view(const MatrixX3d& V, const MatrixX3i& F);
// Azimuth rotates about z; the roll follows the azimuth even straight down.
ViewDirection view_from_angles(double azimuth_deg, double elevation_deg);

Camera make_camera(const MatrixX3d& V, const MatrixX3i& F, const ViewDirection& view, int width, int height);

}  // namespace intrinsic::render
