// The book's program on a small test scene, writing each pixel's mean and the variance of that
// mean (its samples are independent) instead of a PPM: what tests/book_program_test.cpp
// compares rtiow's image with, block by block. Built twice: as the book ships it (glibc's
// rand()), and as book_moments_mt19937 with a sound generator (BOOK_RANDOM_MT19937).
//
//   book_moments WIDTH HEIGHT SPP SEED METAL OUT [DEPTH]
//
// METAL is `book` (v3.2.3: mirror direction plus fuzz times a point in the unit ball) or
// `later` (a later edition's: the unit mirror direction plus fuzz times a unit vector). OUT
// gets WIDTH x HEIGHT records of six little-endian doubles (mean R G B, variance of the mean
// R G B), rows from the top. DEPTH is the book's max_depth (default 50). The scene is the one
// book_program_test.cpp builds in rtiow.

#include <cstdio>
#include <cstdlib>
#include <vector>

#include "rtweekend.h"

#include "camera.h"
#include "hittable_list.h"
#include "material.h"
#include "sphere.h"

namespace {

// A later edition's fuzzy metal, for the comparison's power.
class later_edition_metal : public material {
  public:
    later_edition_metal(const color& a, double f) : albedo(a), fuzz(f < 1 ? f : 1) {}

    bool scatter(const ray& r_in, const hit_record& rec, color& attenuation, ray& scattered)
    const override {
        vec3 reflected = unit_vector(reflect(r_in.direction(), rec.normal));
        scattered = ray(rec.p, reflected + fuzz * random_unit_vector());
        attenuation = albedo;
        return dot(scattered.direction(), rec.normal) > 0;
    }

  private:
    color albedo;
    double fuzz;
};

}  // namespace

int main(int argc, char** argv) {
    if (argc != 7 && argc != 8) {
        std::fprintf(stderr, "usage: book_moments WIDTH HEIGHT SPP SEED book|later OUT [DEPTH]\n");
        return 2;
    }
    const int width = std::atoi(argv[1]), height = std::atoi(argv[2]), spp = std::atoi(argv[3]);
    std::srand(unsigned(std::strtoul(argv[4], nullptr, 10)));
#ifdef BOOK_RANDOM_MT19937
    book_engine().seed(std::strtoull(argv[4], nullptr, 10));
#endif
    const bool later = std::string(argv[5]) == "later";

    hittable_list world;
    world.add(make_shared<sphere>(point3(0, -100.5, -1), 100, make_shared<lambertian>(color(0.5, 0.5, 0.5))));
    world.add(make_shared<sphere>(point3(-1.05, 0, -1.2), 0.5, make_shared<lambertian>(color(0.1, 0.2, 0.5))));
    world.add(make_shared<sphere>(point3(0.15, 0, -1.5), 0.5, make_shared<dielectric>(1.5)));
    const color gold(0.8, 0.6, 0.2);
    shared_ptr<material> fuzzy;
    if (later) fuzzy = make_shared<later_edition_metal>(gold, 0.6);
    else fuzzy = make_shared<metal>(gold, 0.6);
    world.add(make_shared<sphere>(point3(0.9, -0.1, -0.9), 0.4, fuzzy));

    camera cam;
    cam.aspect_ratio = double(width) / height;
    cam.image_width = width;
    cam.samples_per_pixel = spp;
    cam.max_depth = argc == 8 ? std::atoi(argv[7]) : 50;
    cam.vfov = 70;
    cam.lookfrom = point3(0, 0.3, 0.6);
    cam.lookat = point3(0, -0.05, -1);
    cam.vup = vec3(0, 1, 0);
    cam.initialize();
    if (cam.image_height != height) {
        std::fprintf(stderr, "book_moments: height %d, the book's camera makes %d\n", height, cam.image_height);
        return 2;
    }

    std::vector<double> out;
    out.reserve(std::size_t(width) * std::size_t(height) * 6);
    for (int j = 0; j < height; ++j) {
        for (int i = 0; i < width; ++i) {
            color sum(0, 0, 0), squares(0, 0, 0);
            for (int s = 0; s < spp; ++s) {
                const color c = cam.ray_color(cam.get_ray(i, j), cam.max_depth, world);
                sum += c;
                squares += c * c;
            }
            for (int k = 0; k < 3; ++k) out.push_back(sum[k] / spp);
            for (int k = 0; k < 3; ++k) {
                const double mean = sum[k] / spp;
                out.push_back((squares[k] / spp - mean * mean) * spp / (spp - 1) / spp);
            }
        }
    }
    std::FILE* f = std::fopen(argv[6], "wb");
    if (!f || std::fwrite(out.data(), sizeof(double), out.size(), f) != out.size() || std::fclose(f) != 0) {
        std::perror(argv[6]);
        return 1;
    }
    return 0;
}
