// Placements of MuJoCo geoms as graspcd poses (collision_pose.h).
#include "graspcd/mujoco/collision_pose.h"

namespace graspcd::mujoco {

Mat3 from_row_major(const mjtNum* x) {
  Mat3 r;
  r << x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], x[8];
  return r;
}

// mju_isBad's test (x != x || x > mjMAXVAL || x < -mjMAXVAL) inline: a call into MuJoCo per
// number cost more than the test. A NaN fails both comparisons, so it is bad here too.
bool bad_geom_placement(const mjData* d, int g) {
  const mjtNum* pos = d->geom_xpos + 3 * g;
  const mjtNum* mat = d->geom_xmat + 9 * g;
  bool good = true;
  for (int k = 0; k < 3; ++k) good &= pos[k] >= -mjMAXVAL && pos[k] <= mjMAXVAL;
  for (int k = 0; k < 9; ++k) good &= mat[k] >= -mjMAXVAL && mat[k] <= mjMAXVAL;
  return !good;
}

Pose relative_pose(const mjData* d, int g1, int g2) {
  const Mat3 R1 = from_row_major(d->geom_xmat + 9 * g1);
  const Mat3 R2 = from_row_major(d->geom_xmat + 9 * g2);
  const Vec3 p1 = geom_position(d, g1);
  const Vec3 p2 = geom_position(d, g2);
  Pose pose;
  pose.R = R1.transpose() * R2;
  pose.t = R1.transpose() * (p2 - p1);
  return pose;
}

Vec3 geom_position(const mjData* d, int g) {
  return Vec3(d->geom_xpos[3 * g], d->geom_xpos[3 * g + 1], d->geom_xpos[3 * g + 2]);
}

}  // namespace graspcd::mujoco
