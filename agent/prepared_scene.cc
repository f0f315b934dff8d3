#include "agent/prepared_scene.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <exception>
#include <optional>
#include <string>

#include "codec/patch_scene_codec.h"

namespace radfarm::agent {
namespace {

// Patches decoded between two releases of the mapped blob's pages.
constexpr uint32_t kPatchesPerRelease = 1u << 15;

// A file mapped read-only. Its pages are the page cache's: MADV_DONTNEED drops them from the
// process (its resident memory) without losing them; the next read maps them again.
class MappedFile {
 public:
  explicit MappedFile(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return;
    struct stat st {};
    if (::fstat(fd, &st) == 0 && st.st_size > 0) {
      void* data = ::mmap(nullptr, static_cast<size_t>(st.st_size), PROT_READ, MAP_PRIVATE, fd, 0);
      if (data != MAP_FAILED) {
        data_ = static_cast<const uint8_t*>(data);
        size_ = static_cast<size_t>(st.st_size);
      }
    }
    ::close(fd);
  }
  ~MappedFile() {
    if (data_) ::munmap(const_cast<uint8_t*>(data_), size_);
  }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  std::span<const uint8_t> bytes() const { return {data_, size_}; }
  void Release() const {
    if (data_) ::madvise(const_cast<uint8_t*>(data_), size_, MADV_DONTNEED);
  }

 private:
  const uint8_t* data_ = nullptr;
  size_t size_ = 0;
};

// Decodes `blob` into `prepared`'s shapes and the patches' sides; `each_chunk` runs after every
// kPatchesPerRelease patches.
Result<uint32_t> DecodeShapes(std::span<const uint8_t> blob, PreparedScene& prepared,
                              std::vector<uint8_t>& two_sided,
                              const std::function<void()>& each_chunk) {
  std::vector<PatchShape>& shapes = prepared.shapes;
  return codec::DecodePatches(blob, [&](const Patch& patch, uint32_t index, uint32_t count) {
    if (index == 0) {
      shapes.reserve(count);
      two_sided.reserve(count);
    }
    shapes.push_back(patch);
    two_sided.push_back(patch.two_sided ? 1 : 0);
    if ((index + 1) % kPatchesPerRelease == 0 && each_chunk) each_chunk();
  });
}

}  // namespace

Result<std::shared_ptr<const PreparedScene>> PrepareScene(
    const protocol::SceneHash& hash, std::vector<uint8_t> blob,
    const std::function<std::string(std::span<const uint8_t> blob)>& decoded_callback) {
  // First every value is checked, keeping nothing, so a bad scene is neither kept nor half built.
  Result<uint32_t> checked = codec::DecodePatches(blob, [](const Patch&, uint32_t, uint32_t) {});
  if (!checked) return Error{"cannot decode: " + checked.error()};
  if (*checked == 0) return Error{"has no patches"};
  const std::string file = decoded_callback ? decoded_callback(blob) : std::string();
  auto prepared = std::make_shared<PreparedScene>();
  prepared->hash = hash;
  std::vector<uint8_t> two_sided;  // for the caster only
  std::optional<MappedFile> mapped;
  if (!file.empty()) mapped.emplace(file);
  if (mapped && mapped->bytes().size() == blob.size()) {
    // Decoded from the file the blob is kept in, its pages dropped as the patches are read, so
    // the blob and the shapes are not both held whole.
    std::vector<uint8_t>().swap(blob);
    Result<uint32_t> decoded =
        DecodeShapes(mapped->bytes(), *prepared, two_sided, [&] { mapped->Release(); });
    if (!decoded) return Error{"cannot decode " + file + ": " + decoded.error()};
    mapped.reset();
  } else {
    Result<uint32_t> decoded = DecodeShapes(blob, *prepared, two_sided, {});
    if (!decoded) return Error{"cannot decode: " + decoded.error()};
    std::vector<uint8_t>().swap(blob);  // not needed for tracing
  }
  try {
    prepared->caster = std::make_unique<const RayCaster>(prepared->shapes, two_sided);
  } catch (const std::exception& e) {
    return Error{std::string("cannot build its ray caster: ") + e.what()};
  }
  return std::shared_ptr<const PreparedScene>(std::move(prepared));
}

}  // namespace radfarm::agent
