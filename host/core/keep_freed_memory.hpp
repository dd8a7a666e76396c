// The process keeps the memory it frees for its next allocations instead of handing it back.
#pragma once

namespace binpick {

// A detection allocates the same large buffers image after image (the point image alone is
// 16 bytes a pixel: 23 MB at 1600 x 900, 51 MB at 2064 x 1544). glibc serves such sizes with
// fresh mappings and returns them when freed, so every image paid a page fault for each 4 KiB
// of them, and the kernel zeroed each page. With this, freed blocks up to 256 MB stay in the
// heap and the next image's buffers reuse them (the process's peak memory stays as it was; it
// shrinks later). Call once at the start of main, before anything is allocated in threads.
// Does nothing without glibc.
void keep_freed_memory();

}  // namespace binpick
