#pragma once
// `--display HOST:PORT`: the render shown in the tev image viewer as it goes, over tev's own IPC
// protocol (TCP, port 14158 by default; what pbrt-v4's --display-server speaks), with the passes
// as more channels: the image is created once, at the frame's size, then its pixels are sent at
// each of the render's safe points and at the end. Only pixels leave rtiow; nothing is read
// back.
//
// The viewer is served by a thread of its own, so it never holds the render: `show` copies the
// picture into one slot (replacing a picture not yet sent; at most that one and the one going
// out are held) and returns, and that thread finds the host, connects and sends. A host not
// found or reached within kViewerSeconds, or a viewer that takes longer than that over one
// picture, costs one warning and is dropped; the render goes on, and its files are as without
// --display. A resolver that never answers keeps only that thread, which the process leaves
// behind at its end.

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "core/film/film.h"
#include "core/io/image_output.h"

namespace rtiow {

// tev's default port, where HOST is given without one.
inline constexpr const char* kTevDefaultPort = "14158";

// What a viewer is given: to be found and connected, and to take each picture.
inline constexpr int kViewerSeconds = 5;

// The host and port of "HOST", "HOST:PORT" or "[IPV6]:PORT"; throws InvalidInput naming the
// `display` setting when it is none of these.
struct DisplayAddress {
  std::string host, port;
};
DisplayAddress parse_display_address(const std::string& text);

class TevDisplay {
 public:
  // Starts the viewer's thread, which connects and creates the image `name`: R, G, B and the
  // channels `extra` names (the passes), the frame's size (`placement`; a crop shows in its
  // place). Returns at once.
  TevDisplay(const DisplayAddress& address, std::string name, int film_width, int film_height,
             const FramePlacement& placement, std::vector<std::string> extra = {});
  // Ends the viewer's thread, dropping what it has not sent.
  ~TevDisplay();
  TevDisplay(const TevDisplay&) = delete;
  TevDisplay& operator=(const TevDisplay&) = delete;

  // Hands over `film`'s pixels and the extra channels' (as many, in the order created), to be
  // sent after the picture going out now; never waits for the viewer.
  void show(const Film& film, const std::vector<ExtraChannel>& extra = {});

  // Waits for the last picture shown to reach the viewer: at most kViewerSeconds, and no longer
  // once `stop` is set (a signal). A viewer that did not take it is warned about and dropped.
  void finish(const std::atomic<bool>& stop);

  struct Link;  // what the viewer's thread shares with this

 private:
  std::shared_ptr<Link> link_;
};

}  // namespace rtiow
