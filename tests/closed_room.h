#pragma once
// A closed room for tests of the path loop: a hollow sphere of radius 50 around the origin
// (no light gets in, every ray hits), and one path traced from its centre, the camera's
// numbers drawn first as a render does.

#include <cstdint>
#include <limits>

#include "core/accel/naive_accel.h"
#include "core/render/integrator.h"
#include "core/sampling/sampler.h"
#include "core/scene/builtin_scenes.h"

namespace rtiow {

// The materials scene's settings with its spheres replaced by a room of `walls`.
inline Scene closed_room(const Material& walls) {
  Scene room = make_builtin_scene("materials", 1);
  room.spheres = SphereSet{};
  room.spheres.add({0, 0, 0}, 50.0f, room.add_material(walls));
  return room;
}

struct RoomPath {
  Color color;
  std::uint64_t rays = 1;  // the camera ray's included
  int dimensions = 0;      // how many the sample drew
};

// Sample `sample` of pixel (0, 0) with `kind`, traced from the centre toward -z for at most
// `depth` rays, with the Russian roulette or without.
inline RoomPath trace_from_centre(const Scene& room, const NaiveAccel& accel, SamplerKind kind,
                                  std::uint64_t sample, int depth, bool russian_roulette = true) {
  SampleStream rng(kind, 3, 0, 0, sample);
  const auto u = rng.next_camera();
  const Ray first{{0, 0, 0}, normalize(Vec3{u[0] - 0.5f, u[1] - 0.5f, -1.0f})};
  RoomPath path;
  path.color = continue_path(room, accel, first,
                             accel.intersect(first, std::numeric_limits<float>::infinity()), depth,
                             russian_roulette, rng, path.rays);
  path.dimensions = rng.dimension();
  return path;
}

}  // namespace rtiow
