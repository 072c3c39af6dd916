#pragma once
// The provenance an image or part file carries: what was rendered, how, and how far it got,
// stored as "rtiow:<key>" attributes. The keys are named here once, because merging parts
// reads back what rendering wrote; the keys of the render's identity are its table's
// (core/render/render_identity.h), which also gives their values.

#include "core/io/image_output.h"
#include "core/render/render_identity.h"
#include "core/render/render_request.h"
#include "core/render/render_settings.h"
#include "core/scene/scene.h"

namespace rtiow::metadata_key {

inline constexpr const char* kScene = "scene";
inline constexpr const char* kSceneSeed = "scene_seed";
inline constexpr const char* kDepth = declaration_of(IdentityField::Depth).metadata_key;
inline constexpr const char* kSeed = declaration_of(IdentityField::Seed).metadata_key;
inline constexpr const char* kSampler = declaration_of(IdentityField::Sampler).metadata_key;
// How many independent replicates the samples alternate between: 2 where the render kept what
// an error estimate needs (absent in files of an older rtiow, which always kept two), 1 else.
inline constexpr const char* kReplicates = declaration_of(IdentityField::Replicates).metadata_key;
inline constexpr const char* kRussianRoulette =  // "on" or "off"
    declaration_of(IdentityField::Roulette).metadata_key;
inline constexpr const char* kAccelerator = "accelerator";
inline constexpr const char* kRaysTraced = "rays_traced";
inline constexpr const char* kSpp = "spp";                     // uniform sampling
inline constexpr const char* kSppRequested = "spp_requested";  // when stopped early
inline constexpr const char* kTargetError = "target_error";    // adaptive sampling...
inline constexpr const char* kImageError = "image_error";
// ...where they ended: the image's estimated relative RMS error (every render's that has one),
// the pixels left above the target at the cap.
inline constexpr const char* kEstimatedImageError = "estimated_image_error";
// What that estimate is worth: "calibrated", or "upper bound" (one Sobol sequence).
inline constexpr const char* kErrorEstimate = "error_estimate";
// --denoise: the denoised image's estimated relative RMS error and the noisy image's, both
// from the halves (core/denoise/denoiser.h).
inline constexpr const char* kDenoisedError = "denoise.estimated_error";
inline constexpr const char* kDenoisedNoisyError = "denoise.noisy_error";
inline constexpr const char* kPixelsAboveTarget = "pixels_above_target";
inline constexpr const char* kAdaptive = "adaptive";  // the budget mode: "sqrt(variance/cost)"
inline constexpr const char* kSppMin = "spp_min";     // the fewest a pixel took
inline constexpr const char* kMinSpp = "min_spp";     // the fewest a pixel could take (--min-spp)
inline constexpr const char* kSppMax = "spp_max";
inline constexpr const char* kSppMean = "spp_mean";
inline constexpr const char* kSppLimit = "spp_limit";
inline constexpr const char* kSppBudget = "spp_budget";  // --adaptive: the uniform spp it costs
inline constexpr const char* kStopped = "stopped";       // why it ended early
inline constexpr const char* kPreview = "preview";       // --preview: how far, as the render goes
inline constexpr const char* kRenderSeconds = "render_seconds";  // left out if reproducible
// What makes the render again, beyond the scene's name: rtiow's version, the digest of the
// scene rendered (core/scene_file/scene_digest.h: its spheres, materials, camera, sky and image
// settings), the camera used (after any override) and the glass's reflectance model.
inline constexpr const char* kVersion = declaration_of(IdentityField::Version).metadata_key;
inline constexpr const char* kSceneDigest = declaration_of(IdentityField::Scene).metadata_key;
inline constexpr const char* kCamera = "camera";
inline constexpr const char* kFresnel = "fresnel";
inline constexpr const char* kSceneFile = "scene_file";  // the file it was read from, if any
// A crop: its region as --crop takes it ("X0,Y0,X1,Y1") and the frame it is a region of
// ("WIDTHxHEIGHT"); the image's own size is the region's.
inline constexpr const char* kCrop = "crop";
inline constexpr const char* kFrame = "frame";
// The passes written beside the image (--passes), as it takes them: "albedo,normal,depth".
inline constexpr const char* kPasses = "passes";

}  // namespace rtiow::metadata_key

namespace rtiow {

// The metadata of a finished render. `reproducible` leaves out wall-clock time, so the same
// scene, settings and seed give a byte-identical file.
Metadata render_metadata(const Scene& scene, const RenderSettings& settings,
                         const RenderResult& result, bool reproducible);

// The camera as the metadata records it (kCamera), in the scene file's words and exact
// doubles: "lookfrom 13,2,3 lookat 0,0,0 vup 0,1,0 vfov 20 aperture 0.1 focus_distance 10".
std::string camera_record(const CameraSettings& camera);

// The camera a record gives, each setting at most once. Images of rtiow 0.3.0 spelt the same record
// as the render command's options then ("--lookfrom 13,2,3 ... --focus-dist 10"), which
// reads the same. Throws InvalidInput naming `source` and the setting at fault.
CameraOverrides read_camera_record(const std::string& record, const std::string& source);

// The crop the metadata of a `width` x `height` image records (kCrop, kFrame), as a place in
// the frame; the whole frame where it records none. Throws InvalidInput, naming `source`,
// where they cannot be read, the region does not fit the frame, or the image is not the
// region's size.
FramePlacement recorded_placement(const Metadata& metadata, const std::string& source, int width,
                                  int height);

}  // namespace rtiow
