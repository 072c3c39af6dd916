#pragma once
// `rtiow render --display HOST:PORT`: the render shown in the tev image viewer as it goes,
// over tev's own IPC protocol (TCP, port 14158 by default; what pbrt-v4's --display-server
// speaks), with the passes as more channels: the image is created once, at the frame's size, then
// its pixels are sent at each of the render's safe points and at the end. Only pixels leave rtiow;
// nothing is read back. A viewer that cannot be reached, or stops reading, costs the render a
// warning and at most a few seconds: the render goes on, and its files are as without --display.

#include <string>
#include <vector>

#include "core/film/film.h"
#include "core/io/image_output.h"

namespace rtiow {

// tev's default port, where HOST is given without one.
inline constexpr const char* kTevDefaultPort = "14158";

// The host and port of "HOST", "HOST:PORT" or "[IPV6]:PORT"; throws InvalidInput naming
// --display when it is none of these.
struct DisplayAddress {
  std::string host, port;
};
DisplayAddress parse_display_address(const std::string& text);

class TevDisplay {
 public:
  // Connects (within a few seconds) and creates the image `name`: R, G, B and the channels
  // `extra` names (the passes), the frame's size (`placement`; a crop shows in its place).
  // Fails with a warning on stderr, not an exception.
  TevDisplay(const DisplayAddress& address, std::string name, int film_width, int film_height,
             const FramePlacement& placement, std::vector<std::string> extra = {});
  ~TevDisplay();
  TevDisplay(const TevDisplay&) = delete;
  TevDisplay& operator=(const TevDisplay&) = delete;

  // Sends `film`'s pixels and the extra channels' (as many, in the order created); after a
  // failure (warned once) sends nothing more.
  void show(const Film& film, const std::vector<ExtraChannel>& extra = {});

 private:
  bool send_packet(const std::string& packet);
  void fail(const std::string& why);

  std::string where_;  // HOST:PORT, for messages
  std::string name_;
  FramePlacement placement_;
  std::vector<std::string> channels_;  // R, G, B, then the extra ones
  int socket_ = -1;
};

}  // namespace rtiow
