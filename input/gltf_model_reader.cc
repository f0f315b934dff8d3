#include "input/gltf_model_reader.h"

#include <algorithm>
#include <filesystem>
#include <limits>
#include <optional>
#include <sstream>

#include "base/diagnostic.h"
#include "base/file_extension.h"
#include "base/text_file.h"
#include "input/image_header.h"
#include "input/scene_directory.h"

namespace radfarm {
namespace {

std::string FirstLine(const std::string& text) {
  std::string line = text.substr(0, text.find('\n'));
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
  return line;
}

bool IsBinary(const std::string& path) { return LowercaseExtension(path) == ".glb"; }

// tinygltf's own uri decoding (private to it): '+' is a space, "%XX" a byte, a bad hex digit 0.
// Used only to find the field a refused uri came from.
std::string DecodeUri(const std::string& uri) {
  auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return 0;
  };
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '+') {
      out += ' ';
    } else if (uri[i] == '%' && uri.size() > i + 2) {
      out += static_cast<char>(hex(uri[i + 1]) << 4 | hex(uri[i + 2]));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

// The user data of tinygltf's file callbacks and image loader.
struct SceneReads {
  const SceneDirectory& directory;
  uint64_t remaining_bytes;
  uint64_t max_texture_bytes;              // 0: none, but kDefaultMaxTexturePixels per image
  uint64_t texture_bytes_left;             // of max_texture_bytes
  std::optional<std::string> refused_uri;  // the first refused read's uri, as tinygltf decoded it
  std::string refused_why;
  std::optional<std::string> refused_image;  // the first image refused before decoding, and why
};

// tinygltf looks for a uri in its base directory, then in the working directory, asking this
// first: saying yes makes it read the first candidate, which ReadConfined resolves against the
// scene's directory. (tinygltf's own check opened the file, which waits forever on a FIFO.)
bool EveryFileExists(const std::string&, void*) { return true; }

// Every buffer and image file is read here, `uri` as tinygltf decoded it (its base directory is
// empty, so nothing is prefixed): resolved inside the scene's directory, then read by ReadTextFile
// (regular files only, the size checked before reading and the bytes counted while reading)
// against what is left of the scene's byte budget.
bool ReadConfined(std::vector<unsigned char>* out, std::string* err, const std::string& uri,
                  void* user_data) {
  auto* reads = static_cast<SceneReads*>(user_data);
  auto refuse = [&](const std::string& why) {
    if (!reads->refused_uri) {
      reads->refused_uri = uri;
      reads->refused_why = why;
    }
    *err += why;
    return false;
  };
  Result<std::filesystem::path> target = reads->directory.Resolve(uri);
  if (!target) return refuse(target.error());
  std::error_code ec;
  if (!std::filesystem::exists(*target, ec)) {
    // tinygltf decides: a missing buffer fails the load, a missing image is a warning.
    *err += "no such file";
    return false;
  }
  Result<std::string> bytes = reads->directory.Read(*target, reads->remaining_bytes);
  if (!bytes) return refuse("cannot be read: " + bytes.error());
  reads->remaining_bytes -= bytes->size();
  out->assign(bytes->begin(), bytes->end());
  return true;
}

uint64_t Megabytes(uint64_t bytes) { return (bytes + (uint64_t{1} << 20) - 1) >> 20; }

// "images[2] 'wood.png'" (its uri, else its name).
std::string ImageName(const tinygltf::Image& image, int index) {
  const std::string& name = image.uri.empty() ? image.name : image.uri;
  return "images[" + std::to_string(index) + "]" + (name.empty() ? "" : " '" + name + "'");
}

// tinygltf's loader decodes every image to RGBA (4 channels of 8 or 16 bits).
uint64_t DecodedBytes(const ImageHeader& header) {
  return uint64_t{header.width} * header.height * 4 * (header.bits / 8);
}

// Why an image of this header may not be decoded, or empty when it may.
std::string OverBudget(const ImageHeader& header, const SceneReads& reads) {
  const std::string pixels = std::to_string(header.width) + " x " + std::to_string(header.height);
  const uint64_t count = uint64_t{header.width} * header.height;
  // tinygltf multiplies width, height and channels in an int.
  if (count * 4 > static_cast<uint64_t>(std::numeric_limits<int>::max())) {
    return header.format + " of " + pixels + " pixels: too large to decode";
  }
  if (reads.max_texture_bytes == 0) {
    if (count <= kDefaultMaxTexturePixels) return "";
    return header.format + " of " + pixels +
           " pixels, more than the 8192 x 8192 a texture may have without --max-memory";
  }
  if (DecodedBytes(header) <= reads.texture_bytes_left) return "";
  return header.format + " of " + pixels + " pixels (4 x " + std::to_string(header.bits) +
         "-bit channels) needs about " + std::to_string(Megabytes(DecodedBytes(header))) +
         " MB decoded, more than the " + std::to_string(reads.texture_bytes_left >> 20) +
         " MB the memory limit leaves for textures (--max-memory)";
}

// tinygltf hands each image's encoded bytes here to decode: its header gives the decoded size,
// refused over the budget before a byte is decoded; then tinygltf's own loader (stb_image, to
// RGBA) decodes it.
bool DecodeWithinBudget(tinygltf::Image* image, const int index, std::string* err,
                        std::string* warn, int req_width, int req_height,
                        const unsigned char* bytes, int size, void* user_data) {
  auto* reads = static_cast<SceneReads*>(user_data);
  Result<ImageHeader> header = ReadImageHeader(bytes, static_cast<size_t>(size));
  const std::string why = header ? OverBudget(*header, *reads) : header.error();
  if (!why.empty()) {
    if (!reads->refused_image) reads->refused_image = ImageName(*image, index) + ": " + why;
    *err += why + "\n";
    return false;
  }
  // No options: RGBA, as counted above.
  if (!tinygltf::LoadImageData(image, index, err, warn, req_width, req_height, bytes, size,
                               nullptr)) {
    return false;
  }
  reads->texture_bytes_left -= std::min<uint64_t>(reads->texture_bytes_left, image->image.size());
  return true;
}

// The field a refused uri came from. tinygltf reads the buffers first, in order, and stops at the
// first it cannot read; then the images, keeping one it cannot read with its uri.
std::string FieldOf(const tinygltf::Model& model, const std::string& decoded_uri) {
  for (size_t i = 0; i < model.images.size(); ++i) {
    const std::string& uri = model.images[i].uri;
    if (!uri.empty() && !tinygltf::IsDataURI(uri) && DecodeUri(uri) == decoded_uri) {
      return "images[" + std::to_string(i) + "].uri";
    }
  }
  return "buffers[" + std::to_string(model.buffers.size()) + "].uri";
}

}  // namespace

Result<tinygltf::Model> ReadGltfModel(const std::string& path, uint64_t max_file_bytes,
                                      uint64_t max_texture_bytes,
                                      std::vector<std::string>* warnings, FileReach reach) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return ErrorAt(path, 0, "cannot open: no such file");
  if (!std::filesystem::is_regular_file(path, ec)) {
    return ErrorAt(path, 0, "cannot open: not a regular file");
  }
  Result<std::string> file = ReadTextFile(path, max_file_bytes);
  RADFARM_RETURN_IF_ERROR(file);
  if (file->size() > std::numeric_limits<unsigned int>::max()) {
    return ErrorAt(path, 0, "too large for the glTF reader (4 GiB at most)");
  }
  const SceneDirectory directory(path, reach);
  SceneReads reads{directory,         max_file_bytes - file->size(),
                   max_texture_bytes, max_texture_bytes,
                   std::nullopt,      {},
                   std::nullopt};
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({&EveryFileExists, &tinygltf::ExpandFilePath, &ReadConfined,
                         &tinygltf::WriteWholeFile, &reads});
  loader.SetImageLoader(&DecodeWithinBudget, &reads);
  tinygltf::Model model;
  std::string err, warn;
  const auto size = static_cast<unsigned int>(file->size());
  const bool ok =
      IsBinary(path)
          ? loader.LoadBinaryFromMemory(&model, &err, &warn,
                                        reinterpret_cast<const unsigned char*>(file->data()), size,
                                        /*base_dir=*/"")
          : loader.LoadASCIIFromString(&model, &err, &warn, file->data(), size, /*base_dir=*/"");
  std::istringstream lines(warn);
  for (std::string line; std::getline(lines, line);) {
    if (!line.empty()) warnings->push_back(WarningAt(path, 0, line));
  }
  // Also when tinygltf went on (it only warns about an image it cannot read).
  if (reads.refused_uri) {
    return ErrorAt(
        path, 0,
        FieldOf(model, *reads.refused_uri) + " '" + *reads.refused_uri + "' " + reads.refused_why);
  }
  if (reads.refused_image) return ErrorAt(path, 0, *reads.refused_image);
  if (!ok) {
    const std::string why = FirstLine(err);
    return ErrorAt(path, 0, "not a valid glTF file: " + (why.empty() ? "unreadable" : why));
  }
  return model;
}

}  // namespace radfarm
