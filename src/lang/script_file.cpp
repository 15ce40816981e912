// The block cache of a part file read from disk, each read verified against the first.
#include "script_file.hpp"

#include <algorithm>

#include <sys/stat.h>  // fstat: the file's size and modification time
#include <unistd.h>    // pread, close
#include <xxhash.h>    // XXH3_64bits: the blocks' hashes

namespace gantry {

ScriptFile::ScriptFile(int fd, size_t size, timespec mtime)
    : fd_(fd), size_(size), mtime_(mtime), hashes_((size + kBlock - 1) / kBlock, 0) {
  slots_.reserve(kSlots);  // last_ points into it: never reallocated
}

ScriptFile::~ScriptFile() {
  if (fd_ >= 0) ::close(fd_);
}

std::optional<std::string_view> ScriptFile::find_or_read(size_t index) {
  Slot* slot = nullptr;
  for (Slot& s : slots_)
    if (s.index == index) {
      slot = &s;
      break;
    }
  if (!slot) {
    if (slots_.size() < kSlots) {
      slot = &slots_.emplace_back();
    } else {
      slot = &*std::min_element(slots_.begin(), slots_.end(),
                                [](const Slot& a, const Slot& b) { return a.used < b.used; });
    }
    if (!read(*slot, index)) {
      last_ = prev_ = &none_;
      return std::nullopt;
    }
  }
  slot->used = ++clock_;
  prev_ = last_ == slot ? &none_ : last_;
  last_ = slot;
  last_start_ = index * kBlock;
  return std::string_view(slot->bytes.get(), slot->size);
}

bool ScriptFile::read(Slot& slot, size_t index) {
  slot.index = SIZE_MAX;
  const size_t begin = std::min(index * kBlock, size_);
  const size_t want = std::min(kBlock, size_ - begin);
  // No zero fill: room for any block of this file, allocated once per slot.
  if (!slot.bytes)
    slot.bytes = std::make_unique_for_overwrite<char[]>(std::clamp(size_, size_t{1}, kBlock));
  size_t got = 0;
  while (got < want) {
    const ssize_t n =
        ::pread(fd_, slot.bytes.get() + got, want - got, static_cast<off_t>(begin + got));
    if (n <= 0) break;
    got += static_cast<size_t>(n);
  }
  struct stat st {};
  if (got != want || ::fstat(fd_, &st) != 0 || static_cast<size_t>(st.st_size) != size_ ||
      st.st_mtim.tv_sec != mtime_.tv_sec || st.st_mtim.tv_nsec != mtime_.tv_nsec)
    return false;
  if (want > 0) {
    // The first read of a block records its hash (|1: never 0), every later one compares.
    const std::uint64_t h = XXH3_64bits(slot.bytes.get(), want) | 1u;
    std::uint64_t& known = hashes_[index];
    if (known == 0) known = h;
    if (known != h) return false;
  }
  slot.index = index;
  slot.size = want;
  return true;
}

}  // namespace gantry
