// A peer never holds the render (issue 69): a viewer given with --display that stalls or
// crawls, or whose name the resolver never answers for, costs one warning and at most the
// viewer's allowance after the render, never render time, and never delays a signal's stop.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sched.h>
#include <sys/mount.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/cli_helpers.h"
#include "tests/fake_viewer.h"

namespace {

using namespace rtiow::test::cli;
using rtiow::test::FakeTev;
using rtiow::test::ViewerPace;
using rtiow::test::words;

// A render whose pictures (600x400, ten channels: about 9.6 MB) are more than the kernel buffers
// between rtiow and a viewer that does not read, shown at every safe point.
std::string displayed_render(int port, const fs::path& out, const fs::path& summary) {
  return "render -q --scene cover --width 600 --height 400 --spp 4 --passes albedo,normal,depth "
         "--preview 0.001 --display 127.0.0.1:" +
         std::to_string(port) + " -o " + out.string() + " --summary-json " + summary.string();
}

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// A viewer that accepts and never reads: the render is whole, its time is its own (the wait for
// the viewer comes after it, in the command's time), and one warning says the viewer was dropped.
TEST(SlowPeers, AViewerThatNeverReadsHoldsNeitherTheRenderNorItsTime) {
  FakeTev viewer(ViewerPace::Never);
  ASSERT_GT(viewer.port(), 0);
  const fs::path dir = empty_output_dir(test_name());
  const fs::path out = dir / "stalled.exr", summary = dir / "stalled.json";
  const CommandResult r = run_rtiow(displayed_render(viewer.port(), out, summary));
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_TRUE(fs::exists(out));
  EXPECT_EQ(count_lines(r.stderr_text), 1) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("warning: --display '127.0.0.1:" + std::to_string(viewer.port()) +
                               "': the viewer"),
            std::string::npos)
      << r.stderr_text;
  // The render's own time (about 1 s here; its previews at every safe point included): before
  // the change the first picture held it for the viewer's whole 5 s.
  const nlohmann::json s = read_json(summary);
  EXPECT_LT(s["render_seconds"].get<double>(), 5.0) << s.dump();
}

// A viewer that reads 4 KB every half second would take minutes over one picture: it is dropped
// after its allowance and the command ends.
TEST(SlowPeers, ACrawlingViewerIsDroppedAfterItsAllowance) {
  FakeTev viewer(ViewerPace::Crawling);
  ASSERT_GT(viewer.port(), 0);
  const fs::path dir = empty_output_dir(test_name());
  const fs::path out = dir / "crawled.exr", summary = dir / "crawled.json";
  BackgroundRender render(words(displayed_render(viewer.port(), out, summary)));
  ASSERT_EQ(render.wait(60), 0) << render.stderr_text();
  EXPECT_TRUE(fs::exists(out));
  EXPECT_NE(render.stderr_text().find("the viewer took more than 5 s over one picture"),
            std::string::npos)
      << render.stderr_text();
}

// A signal while the viewer stalls stops the render as without a viewer: the render is kept,
// and nothing waits for the viewer's allowance.
TEST(SlowPeers, ASignalIsNotHeldByAStalledViewer) {
  FakeTev viewer(ViewerPace::Never);
  ASSERT_GT(viewer.port(), 0);
  const fs::path out = empty_output_dir(test_name()) / "signalled.exr";
  BackgroundRender render(
      words("render -q --scene cover --width 600 --height 400 --spp 100000 "
            "--passes albedo,normal,depth --preview 0.001 --display "
            "127.0.0.1:" +
            std::to_string(viewer.port()) + " -o " + out.string()));
  ASSERT_TRUE(render.wait_until_rendering());
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // a picture or two handed over
  render.signal(SIGTERM);
  // Well inside the viewer's 5 s: before the change the stop waited for the send's timeout.
  EXPECT_EQ(render.wait(3.0), 128 + SIGTERM) << render.stderr_text();
  EXPECT_NE(render.stderr_text().find("rtiow: interrupted: "), std::string::npos)
      << render.stderr_text();
}

// A host whose resolver never answers (a name server at 127.0.0.77 that takes every query and
// answers none, put in /etc/resolv.conf for rtiow alone in a mount namespace of its own): the
// render starts and ends as without --display, then the viewer is given up after its allowance.
// Needs root (a mount namespace); skipped elsewhere.
TEST(SlowPeers, ASilentResolverDoesNotHoldTheStart) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root for a mount namespace";
  const int silent = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(53);
  address.sin_addr.s_addr = htonl(0x7f00004d);  // 127.0.0.77
  if (::bind(silent, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
    ::close(silent);
    GTEST_SKIP() << "cannot bind 127.0.0.77:53";
  }
  const fs::path resolv = output_path("silent-resolv.conf");
  std::ofstream(resolv) << "nameserver 127.0.0.77\noptions timeout:5 attempts:3\n";
  const fs::path dir = empty_output_dir(test_name());
  const fs::path out = dir / "unresolved.png", summary = dir / "unresolved.json";
  const fs::path err = output_path("unresolved.stderr");
  std::vector<std::string> args = {RTIOW_BINARY,
                                   "render",
                                   "-q",
                                   "--scene",
                                   "cover",
                                   "--width",
                                   "64",
                                   "--spp",
                                   "2",
                                   "--display",
                                   "viewer.invalid:14158",
                                   "-o",
                                   out.string(),
                                   "--summary-json",
                                   summary.string()};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const auto started = std::chrono::steady_clock::now();
  const pid_t child = ::fork();
  if (child == 0) {  // only system calls from here to exec
    const int fd = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0 || ::dup2(fd, 2) < 0 || ::unshare(CLONE_NEWNS) != 0 ||
        ::mount(nullptr, "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0 ||
        ::mount(resolv.c_str(), "/etc/resolv.conf", nullptr, MS_BIND, nullptr) != 0) {
      ::_exit(125);
    }
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  ::close(silent);
  ASSERT_TRUE(WIFEXITED(status));
  if (WEXITSTATUS(status) == 125) GTEST_SKIP() << "no mount namespace to be had here";
  const std::string stderr_text = slurp(err);
  ASSERT_EQ(WEXITSTATUS(status), 0) << stderr_text;
  EXPECT_TRUE(fs::exists(out));
  EXPECT_NE(stderr_text.find("warning: --display 'viewer.invalid:14158': finding it took more "
                             "than 5 s (its resolver did not answer); nothing was shown"),
            std::string::npos)
      << stderr_text;
  // The resolver's own timeouts (5 s, three tries) would hold a waiting render 15 s: the
  // command ends after the viewer's allowance.
  EXPECT_LT(seconds, 12.0) << stderr_text;
  const nlohmann::json s = read_json(summary);
  EXPECT_LT(s["render_seconds"].get<double>(), s["seconds"].get<double>() - 4.0) << s.dump();
}

}  // namespace
