#include "core/process_memory.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace scanstation {
namespace {

// After keep_freed_memory, a large block comes from the heap (glibc would
// otherwise map it on its own and unmap it on free), and once freed it stays
// in the heap as free space for the next allocation instead of going back to
// the kernel.
TEST(ProcessMemory, FreedLargeBlocksStayWithTheProcess) {
#if defined(__GLIBC__)
  ASSERT_TRUE(keep_freed_memory());
  constexpr std::size_t kBytes = std::size_t{48} << 20;
  const struct mallinfo2 before = mallinfo2();
  auto* volatile block = static_cast<char*>(std::malloc(kBytes));
  ASSERT_NE(block, nullptr);
  std::memset(block, 1, kBytes);
  const struct mallinfo2 holding = mallinfo2();
  EXPECT_EQ(holding.hblks, before.hblks) << "the block was mapped on its own";
  EXPECT_GE(holding.arena, before.arena + kBytes);
  std::free(block);
  const struct mallinfo2 after = mallinfo2();
  EXPECT_GE(after.fordblks, kBytes) << "the freed block left the heap";
  EXPECT_GE(after.arena, before.arena + kBytes) << "the heap was trimmed";
#else
  EXPECT_FALSE(keep_freed_memory());
#endif
}

}  // namespace
}  // namespace scanstation
