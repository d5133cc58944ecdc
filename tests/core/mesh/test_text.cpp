// core/base/text.h: UTF-8 well-formedness (the Unicode Standard's Table 3-7), as glTF name repair and the command
// log's check use it, and printf_string.
#include <gtest/gtest.h>

#include <string>

#include "core/base/text.h"

namespace trispline::core {
namespace {

std::size_t length_at_0(const std::string& s) { return utf8_sequence_length(s, 0); }

TEST(Utf8, WellFormedSequencesHaveTheirLength) {
  EXPECT_EQ(length_at_0("a"), 1u);
  EXPECT_EQ(length_at_0("\xC2\x80"), 2u);          // U+0080, the first two-byte character
  EXPECT_EQ(length_at_0("\xDF\xBF"), 2u);          // U+07FF
  EXPECT_EQ(length_at_0("\xE0\xA0\x80"), 3u);      // U+0800
  EXPECT_EQ(length_at_0("\xED\x9F\xBF"), 3u);      // U+D7FF, below the surrogates
  EXPECT_EQ(length_at_0("\xEE\x80\x80"), 3u);      // U+E000, above them
  EXPECT_EQ(length_at_0("\xF0\x90\x80\x80"), 4u);  // U+10000
  EXPECT_EQ(length_at_0("\xF4\x8F\xBF\xBF"), 4u);  // U+10FFFF, the last code point
  EXPECT_EQ(utf8_sequence_length("ab\xC3\xAF", 2), 2u);
}

TEST(Utf8, IllFormedBytesStartNoSequence) {
  EXPECT_EQ(length_at_0("\x80"), 0u);              // a continuation byte alone
  EXPECT_EQ(length_at_0("\xC0\xAF"), 0u);          // overlong '/'
  EXPECT_EQ(length_at_0("\xC1\xBF"), 0u);          // overlong
  EXPECT_EQ(length_at_0("\xE0\x9F\xBF"), 0u);      // overlong three-byte form
  EXPECT_EQ(length_at_0("\xED\xA0\x80"), 0u);      // U+D800, a surrogate
  EXPECT_EQ(length_at_0("\xF0\x8F\xBF\xBF"), 0u);  // overlong four-byte form
  EXPECT_EQ(length_at_0("\xF4\x90\x80\x80"), 0u);  // above U+10FFFF
  EXPECT_EQ(length_at_0("\xF5\x80\x80\x80"), 0u);  // no such lead byte
  EXPECT_EQ(length_at_0("\xE2\x82"), 0u);          // the text ends inside the sequence
  EXPECT_EQ(length_at_0("\xE2\x28\xA1"), 0u);      // a bad continuation byte
  EXPECT_EQ(utf8_lead_length(0xE2), 3);
  EXPECT_EQ(utf8_lead_length(0xC1), 0);
}

TEST(PrintfString, FormatsAnyLength) {
  EXPECT_EQ(printf_string("frame_%04d", 7), "frame_0007");
  EXPECT_EQ(printf_string("%.6g", 0.1 + 0.2), "0.3");
  const std::string long_text(500, 'x');
  EXPECT_EQ(printf_string("<%s>", long_text.c_str()), "<" + long_text + ">");
  EXPECT_EQ(printf_string("%s", ""), "");
}

}  // namespace
}  // namespace trispline::core
