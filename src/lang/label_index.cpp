// An open-addressed table over packed label names (label_index.hpp says why).
#include "label_index.hpp"

#include <algorithm>   // max
#include <cstring>     // memcpy
#include <functional>  // hash

namespace gantry {
namespace {
constexpr size_t kPage = size_t{1} << 16;  // bytes of names a page holds
}  // namespace

size_t LabelIndex::slot(std::string_view name) const {
  const size_t mask = slots_.size() - 1;
  const size_t hash = std::hash<std::string_view>{}(name);
  for (size_t i = hash & mask;; i = (i + 1) & mask)
    if (slots_[i] == kEmpty || this->name(slots_[i]) == name) return i;  // never full: grow
}

const char* LabelIndex::keep(std::string_view name) {
  if (name.size() > page_left_) {
    const size_t size = std::max(kPage, name.size());
    pages_.push_back(std::make_unique<char[]>(size));
    page_at_ = pages_.back().get();
    page_left_ = size;
  }
  char* at = page_at_;
  if (!name.empty()) std::memcpy(at, name.data(), name.size());
  page_at_ += name.size();
  page_left_ -= name.size();
  return at;
}

void LabelIndex::grow() {
  slots_.assign(std::max<size_t>(64, slots_.size() * 2), kEmpty);
  for (Id id = 0; id < entries_.size(); ++id) slots_[slot(name(id))] = id;
}

LabelIndex::Id LabelIndex::intern(std::string_view name) {
  if ((entries_.size() + 1) * 4 > slots_.size() * 3) grow();
  uint32_t& s = slots_[slot(name)];
  if (s == kEmpty) {
    s = static_cast<Id>(entries_.size());
    entries_.push_back({keep(name), 0, static_cast<uint32_t>(name.size()), 0});
  }
  return s;
}

bool LabelIndex::define(Id id, Cursor at) {
  Entry& e = entries_[id];
  if (e.line != 0) return false;
  e.offset = at.offset;
  e.line = at.line;
  return true;
}

std::optional<Cursor> LabelIndex::at(Id id) const {
  const Entry& e = entries_[id];
  if (e.line == 0) return std::nullopt;
  return Cursor{e.offset, e.line};
}

std::optional<Cursor> LabelIndex::find(std::string_view name) const {
  if (slots_.empty()) return std::nullopt;
  const uint32_t s = slots_[slot(name)];
  return s == kEmpty ? std::nullopt : at(s);
}

}  // namespace gantry
