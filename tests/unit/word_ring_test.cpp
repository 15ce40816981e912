// The cards' lock-free word queue (hal/word_ring.hpp): order across the wrap, what does not
// fit, and both ways of taking words (in place for gpiod, copied out for pci7200).
#include <gtest/gtest.h>

#include <cstdint>
#include <span>
#include <vector>

#include "gantry/hal/word_ring.hpp"

namespace gantry {
namespace {

TEST(WordRing, KeepsOrderAcrossTheWrapAndRefusesWhatDoesNotFit) {
  WordRing ring(16);
  std::vector<std::uint32_t> words(20);
  for (std::uint32_t i = 0; i < 20; ++i) words[i] = i;
  EXPECT_EQ(ring.push(words), 16u);
  EXPECT_EQ(ring.available(), 16u);
  EXPECT_EQ(ring.peek(15), 15u);
  ring.drop(10);
  EXPECT_EQ(ring.push(std::span(words).subspan(16)), 4u);  // wraps around the end
  EXPECT_EQ(ring.size(), 10u);
  for (std::uint32_t i = 0; i < 10; ++i) EXPECT_EQ(ring.peek(i), 10 + i);
  ring.clear();
  EXPECT_EQ(ring.available(), 0u);
}

TEST(WordRing, PopCopiesOutAcrossTheWrap) {
  WordRing ring(8);
  std::vector<std::uint32_t> words(12);
  for (std::uint32_t i = 0; i < 12; ++i) words[i] = 100 + i;
  EXPECT_EQ(ring.push(std::span(words).first(6)), 6u);
  std::vector<std::uint32_t> out(4);
  EXPECT_EQ(ring.pop(out), 4u);
  EXPECT_EQ(out, (std::vector<std::uint32_t>{100, 101, 102, 103}));
  EXPECT_EQ(ring.push(std::span(words).subspan(6)), 6u);  // 8 queued, across the end
  out.assign(10, 0);
  EXPECT_EQ(ring.pop(out), 8u);  // only what was published
  for (std::uint32_t i = 0; i < 8; ++i) EXPECT_EQ(out[i], 104 + i);
  EXPECT_EQ(ring.available(), 0u);
}

TEST(WordRing, RoundsItsCapacityUpToAPowerOfTwo) {
  EXPECT_EQ(WordRing(16).capacity(), 16u);
  EXPECT_EQ(WordRing(17).capacity(), 32u);
  EXPECT_EQ(WordRing(0).capacity(), 2u);
}

}  // namespace
}  // namespace gantry
