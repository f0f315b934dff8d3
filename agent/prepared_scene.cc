#include "agent/prepared_scene.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstddef>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>

#include "codec/patch_scene_codec.h"

namespace radfarm::agent {
namespace {

// Patches decoded between two releases of the mapped blob's pages (about 1.8 MB of them).
constexpr uint32_t kPatchesPerRelease = 1u << 13;

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

// Decodes every patch of `blob`, which was checked before, for `each`; `each_chunk` runs after
// every kPatchesPerRelease patches and at the end.
void Stream(std::span<const uint8_t> blob, const std::function<void()>& each_chunk,
            const std::function<void(const Patch& patch)>& each) {
  Result<uint32_t> decoded =
      codec::DecodeAcceptedPatches(blob, [&](const Patch& patch, uint32_t index, uint32_t) {
        each(patch);
        if ((index + 1) % kPatchesPerRelease == 0 && each_chunk) each_chunk();
      });
  if (each_chunk) each_chunk();
  if (!decoded) throw std::runtime_error(decoded.error());
}

// Seconds since `since`, and `since` moved to now.
double Lap(std::chrono::steady_clock::time_point& since) {
  const auto now = std::chrono::steady_clock::now();
  const double seconds = std::chrono::duration<double>(now - since).count();
  since = now;
  return seconds;
}

// Where the normals of `shapes` will be, once it holds them: room reserved is enough.
const Vec3* NormalsOf(const std::vector<PatchShape>& shapes) {
  return reinterpret_cast<const Vec3*>(reinterpret_cast<const char*>(shapes.data()) +
                                       offsetof(PatchShape, normal));
}

}  // namespace

Result<std::shared_ptr<const PreparedScene>> PrepareScene(
    const protocol::SceneHash& hash, std::vector<uint8_t> blob,
    const std::function<std::string(std::span<const uint8_t> blob)>& decoded_callback,
    PrepareTimes* times) {
  PrepareTimes unused;
  if (times == nullptr) times = &unused;
  auto since = std::chrono::steady_clock::now();
  // First every value is checked, keeping nothing, so a bad scene is neither kept nor half built.
  Result<uint32_t> checked = codec::DecodePatches(blob, [](const Patch&, uint32_t, uint32_t) {});
  if (!checked) return Error{"cannot decode: " + checked.error()};
  if (*checked == 0) return Error{"has no patches"};
  times->check = Lap(since);
  const std::string file = decoded_callback ? decoded_callback(blob) : std::string();
  times->decoded_callback = Lap(since);
  auto prepared = std::make_shared<PreparedScene>();
  prepared->hash = hash;
  std::optional<MappedFile> mapped;
  if (!file.empty()) mapped.emplace(file);
  std::vector<PatchShape>& shapes = prepared->shapes;
  if (!mapped || mapped->bytes().size() != blob.size()) {
    // No file: the shapes from the blob, which is freed before the caster is built from them.
    std::vector<uint8_t> two_sided;  // for the caster only
    try {
      shapes.reserve(*checked);
      two_sided.reserve(*checked);
      Stream(blob, {}, [&](const Patch& p) {
        shapes.push_back(p);
        two_sided.push_back(p.two_sided ? 1 : 0);
      });
    } catch (const std::exception& e) {
      return Error{std::string("cannot decode: ") + e.what()};
    }
    std::vector<uint8_t>().swap(blob);
    times->shapes = Lap(since);
    try {
      prepared->caster = std::make_unique<const RayCaster>(shapes, two_sided);
    } catch (const std::exception& e) {
      return Error{std::string("cannot build its ray caster: ") + e.what()};
    }
    times->caster = Lap(since);
    return std::shared_ptr<const PreparedScene>(std::move(prepared));
  }
  // From the file the blob is kept in, its pages dropped as the patches are read, so the blob is
  // never held beside the caster's build or the shapes. The caster first, the shapes' room only
  // reserved (untouched), so its build's scratch does not sit on top of them; then the shapes.
  std::vector<uint8_t>().swap(blob);
  const auto release = [&] { mapped->Release(); };
  shapes.reserve(*checked);
  try {
    prepared->caster = std::make_unique<const RayCaster>(
        *checked,
        [&](const RayCaster::PatchVisitor& each) {
          Stream(mapped->bytes(), release, [&](const Patch& p) { each(p, p.two_sided); });
        },
        NormalsOf(shapes), sizeof(PatchShape));
  } catch (const std::exception& e) {
    return Error{std::string("cannot build its ray caster: ") + e.what()};
  }
  times->caster = Lap(since);
  try {
    Stream(mapped->bytes(), release, [&](const Patch& p) { shapes.push_back(p); });
  } catch (const std::exception& e) {
    return Error{"cannot decode " + file + ": " + e.what()};
  }
  times->shapes = Lap(since);
  if (shapes.size() != *checked) return Error{"changed while it was decoded"};
  return std::shared_ptr<const PreparedScene>(std::move(prepared));
}

}  // namespace radfarm::agent
