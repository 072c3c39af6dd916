#include "core/render/checkpoint_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <new>
#include <optional>
#include <stdexcept>
#include <variant>
#include <vector>

#include "core/io/checksum.h"
#include "core/limits/error.h"
#include "core/scene/scene_digest.h"
#include "core/version.h"

namespace rtiow {
namespace {

namespace fs = std::filesystem;

constexpr char kMagic[] = "rtiow-checkpoint 2\n";
constexpr std::size_t kMaxHeaderBytes = 1 << 16;
constexpr std::size_t kChunkBytes = 1 << 20;

// Fixed-size little-endian records (x86-64 and the other targets rtiow builds on are
// little-endian; the header's magic would not parse on a machine that disagreed).
template <typename T>
void put(std::vector<char>& out, const T& value) {
  const char* bytes = reinterpret_cast<const char*>(&value);
  out.insert(out.end(), bytes, bytes + sizeof(T));
}

template <typename T>
T take(const char*& in) {
  T value;
  std::memcpy(&value, in, sizeof(T));
  in += sizeof(T);
  return value;
}

void put_sum(std::vector<char>& out, const PixelSum& sum) {
  for (int c = 0; c < 3; ++c) {
    const auto v = uint128(sum.channel(c));
    put(out, std::uint64_t(v));
    put(out, std::uint64_t(v >> 64));
  }
}

PixelSum take_sum(const char*& in) {
  PixelSum sum;
  for (int c = 0; c < 3; ++c) {
    const auto low = take<std::uint64_t>(in), high = take<std::uint64_t>(in);
    sum.set_channel(c, int128((uint128(high) << 64) | low));
  }
  return sum;
}

std::size_t record_bytes(bool targets) {
  return 3 * 16 + 3 * 16 + 3 * 16 + 4 + 8 + (targets ? 4 : 0);
}

std::string exact(double v) {  // a double in text that reads back to the same bits
  char text[40];
  std::snprintf(text, sizeof text, "%a", v);
  return text;
}

std::string header_text(const CheckpointIdentity& id, const RenderState& state) {
  std::string h = kMagic;
  const auto line = [&](const char* key, const std::string& value) {
    h.append(key).append(" ").append(value).append("\n");
  };
  line("version", id.version);
  line("scene", id.scene);
  line("size", id.size);
  line("depth", id.depth);
  line("seed", id.seed);
  line("sampler", id.sampler);
  line("first_sample", id.first_sample);
  line("mode", id.mode);
  line("pixels", std::to_string(state.pixels.samples.size()));
  line("targets", state.targets.empty() ? "0" : "1");
  line("last_round", state.last_round ? "1" : "0");
  line("rays_traced", std::to_string(state.rays_traced));
  line("render_seconds", exact(state.render_seconds));
  line("estimated_image_error", exact(state.estimated_image_error));
  line("pixels_above_target", std::to_string(state.pixels_above_target));
  h.append("end\n");
  return h;
}

std::string system_reason(int error) {
  return std::strerror(error);
}

// Writes all of `data` to `fd`, adding it to `checksum`; false (errno set) on failure.
bool write_all(int fd, const char* data, std::size_t n, Checksum* checksum) {
  if (checksum) checksum->update(data, n);
  while (n > 0) {
    const ssize_t written = ::write(fd, data, n);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) return false;
    data += written;
    n -= std::size_t(written);
  }
  return true;
}

bool write_state(int fd, const CheckpointIdentity& identity, const RenderState& state) {
  Checksum checksum;
  const std::string header = header_text(identity, state);
  if (!write_all(fd, header.data(), header.size(), &checksum)) return false;
  const PixelAccumulators& p = state.pixels;
  const bool targets = !state.targets.empty();
  std::vector<char> chunk;
  chunk.reserve(kChunkBytes + record_bytes(true));
  for (std::size_t i = 0; i < p.samples.size(); ++i) {
    put_sum(chunk, p.sums[i]);
    put_sum(chunk, p.spreads[i].squares);
    put_sum(chunk, p.spreads[i].odd);
    put(chunk, p.samples[i]);
    put(chunk, p.rays[i]);
    if (targets) put(chunk, state.targets[i]);
    if (chunk.size() >= kChunkBytes || i + 1 == p.samples.size()) {
      if (!write_all(fd, chunk.data(), chunk.size(), &checksum)) return false;
      chunk.clear();
    }
  }
  const std::uint64_t sum = checksum.value();
  return write_all(fd, reinterpret_cast<const char*>(&sum), sizeof sum, nullptr);
}

// Reads exactly n bytes; false at the end of the file or on an error.
bool read_exact(int fd, char* data, std::size_t n) {
  while (n > 0) {
    const ssize_t got = ::read(fd, data, n);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) return false;
    data += got;
    n -= std::size_t(got);
  }
  return true;
}

class FileCloser {
 public:
  explicit FileCloser(int fd) : fd_(fd) {}
  ~FileCloser() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileCloser(const FileCloser&) = delete;
  FileCloser& operator=(const FileCloser&) = delete;

