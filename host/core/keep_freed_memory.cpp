#include "host/core/keep_freed_memory.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace binpick {

void keep_freed_memory() {
#if defined(__GLIBC__)
  // A fixed threshold also stops glibc's own adjustment of both (it raises them only up to
  // 32 MB, below a 2064 x 1544 point image).
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
#endif
}

}  // namespace binpick
