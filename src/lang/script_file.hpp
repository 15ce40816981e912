// A part file on disk read in 64 KiB blocks, each checked against the hash of its first read,
// the most recently used blocks kept so that a jump or RETURN anywhere costs no read.
#pragma once

#include <cstddef>
#include <cstdint>
#include <ctime>  // timespec
#include <memory>
#include <optional>
#include <string_view>
#include <utility>  // swap
#include <vector>

namespace gantry {

// Why blocks read with pread and not a memory map of the file: a map is no snapshot. Linux
// shows a MAP_PRIVATE page that was not written by us as the file is now, so bytes checked by
// the load pass could change under a run unseen; and a file truncated while mapped (a CAM
// program exporting again to the same name opens it with O_TRUNC) makes every later access
// past its new end a SIGBUS, killing the controller in the middle of a cut, or needing a
// process-wide signal handler around every read of a line (the parsers read the views too).
// A block read from the file is a private copy: it cannot change or vanish, and each read
// from the disk is verified (size, modification time, the block's hash), as before. What the
// map would have given, no line read twice from the kernel while it is in use, the cache
// gives: a GOSUB loop touches a few blocks, and they stay.
class ScriptFile {
 public:
  static constexpr size_t kBlock = size_t{1} << 16;  // bytes per hash and per read
  // Blocks kept: 1 MiB, the memory of the single window this cache replaced.
  static constexpr size_t kSlots = 16;

  // Takes `fd` (closed by the destructor), a regular file of `size` bytes last modified at
  // `mtime` when it was opened.
  ScriptFile(int fd, size_t size, timespec mtime);
  ~ScriptFile();
  ScriptFile(const ScriptFile&) = delete;
  ScriptFile& operator=(const ScriptFile&) = delete;

  size_t size() const { return size_; }
  // The bytes of block `index` (kBlock of them, fewer in the last block, none past the end):
  // valid until the next call. nullopt when the file is no longer the one first read (its
  // size or modification time differ, or this block's bytes hash differently).
  std::optional<std::string_view> block(size_t index) {
    if (index == last_->index) return std::string_view(last_->bytes.get(), last_->size);
    if (index == prev_->index) {  // a GOSUB's RETURN, or the next GOSUB: no search
      std::swap(last_, prev_);
      last_start_ = index * kBlock;
      last_->used = ++clock_;
      return std::string_view(last_->bytes.get(), last_->size);
    }
    return find_or_read(index);
  }
  // The block `block` gave last (none before the first and after a failed read) and its offset
  // in the file: the fast path of Script::line_at.
  std::string_view last() const { return {last_->bytes.get(), last_->size}; }
  size_t last_start() const { return last_start_; }

 private:
  struct Slot {
    size_t index = SIZE_MAX;  // the block held; SIZE_MAX: none
    size_t size = 0;
    std::uint64_t used = 0;  // when last looked up: the least recent is read over
    std::unique_ptr<char[]> bytes;
  };
  std::optional<std::string_view> find_or_read(size_t index);
  bool read(Slot& slot, size_t index);  // false: the file changed

  int fd_;
  size_t size_;
  timespec mtime_;
  std::vector<std::uint64_t> hashes_;  // per block; 0: not read yet
  std::vector<Slot> slots_;            // up to kSlots, allocated as first used
  Slot none_;                          // last_ before any read
  Slot* last_ = &none_;
  Slot* prev_ = &none_;  // the block given before last_
  size_t last_start_ = 0;
  std::uint64_t clock_ = 0;
};

}  // namespace gantry
