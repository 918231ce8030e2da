#include "generator/models/weber_penn/weber_penn_leaves.h"

#include <algorithm>
#include <cmath>

#include "common/fast_trig.h"
#include "common/frame.h"

namespace arbor::generator::wp {

void orient_toward_light(float bend, float at_x, float at_y, glm::vec3& axis, glm::vec3& normal) {
  if (bend == 0.0f) return;
  if (at_x != 0.0f || at_y != 0.0f) {
    const float nx = normal.x, ny = normal.y;
    const float theta_bend = nx == 0.0f && ny == 0.0f
                                 ? fast_atan2(at_y, at_x)
                                 : fast_atan2(nx * at_y - ny * at_x, nx * at_x + ny * at_y);
    float c = 1.0f, s = 0.0f;
    fast_sincos(bend * theta_bend, s, c);
    // About the vertical: x toward y, z unchanged.
    axis = glm::vec3(c * axis.x - s * axis.y, s * axis.x + c * axis.y, axis.z);
    normal = glm::vec3(c * normal.x - s * normal.y, s * normal.x + c * normal.y, normal.z);
  }
  const float horizontal = std::sqrt(normal.x * normal.x + normal.y * normal.y);
  if (horizontal < 1e-12f) return;
  const float phi_bend = fast_atan2(horizontal, normal.z);
  const glm::vec3 across = glm::vec3(normal.y, -normal.x, 0.0f) / horizontal;  // normal × up
  float c = 1.0f, s = 0.0f;
  fast_sincos(bend * phi_bend, s, c);
  axis = rotate(axis, across, c, s);
  normal = rotate(normal, across, c, s);
}

namespace {

constexpr std::size_t kBlock = LeafOrienter::kBlock;  // 13 + 6 streams of it: 19 KiB

// orient_leaves on one block in structure-of-arrays form, stream k of `in` at in[k * kBlock]: the
// frame x, y, z (9 streams), turn, down, the position's x and y; `out`: axis and normal. Without
// branches, so that the compiler vectorises the loop (this file is built with -fno-math-errno and
// -fno-trapping-math, which vectorising sqrt and if-converting need); each lane computes what
// orient_toward_light computes for its leaf, operation for operation, so the bits are the same.
// Without bend (LeafBend 0) the leaves keep their frames, as orient_toward_light returns at once.
template <bool kBend>
void orient_block(const float* __restrict in, float* __restrict out, float bend, std::size_t m) {
  constexpr std::size_t n = kBlock;
  for (std::size_t i = 0; i < m; ++i) {
    const float xx = in[i], xy = in[n + i], xz = in[2 * n + i];
    const float yx = in[3 * n + i], yy = in[4 * n + i], yz = in[5 * n + i];
    const float zx = in[6 * n + i], zy = in[7 * n + i], zz = in[8 * n + i];
    const float turn = in[9 * n + i], down = in[10 * n + i], px = in[11 * n + i],
                py = in[12 * n + i];
    float st = 0.0f, ct = 1.0f, sd = 0.0f, cd = 1.0f;
    fast_sincos(turn, st, ct);
    fast_sincos(down, sd, cd);
    const float tx = ct * yx - st * xx, ty = ct * yy - st * xy, tz = ct * yz - st * xz;
    float ax = cd * zx - sd * tx, ay = cd * zy - sd * ty, az = cd * zz - sd * tz;
    float nx = cd * tx + sd * zx, ny = cd * ty + sd * zy, nz = cd * tz + sd * zz;
    if (!kBend) {
      out[i] = ax, out[n + i] = ay, out[2 * n + i] = az;
      out[3 * n + i] = nx, out[4 * n + i] = ny, out[5 * n + i] = nz;
      continue;
    }
    // About the vertical by bend·θ (none for a leaf on the axis).
    const bool vertical = (nx == 0.0f) & (ny == 0.0f), centred = (px == 0.0f) & (py == 0.0f);
    const float theta =
        fast_atan2(vertical ? py : nx * py - ny * px, vertical ? px : nx * px + ny * py);
    float s = 0.0f, c = 1.0f;
    fast_sincos(bend * theta, s, c);
    const float ax1 = c * ax - s * ay, ay1 = s * ax + c * ay;
    const float nx1 = c * nx - s * ny, ny1 = s * nx + c * ny;
    ax = centred ? ax : ax1, ay = centred ? ay : ay1;
    nx = centred ? nx : nx1, ny = centred ? ny : ny1;
    // Across the normal by bend·φ (none for a level leaf).
    const float horizontal = std::sqrt(nx * nx + ny * ny);
    const bool level = horizontal < 1e-12f;
    const float phi = fast_atan2(horizontal, nz);
    const float h = level ? 1.0f : horizontal;
    const float ux = ny / h, uy = -nx / h, uz = 0.0f;  // normal × up, normalised
    fast_sincos(bend * phi, s, c);
    // Rodrigues' formula as common/frame.h's rotate writes it.
    // A level leaf keeps its vectors as they are (selected, not recomputed: zeros keep their sign).
    auto turn_about = [&](float& vx, float& vy, float& vz) {
      const float cx = uy * vz - uz * vy, cy = uz * vx - ux * vz, cz = ux * vy - uy * vx;
      const float dot = ux * vx + uy * vy + uz * vz;
      const float rx = vx * c + cx * s + ux * dot * (1.0f - c);
      const float ry = vy * c + cy * s + uy * dot * (1.0f - c);
      const float rz = vz * c + cz * s + uz * dot * (1.0f - c);
      vx = level ? vx : rx, vy = level ? vy : ry, vz = level ? vz : rz;
    };
    turn_about(ax, ay, az);
    turn_about(nx, ny, nz);
    out[i] = ax, out[n + i] = ay, out[2 * n + i] = az;
    out[3 * n + i] = nx, out[4 * n + i] = ny, out[5 * n + i] = nz;
  }
}

}  // namespace

void LeafOrienter::flush() {
  for (std::size_t j = 0; j < count_; ++j) {
    in_[11 * kBlock + j] = leaves_[first_ + j].position.x;
    in_[12 * kBlock + j] = leaves_[first_ + j].position.y;
  }
  if (bend_ == 0.0f)
    orient_block<false>(in_.data(), out_.data(), bend_, count_);
  else
    orient_block<true>(in_.data(), out_.data(), bend_, count_);
  for (std::size_t j = 0; j < count_; ++j) {
    Leaf& leaf = leaves_[first_ + j];
    leaf.axis = {out_[j], out_[kBlock + j], out_[2 * kBlock + j]};
    leaf.normal = {out_[3 * kBlock + j], out_[4 * kBlock + j], out_[5 * kBlock + j]};
  }
  first_ += count_;
  count_ = 0;
}

}  // namespace arbor::generator::wp
