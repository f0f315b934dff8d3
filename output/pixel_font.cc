#include "output/pixel_font.h"

namespace radfarm {

void Rgb8Image::Fill(uint32_t x, uint32_t y, uint32_t w, uint32_t h,
                     std::array<uint8_t, 3> colour) {
  for (uint32_t row = y; row < y + h && row < height; ++row) {
    for (uint32_t col = x; col < x + w && col < width; ++col) {
      const size_t at = (size_t(row) * width + col) * 3;
      rgb[at] = colour[0], rgb[at + 1] = colour[1], rgb[at + 2] = colour[2];
    }
  }
}

std::array<uint8_t, kGlyphHeight> GlyphRows(char c) {
  switch (c) {
    case '0':
      return {7, 5, 5, 5, 7};
    case '1':
      return {2, 6, 2, 2, 7};
    case '2':
      return {7, 1, 7, 4, 7};
    case '3':
      return {7, 1, 7, 1, 7};
    case '4':
      return {5, 5, 7, 1, 1};
    case '5':
      return {7, 4, 7, 1, 7};
    case '6':
      return {7, 4, 7, 5, 7};
    case '7':
      return {7, 1, 1, 2, 2};
    case '8':
      return {7, 5, 7, 5, 7};
    case '9':
      return {7, 5, 7, 1, 7};
    case '.':
      return {0, 0, 0, 0, 2};
    case '-':
      return {0, 0, 7, 0, 0};
    case '+':
      return {0, 2, 7, 2, 0};
    case 'e':
      return {0, 7, 7, 4, 7};
    case 'l':
      return {6, 2, 2, 2, 7};
    case 'x':
      return {0, 5, 2, 5, 5};
    default:
      return {0, 0, 0, 0, 0};
  }
}

bool HasGlyph(char c) {
  if (c == ' ') return true;
  for (uint8_t row : GlyphRows(c)) {
    if (row != 0) return true;
  }
  return false;
}

uint32_t TextWidth(std::string_view text, int scale) {
  if (text.empty()) return 0;
  return uint32_t(text.size() * (kGlyphWidth + 1) - 1) * uint32_t(scale);
}

void DrawText(Rgb8Image* image, uint32_t x, uint32_t y, std::string_view text, int scale,
              std::array<uint8_t, 3> colour) {
  const uint32_t s = uint32_t(scale);
  for (size_t k = 0; k < text.size(); ++k) {
    const std::array<uint8_t, kGlyphHeight> rows = GlyphRows(text[k]);
    const uint32_t left = x + uint32_t(k) * (kGlyphWidth + 1) * s;
    for (int row = 0; row < kGlyphHeight; ++row) {
      for (int col = 0; col < kGlyphWidth; ++col) {
        if ((rows[row] >> (kGlyphWidth - 1 - col) & 1) == 0) continue;
        image->Fill(left + uint32_t(col) * s, y + uint32_t(row) * s, s, s, colour);
      }
    }
  }
}

}  // namespace radfarm
