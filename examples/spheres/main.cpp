// Three spheres on a ground, built in C++ and rendered through the API the rtiow command
// line uses: a Scene, RenderSettings, render(), write_image().
#include <cstdio>
#include <exception>

#include <rtiow/rtiow.h>

int main(int argc, char** argv) {
  const char* output = argc > 1 ? argv[1] : "three.png";
  try {
    rtiow::Scene scene;
    scene.name = "three spheres";
    const auto ground = scene.add_material(rtiow::Lambertian{{0.5f, 0.5f, 0.5f}});
    const auto glass = scene.add_material(rtiow::Dielectric{1.5f});
    const auto brown = scene.add_material(rtiow::Lambertian{{0.4f, 0.2f, 0.1f}});
    const auto steel = scene.add_material(rtiow::make_metal({0.7f, 0.6f, 0.5f}, 0.0f));
    scene.spheres.add({0, -1000, 0}, 1000, ground);
    scene.spheres.add({0, 1, 0}, 1, glass);
    scene.spheres.add({-4, 1, 0}, 1, brown);
    scene.spheres.add({4, 1, 0}, 1, steel);
    scene.camera.lookfrom = {13, 2, 3};
    scene.camera.lookat = {0, 0, 0};
    scene.camera.vfov_degrees = 20;  // a pinhole: no aperture, so no focus distance either

    // Left unset, a setting is the scene's, as in a scene file: here the height follows the
    // width and the scene's aspect ratio (16:9).
    rtiow::RenderSettings settings;
    settings.width = 400;
    settings.samples = rtiow::FixedSamples{32};
    settings.max_depth = 20;
    const rtiow::RenderResult result = rtiow::render(scene, settings);
    rtiow::write_image(output, result.film);
    std::printf("rendered %s: %dx%d, %d spp -> %s\n", scene.name.c_str(), result.film.width(),
                result.film.height(), result.samples_completed, output);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "spheres: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
