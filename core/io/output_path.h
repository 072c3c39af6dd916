#pragma once
// Output paths are input too. Before any work, an output must be a path rtiow can write
// without losing anything: not empty, in an existing writable directory, not a directory
// or a device itself, not read-only to the user, not another user's file in a sticky
// directory (where the final rename would fail), not one of the command's input files
// (compared as files, not as strings), and, for images, one of the formats rtiow writes.
// Nothing here touches the file system beyond looking.

#include <string>
#include <vector>

namespace rtiow {

// An image format rtiow writes, chosen by the file extension (lower case, with the dot).
// Where a format keeps a render's provenance (core/render/render_metadata.h): every key as its
// own "rtiow:<key>" attribute (PNG text chunks, EXR attributes); all of them as one JSON object
// in the image description (JPEG's EXIF, TIFF's tag); or nowhere (HDR, PPM and BMP hold no
// text; TGA's comment field holds 320 characters, too few, and its version field reads back
// as a number that was never written).
enum class Provenance { Attributes, Description, None };

struct ImageFormat {
  const char* extension;
  bool linear_float;    // linear float pixels; otherwise 8-bit with the book's gamma 2
  bool extra_channels;  // can hold channels beyond R, G, B (--stats-channels, part files)
  bool own_encoder;     // encoded by rtiow itself (core/io/png_encoder.h), not the image library
  Provenance provenance;
  bool data_window;  // keeps a crop's place in the frame (a data window inside a display window)
};

// The format of `path`, or nullptr when rtiow does not write that extension.
const ImageFormat* image_format(const std::string& path);

// ".png .jpg .jpeg .ppm .bmp .tga .tif .tiff .exr .hdr", for messages and --help.
std::string image_extensions();

// Throws InvalidInput "<what> '<path>': <reason>" unless `path` may be written as described
// above; `inputs` are the files the command reads.
void check_output_path(const std::string& path, const std::vector<std::string>& inputs,
                       const char* what = "output");

// The marks of the files rtiow keeps beside an output NAME: its lock ".NAME" + kLockSuffix,
// its temporaries ".NAME" + kTemporaryMark + 8 letters, its checkpoint NAME + kCheckpointSuffix.
inline constexpr const char* kLockSuffix = ".rtiow-lock";
inline constexpr const char* kTemporaryMark = ".rtiow-tmp-";
inline constexpr const char* kCheckpointSuffix = ".rtiow-checkpoint";

// Whether a file name is one rtiow gives its own files beside an output: a lock
// (".NAME.rtiow-lock"), a temporary ("….rtiow-tmp-…") or a checkpoint ("NAME.rtiow-checkpoint").
// check_output_path refuses them: the next render of that image would replace or remove them.
bool is_own_file_name(const std::string& file_name);

// Where a render stopped short writes its image when the output holds a file it did not
// write: beside it, "cover.png" -> "cover.partial.png" (the extension kept, for the format).
std::string partial_output_path(const std::string& output);

// check_output_path, and the extension must name an image format (with extra channels
// when `extra_channels`).
void check_image_output(const std::string& path, const std::vector<std::string>& inputs,
                        bool extra_channels = false);

// A file name stem made from a scene name for a default output: letters, digits, '.', '_'
// and '-' only, no leading dot or dash, at most 64 characters, "render" when nothing is left.
std::string safe_file_stem(const std::string& scene_name);

// A directory rtiow will write files into (made if missing): not empty, and not a path that
// is something else. `what` names it in the error (an option such as "--out").
void check_output_directory(const std::string& path, const std::string& what);

}  // namespace rtiow
