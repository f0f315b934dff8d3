#include "store/blob_codec.h"

#include <bit>
#include <cstddef>
#include <cstring>
#include <string>

namespace radfarm::store {
namespace {

void PutDouble(double value, uint8_t* out) {
  uint64_t bits = std::bit_cast<uint64_t>(value);
  for (int i = 0; i < 8; ++i) out[i] = static_cast<uint8_t>(bits >> (8 * i));
}

double GetDouble(const uint8_t* in) {
  uint64_t bits = 0;
  for (int i = 0; i < 8; ++i) bits |= static_cast<uint64_t>(in[i]) << (8 * i);
  return std::bit_cast<double>(bits);
}

// Rgb is three doubles with nothing between them: on a little-endian host its bytes are the blob's.
constexpr bool kRgbIsBlob = std::endian::native == std::endian::little &&
                            sizeof(Rgb) == kRgbBlobBytes && offsetof(Rgb, r) == 0 &&
                            offsetof(Rgb, g) == 8 && offsetof(Rgb, b) == 16;

}  // namespace

std::vector<uint8_t> EncodeRgbs(std::span<const Rgb> values) {
  std::vector<uint8_t> bytes(values.size() * kRgbBlobBytes);
  // A checkpoint at 10^6 patches holds 48 MB of these: one copy, not a loop over bytes.
  if constexpr (kRgbIsBlob) {
    if (!values.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
    return bytes;
  }
  uint8_t* out = bytes.data();
  for (const Rgb& value : values) {
    PutDouble(value.r, out);
    PutDouble(value.g, out + 8);
    PutDouble(value.b, out + 16);
    out += kRgbBlobBytes;
  }
  return bytes;
}

std::span<const uint8_t> RgbBlob(std::span<const Rgb> values, std::vector<uint8_t>* buffer) {
  if constexpr (kRgbIsBlob) {
    return {reinterpret_cast<const uint8_t*>(values.data()), values.size() * kRgbBlobBytes};
  }
  *buffer = EncodeRgbs(values);
  return *buffer;
}

Result<std::vector<Rgb>> DecodeRgbs(std::span<const uint8_t> bytes) {
  if (bytes.size() % kRgbBlobBytes != 0) {
    return Error{"checkpoint blob of " + std::to_string(bytes.size()) +
                 " bytes is not a whole number of 24-byte RGB entries"};
  }
  std::vector<Rgb> values(bytes.size() / kRgbBlobBytes);
  if constexpr (kRgbIsBlob) {
    if (!values.empty()) std::memcpy(values.data(), bytes.data(), bytes.size());
    return values;
  }
  const uint8_t* in = bytes.data();
  for (Rgb& value : values) {
    value = Rgb(GetDouble(in), GetDouble(in + 8), GetDouble(in + 16));
    in += kRgbBlobBytes;
  }
  return values;
}

std::vector<uint8_t> EncodeEnergy(const EnergyAccount& energy) {
  std::vector<uint8_t> bytes(kEnergyBlobBytes);
  PutDouble(energy.emitted, bytes.data());
  PutDouble(energy.absorbed, bytes.data() + 8);
  PutDouble(energy.escaped, bytes.data() + 16);
  PutDouble(energy.unshot, bytes.data() + 24);
  return bytes;
}

Result<EnergyAccount> DecodeEnergy(std::span<const uint8_t> bytes) {
  if (bytes.size() != kEnergyBlobBytes) {
    return Error{"energy blob of " + std::to_string(bytes.size()) + " bytes, expected 32"};
  }
  EnergyAccount energy;
  energy.emitted = GetDouble(bytes.data());
  energy.absorbed = GetDouble(bytes.data() + 8);
  energy.escaped = GetDouble(bytes.data() + 16);
  energy.unshot = GetDouble(bytes.data() + 24);
  return energy;
}

}  // namespace radfarm::store
