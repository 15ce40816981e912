// The labels of an OpenSBP or Friendly Motion file: each name's line, found by its text.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "gantry/lang/script.hpp"  // Cursor

namespace gantry {

// Why not std::unordered_map<std::string, Cursor>: a node per label (the string, the cursor,
// the cached hash, the next pointer and the bucket) is about 88 bytes, and a 10M-line file
// of 2.5 M labels took 220 MB for them alone. Here a label is a 24-byte entry in chunked
// storage (nothing is copied as it grows, so no peak of twice the size), its name packed
// into pages, and the table is 4-byte slots at most 3/4 full: about 40 bytes a label.
//
// A name is interned when a jump names it, before its label is read, so the load pass keeps
// for a forward jump only the name's number (LabelIndex::Id), not its text.
class LabelIndex {
 public:
  using Id = uint32_t;

  // The number of `name`, added (not defined yet) when it is new.
  Id intern(std::string_view name);
  // Puts label `id` at `at`; false when it was defined before (that first one stays).
  bool define(Id id, Cursor at);
  // Where label `id` is, or nullopt while no line defines it.
  std::optional<Cursor> at(Id id) const;
  std::string_view name(Id id) const { return {entries_[id].name, entries_[id].size}; }
  // Where the label `name` is, or nullopt when it is not defined.
  std::optional<Cursor> find(std::string_view name) const;

 private:
  struct Entry {  // 24 bytes: a Cursor's fields, unpadded
    const char* name;
    size_t offset;
    uint32_t size;
    int line;  // 0: not defined yet (a label's cursor is the line after it, >= 2)
  };
  static constexpr uint32_t kEmpty = 0xFFFFFFFF;
  // The slot holding `name`, or the empty one where it would go.
  size_t slot(std::string_view name) const;
  const char* keep(std::string_view name);
  void grow();

  std::deque<Entry> entries_;
  std::vector<uint32_t> slots_;  // an entry's number, or kEmpty; a power of two of them
  std::vector<std::unique_ptr<char[]>> pages_;
  char* page_at_ = nullptr;
  size_t page_left_ = 0;
};

}  // namespace gantry
