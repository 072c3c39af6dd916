#pragma once
// Cutting a big JSON document into pieces that several cores can parse at once. A scene file
// is mostly two top-level containers ("materials" and "spheres") of many small members; a
// scan that only follows strings and brackets finds where their members begin and end, and
// hands runs of whole members to be parsed apart. What is left (the skeleton: the document
// with those containers emptied) is small and parsed as before.
//
// The scan checks no syntax. That is sound because the parser checks every piece: if the
// skeleton parses, and every run parses as a container holding exactly the members the scan
// counted, then the document is the skeleton with valid member lists put back into empty
// containers, so it is valid, and on valid JSON the scan's structure is the true one. A caller
// that gets any error from a piece parses the whole document again in one piece, for the
// error the user sees.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace rtiow {

// Whole members of one split container, and the commas between them (not the brackets).
struct MemberRun {
  std::string key;          // the container's key in the root object
  bool is_object = false;   // its members are "key": value pairs
  std::uint64_t first = 0;  // the index of the run's first member in the container
  std::size_t members = 0;  // how many the scan counted
  std::string_view text;    // in its window's text
};

// What one window of input gives: its text (kept alive for as long as the runs are read, and
// the reader's to change: it may parse in place) and the runs of whole members in it, in
// document order.
struct SplitWindow {
  std::shared_ptr<std::string> text;
  std::vector<MemberRun> runs;
};

class JsonSplitter {
 public:
  // Fills `buffer` with up to `size` bytes and returns how many, 0 at the end.
  using Source = std::function<std::size_t(char* buffer, std::size_t size)>;

  // `split`: the root object's keys whose containers are cut, with the bracket each must
  // open with ('{' or '['); a container under such a key that opens otherwise is left whole.
  // Runs are cut at about `run_bytes`; the input is read `window_bytes` at a time, so memory
  // stays near a few windows whatever the document's size.
  JsonSplitter(std::map<std::string, char, std::less<>> split, std::size_t run_bytes,
               std::size_t window_bytes);

  // Reads the next window of `source` (at most `max_bytes` in all) and returns its runs; at
  // the end, `done` is set and `skeleton` holds the rest of the document. False when the
  // document is not one this scan can cut (a root that is not an object, a root key with an
  // escape, brackets that do not balance, a member or skeleton longer than the window or
  // 1 MiB, more than `max_bytes`).
  bool next(const Source& source, std::uint64_t max_bytes, SplitWindow& window, bool& done,
            std::string& skeleton);

 private:
  // Scans bytes [from, to) of the window; false when the document cannot be cut.
  bool scan(const std::string& window, std::size_t from, std::size_t to, std::string& skeleton);
  // The 64 bytes of a split container at i, at once; moves i past them, or to the block's first
  // byte that is not plain (a backslash, a run's end).
  void scan_block(const std::string& window, std::size_t& i, std::size_t& copied,
                  std::size_t& bytewise_until);
  // One byte of the root's structure, outside the split containers; false where the scene is
  // not one the scan can split (then it is read whole).
  bool root_byte(const std::string& window, std::size_t i, std::size_t copied,
                 std::string& skeleton);
  void end_run(const std::string& window, std::size_t end, bool last);
  // A bracket or comma outside strings inside a split container; true when it closes it.
  bool container_byte(const std::string& window, std::size_t at);

  // A window's buffer, taken from those its readers have let go of.
  std::shared_ptr<std::string> take_buffer();

  std::map<std::string, char, std::less<>> split_;
  std::size_t run_bytes_, window_bytes_;
  struct BufferPool;
  std::shared_ptr<BufferPool> pool_;

  std::string carry_;  // the open run's bytes at the end of the last window
  std::uint64_t total_ = 0;

  // Outside a split container.
  long depth_ = 0;
  bool in_string_ = false, escaped_ = false;
  bool expect_key_ = false;    // the next string at depth 1 is a root key
  bool in_key_ = false;        // inside a root key's string
  bool key_escaped_ = false;   // that key holds an escape (the scan does not decode them)
  bool expect_value_ = false;  // after a root key's ':' (the value has not begun)
  std::string key_;

  // Inside a split container.
  bool splitting_ = false;
  MemberRun container_;             // its key, kind and the next run's first index
  long inner_depth_ = 0;            // nesting inside the container
  std::size_t run_start_ = 0;       // where the open run starts in the window
  std::size_t run_commas_ = 0;      // top-level commas in it
  std::size_t last_comma_ = 0;      // the last of them (in the window) ...
  std::size_t commas_at_last_ = 0;  // ... and how many up to it
  std::vector<MemberRun> runs_;
};

}  // namespace rtiow
