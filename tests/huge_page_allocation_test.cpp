// The programs' operator new (core/parallel/huge_page_allocation.cpp), linked into this test
// as into rtiow: large blocks advised huge pages before their first touch, and the standard's
// failure path kept (the new-handler, then bad_alloc).

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <new>
#include <sstream>
#include <string>

namespace {

// The VmFlags of the mapping that holds `address` (/proc/self/smaps), or "" if none does.
std::string flags_of_mapping_at(const void* address) {
  const auto at = reinterpret_cast<std::uintptr_t>(address);
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::uintptr_t begin = 0, end = 0;
    char dash = 0;
    std::istringstream range(line);
    if (range >> std::hex >> begin >> dash >> end && dash == '-') {
      inside = begin <= at && at < end;
    } else if (inside && line.rfind("VmFlags:", 0) == 0) {
      return line;
    }
  }
  return "";
}

TEST(HugePageAllocation, LargeBlocksAreAdvisedHugePagesBeforeTheirFirstTouch) {
  if (!std::filesystem::exists("/sys/kernel/mm/transparent_hugepage/enabled"))
    GTEST_SKIP() << "this kernel has no transparent huge pages";
  constexpr std::size_t kBytes = std::size_t(64) << 20;
  const auto block = std::make_unique<char[]>(kBytes);
  // The 2 MB page in the middle lies inside the advised range whatever malloc's offset.
  const std::string flags = flags_of_mapping_at(block.get() + kBytes / 2);
  ASSERT_FALSE(flags.empty()) << "no mapping holds the block";
  EXPECT_NE(flags.find(" hg"), std::string::npos) << flags;
}

int handler_calls = 0;

TEST(HugePageAllocation, ItFailsAsTheStandardsOperatorNewDoes) {
  // No memory for it: the new-handler is called, and once none is left, bad_alloc.
  handler_calls = 0;
  std::set_new_handler([] {
    ++handler_calls;
    std::set_new_handler(nullptr);
  });
  constexpr std::size_t kImpossible = std::size_t(1) << 62;
  EXPECT_THROW(static_cast<void>(::operator new(kImpossible)), std::bad_alloc);
  EXPECT_EQ(handler_calls, 1);
  EXPECT_EQ(std::get_new_handler(), nullptr);
}

}  // namespace