 private:
  int fd_;
};

// The header's lines up to "end", as key -> value; the bytes it took go to `checksum`.
std::map<std::string, std::string> read_header(int fd, const std::string& path,
                                               Checksum& checksum) {
  const auto bad = [&](const std::string& why) {
    return InvalidInput("checkpoint " + quote_value(path) + ": " + why +
                        " (not a checkpoint of this rtiow, or a damaged one: remove it)");
  };
  std::string text;
  char c = 0;
  while (text.size() < kMaxHeaderBytes && read_exact(fd, &c, 1)) {
    text.push_back(c);
    if (c == '\n' && text.size() >= 4 && text.compare(text.size() - 4, 4, "end\n") == 0) break;
  }
  if (text.rfind(kMagic, 0) != 0) {
    throw bad(text.rfind("rtiow-checkpoint ", 0) == 0 ? "a checkpoint of another format"
                                                      : "no checkpoint header");
  }
  if (text.size() < 4 || text.compare(text.size() - 4, 4, "end\n") != 0) {
    throw bad("the header does not end");
  }
  checksum.update(text.data(), text.size());
  std::map<std::string, std::string> fields;
  std::size_t at = std::strlen(kMagic);
  while (at < text.size()) {
    const std::size_t end = text.find('\n', at);
    const std::string line = text.substr(at, end - at);
    at = end + 1;
    if (line == "end") break;
    const std::size_t space = line.find(' ');
    if (space == std::string::npos) throw bad("a header line without a value");
    fields[line.substr(0, space)] = line.substr(space + 1);
  }
  return fields;
}

std::uint64_t field_number(const std::map<std::string, std::string>& fields, const char* key,
                           const std::string& path) {
  const auto it = fields.find(key);
  std::uint64_t value = 0;
  if (it != fields.end()) {
    const std::string& t = it->second;
    const auto [end, error] = std::from_chars(t.data(), t.data() + t.size(), value);
    if (error == std::errc() && end == t.data() + t.size()) return value;
  }
  throw InvalidInput("checkpoint " + quote_value(path) + ": header field " + key +
                     " is missing or not a whole number");
}

double field_double(const std::map<std::string, std::string>& fields, const char* key,
                    const std::string& path) {
  const auto it = fields.find(key);
  if (it != fields.end()) {
    char* end = nullptr;
    const double v = std::strtod(it->second.c_str(), &end);
    if (!it->second.empty() && *end == '\0') return v;
  }
  throw InvalidInput("checkpoint " + quote_value(path) + ": header field " + key +
                     " is missing or not a number");
}

CheckpointIdentity stored_identity(const std::map<std::string, std::string>& fields) {
  const auto get = [&](const char* key) {
    const auto it = fields.find(key);
    return it == fields.end() ? std::string("(none)") : it->second;
  };
  return {get("version"), get("scene"),   get("size"),         get("depth"),
          get("seed"),    get("sampler"), get("first_sample"), get("mode")};
}

}  // namespace

CheckpointIdentity checkpoint_identity(const Scene& scene, const RenderSettings& s) {
  // A uniform render continues to any count; an adaptive one only as it was asked.
  std::string mode = "uniform";
  if (const std::optional<int> least = least_samples(s.samples)) {
    const std::optional<int> asked = spp_option(s.samples);
    const std::string spp =
        asked ? " --spp " + std::to_string(*asked) : std::string(" (until the time limit)");
    const std::string min_spp = " --min-spp " + std::to_string(*least);
    char value[64];
    if (const auto* t = std::get_if<PixelErrorTarget>(&s.samples)) {
      std::snprintf(value, sizeof value, "--target-error %g", t->error);
    } else if (const auto* i = std::get_if<ImageErrorTarget>(&s.samples)) {
      std::snprintf(value, sizeof value, "--image-error %g", i->error);
    } else {
      std::snprintf(value, sizeof value, "--adaptive");
    }
    mode = value + min_spp + spp;
  }
  return {version(),
          scene_digest(scene),
          std::to_string(s.width) + "x" + std::to_string(s.height),
          std::to_string(s.max_depth),
          std::to_string(s.seed),
          to_string(s.sampler),
          std::to_string(s.first_sample),
          mode};
}

std::string identity_mismatch(const CheckpointIdentity& checkpoint, const CheckpointIdentity& now) {
  std::string text;
  const auto compare = [&](const char* what, const std::string& a, const std::string& b) {
    if (a == b) return;
    if (!text.empty()) text += "; ";
    text += std::string(what) + ": the checkpoint's " + quote_value(a, 60) + ", this render's " +
            quote_value(b, 60);
  };
  compare("rtiow version", checkpoint.version, now.version);
  compare("scene", checkpoint.scene, now.scene);
  compare("image size", checkpoint.size, now.size);
  compare("depth", checkpoint.depth, now.depth);
  compare("seed", checkpoint.seed, now.seed);
  compare("sampler", checkpoint.sampler, now.sampler);
  compare("first sample", checkpoint.first_sample, now.first_sample);
  compare("sampling", checkpoint.mode, now.mode);
  return text;
}

