// A tiny bitmap font for the labels of generated images (the illuminance legend's numbers): glyphs
// of 3 x 5 pixels, drawn scaled up into an 8-bit RGB buffer. Only what labels of numbers in lux
// need: digits, '.', '-', '+', 'e', 'l', 'x' and the space.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

namespace radfarm {

inline constexpr int kGlyphWidth = 3;
inline constexpr int kGlyphHeight = 5;

// An 8-bit RGB picture, rows top first.
struct Rgb8Image {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> rgb;  // width * height * 3

  void Fill(uint32_t x, uint32_t y, uint32_t w, uint32_t h, std::array<uint8_t, 3> colour);
};

// Whether the font has a glyph for c.
bool HasGlyph(char c);
// The glyph's rows, top first, each in its low 3 bits (bit 2 the left pixel); all zero without one.
std::array<uint8_t, kGlyphHeight> GlyphRows(char c);

// The width in pixels of `text` at `scale` (glyphs one scaled pixel apart).
uint32_t TextWidth(std::string_view text, int scale);
// Draws `text` with its top left at (x, y), clipped to the image.
void DrawText(Rgb8Image* image, uint32_t x, uint32_t y, std::string_view text, int scale,
              std::array<uint8_t, 3> colour);

}  // namespace radfarm
