// SPDX-License-Identifier: LGPL-2.1-or-later
// The heap keeps a solve's freed blocks for the next solve instead of returning them to the
// kernel (whose pages would then be faulted in again).
#include <gtest/gtest.h>
#include <malloc.h>

#include <cstdlib>
#include <cstring>

#include "varsurf/core/heap_policy.hpp"

// AddressSanitizer brings its own allocator: mallopt and mallinfo2 then speak of glibc's idle heap.
#if defined(__SANITIZE_ADDRESS__)
#define VARSURF_OWN_ALLOCATOR 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define VARSURF_OWN_ALLOCATOR 1
#endif
#endif

TEST(HeapPolicy, FreedSolveSizedBlocksStayInTheProcess) {
#ifdef VARSURF_OWN_ALLOCATOR
  GTEST_SKIP() << "the sanitizer's allocator replaces glibc's heap";
#endif
  varsurf::keep_freed_heap();
  varsurf::keep_freed_heap();                 // idempotent
  constexpr size_t kBlock = size_t{4} << 20;  // the size of a 19 x 19 sheet's sample matrices
  const size_t mapped = mallinfo2().hblks;
  void* block = std::malloc(kBlock);
  ASSERT_NE(block, nullptr);
  std::memset(block, 1, kBlock);
  // glibc's default maps a block this size on its own (and unmaps it when freed).
  EXPECT_EQ(mallinfo2().hblks, mapped);
  std::free(block);
  // Freed, it stays in the heap: the heap's top is not trimmed back to the kernel.
  EXPECT_GE(mallinfo2().fordblks, kBlock);
}