std::string checkpoint_path(const std::string& output) {
  return output + ".rtiow-checkpoint";
}

void write_checkpoint(const std::string& path, const CheckpointIdentity& identity,
                      const RenderState& state) {
  const fs::path target(path);
  std::string name = ".";
  name.append(target.filename().string()).append(".tmp-").append(std::to_string(::getpid()));
  const fs::path temporary = target.parent_path() / name;
  const auto fail = [&](int error) {
    ::unlink(temporary.c_str());
    throw std::runtime_error("cannot write the checkpoint " + quote_value(path) + ": " +
                             system_reason(error));
  };
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail(errno);
  bool written = false;
  try {
    written = write_state(fd, identity, state) && ::fsync(fd) == 0;
  } catch (const std::bad_alloc&) {
    ::close(fd);  // no temporary left behind, and the caller hears why
    fail(ENOMEM);
  }
  const int error = errno;
  if (::close(fd) != 0 && written) fail(errno);
  if (!written) fail(error);
  if (::rename(temporary.c_str(), target.c_str()) != 0) fail(errno);
  // The rename itself survives a power cut only once the directory is on the disk.
  const std::string dir = target.parent_path().empty() ? "." : target.parent_path().string();
  const int dir_fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir_fd >= 0) {
    ::fsync(dir_fd);
    ::close(dir_fd);
  }
}

std::optional<RenderState> read_checkpoint(const std::string& path,
                                           const CheckpointIdentity& expected) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0 && errno == ENOENT) return std::nullopt;
  if (fd < 0) {
    throw InvalidInput("checkpoint " + quote_value(path) + ": " + system_reason(errno));
  }
  const FileCloser closer(fd);
  Checksum checksum;
  const auto fields = read_header(fd, path, checksum);
  const std::string differs = identity_mismatch(stored_identity(fields), expected);
  if (!differs.empty()) {
    throw InvalidInput("checkpoint " + quote_value(path) + " is of another render (" + differs +
                       "): remove it, or render without --resume to replace it");
  }
  const std::uint64_t pixels = field_number(fields, "pixels", path);
  const int sep = int(expected.size.find('x'));
  const std::uint64_t expected_pixels = std::stoull(expected.size.substr(0, std::size_t(sep))) *
                                        std::stoull(expected.size.substr(std::size_t(sep) + 1));
  if (pixels != expected_pixels) {
    throw InvalidInput("checkpoint " + quote_value(path) + ": holds " + std::to_string(pixels) +
                       " pixels, not the image's " + std::to_string(expected_pixels));
  }
  RenderState state{std::size_t(pixels)};
  const bool targets = field_number(fields, "targets", path) != 0;
  if (targets) state.targets.resize(std::size_t(pixels));
  state.last_round = field_number(fields, "last_round", path) != 0;
  state.rays_traced = field_number(fields, "rays_traced", path);
  state.render_seconds = field_double(fields, "render_seconds", path);
  state.estimated_image_error = field_double(fields, "estimated_image_error", path);
  state.pixels_above_target = field_number(fields, "pixels_above_target", path);

  const auto truncated = [&] {
    return InvalidInput("checkpoint " + quote_value(path) +
                        ": ends before its pixels do (a damaged file: remove it)");
  };
  const std::size_t record = record_bytes(targets);
  const std::size_t per_chunk = kChunkBytes / record;
  std::vector<char> chunk(per_chunk * record);
  PixelAccumulators& p = state.pixels;
  for (std::size_t first = 0; first < pixels; first += per_chunk) {
    const std::size_t count = std::min<std::size_t>(per_chunk, std::size_t(pixels) - first);
    if (!read_exact(fd, chunk.data(), count * record)) throw truncated();
    checksum.update(chunk.data(), count * record);
    const char* in = chunk.data();
    for (std::size_t i = first; i < first + count; ++i) {
      p.sums[i] = take_sum(in);
      const PixelSum squares = take_sum(in);
      for (int c = 0; c < 3; ++c) p.spreads[i].squares.set_channel(c, squares.channel(c));
      p.spreads[i].odd = take_sum(in);
      p.samples[i] = take<std::uint32_t>(in);
      p.rays[i] = take<std::uint64_t>(in);
      if (targets) state.targets[i] = take<std::uint32_t>(in);
    }
  }
  std::uint64_t stored = 0;
  char extra = 0;
  if (!read_exact(fd, reinterpret_cast<char*>(&stored), sizeof stored)) throw truncated();
  if (stored != checksum.value() || read_exact(fd, &extra, 1)) {
    throw InvalidInput("checkpoint " + quote_value(path) +
                       ": its checksum does not match its content (a damaged file: remove it)");
  }
  return state;
}

}  // namespace rtiow
