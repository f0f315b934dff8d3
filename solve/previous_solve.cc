#include "solve/previous_solve.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <string>
#include <string_view>
#include <utility>

#include "base/atomic_file.h"
#include "base/little_endian.h"
#include "base/text_file.h"
#include "core/delta_start.h"
#include "core/ray_caster.h"

namespace radfarm {
namespace {

constexpr std::string_view kMagic = "RFREBAKE";
constexpr uint32_t kVersion = 1;
constexpr uint8_t kEmittersDirect = 1, kDirectStored = 2, kStartWorkStored = 4;
constexpr size_t kHashChars = 64;
constexpr size_t kHeaderBytes = 8 + 4 + 4 + 1 + 2 * kHashChars + 4 + 8 + 1 + 4 + 8;
constexpr size_t kPatchBytes = 15 * sizeof(double);

void AppendRgb(const Rgb& c, std::string* out) {
  AppendLittleEndian(c.r, out);
  AppendLittleEndian(c.g, out);
  AppendLittleEndian(c.b, out);
}

// Reads values in order from a buffer whose size was checked first.
class Reader {
 public:
  explicit Reader(std::string_view bytes) : bytes_(bytes) {}
  template <typename T>
  T Next() {
    char raw[sizeof(T)];
    std::memcpy(raw, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    if constexpr (std::endian::native == std::endian::big) {
      for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
    }
    T value;
    std::memcpy(&value, raw, sizeof(T));
    return value;
  }
  std::string Text(size_t n) {
    std::string out(bytes_.substr(at_, n));
    at_ += n;
    return out;
  }
  Rgb NextRgb() {
    const double r = Next<double>(), g = Next<double>(), b = Next<double>();
    return {r, g, b};
  }

 private:
  std::string_view bytes_;
  size_t at_ = 0;
};

bool IsHex(const std::string& s) {
  if (s.size() != kHashChars) return false;
  for (char c : s) {
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  }
  return true;
}

}  // namespace

PreviousPatchValues PreviousValuesOf(const PatchScene& scene, const SolveResult& solution) {
  PreviousPatchValues v;
  v.radiosity = solution.radiosity;
  v.unshot = solution.unshot;
  v.direct = solution.direct_light;
  v.emitters_direct = solution.emitters_direct;
  v.punctual_power = solution.punctual_power;
  for (const Patch& p : scene.patches) {
    v.emission.push_back(p.emission);
    v.reflectance.push_back(p.reflectance);
  }
  return v;
}

StartLightSource RebakeStart(const PreviousPatchValues& previous, unsigned threads) {
  return [&previous, threads](const PatchScene& scene, const StartWork& work) {
    if (!previous.direct.empty() && previous.emitters_direct == work.emitters) {
      return DeltaStart(scene, work, previous.emission, previous.direct, previous.punctual_power,
                        threads);
    }
    const RayCaster caster(scene);
    const DirectLight direct = StartDirectLight(scene, caster, work);
    return StartLightOf(
        scene, TraceStartPatches(scene, direct, caster, work, 0, scene.patches.size(), threads));
  };
}

Status WritePreviousSolve(const std::string& path, const PreviousSolve& solve) {
  const PreviousPatchValues& v = solve.values;
  const size_t n = v.radiosity.size();
  std::string out;
  out.reserve(kHeaderBytes + n * kPatchBytes);
  out.append(kMagic);
  AppendLittleEndian(kVersion, &out);
  AppendLittleEndian(static_cast<uint32_t>(n), &out);
  const uint8_t flags = (v.emitters_direct ? kEmittersDirect : 0) |
                        (v.direct.empty() ? 0 : kDirectStored) |
                        (solve.start_work ? kStartWorkStored : 0);
  AppendLittleEndian(flags, &out);
  out.append(solve.geometry_hash);
  out.append(solve.lamps_hash);
  const StartWork work = solve.start_work.value_or(StartWork{});
  AppendLittleEndian(work.sections, &out);
  AppendLittleEndian(work.seed, &out);
  AppendLittleEndian(static_cast<uint8_t>(work.emitters), &out);
  AppendLittleEndian(work.rays_per_light, &out);
  AppendLittleEndian(v.punctual_power, &out);
  for (size_t i = 0; i < n; ++i) {
    AppendRgb(v.radiosity[i], &out);
    AppendRgb(v.unshot[i], &out);
    AppendRgb(v.emission[i], &out);
    AppendRgb(v.reflectance[i], &out);
    AppendRgb(v.direct.empty() ? Rgb{} : v.direct[i], &out);
  }
  return WriteFileAtomically(path, out);
}

Result<PreviousSolve> ReadPreviousSolve(const std::string& path) {
  Result<std::string> bytes = ReadTextFile(path);
  if (!bytes) return Error{bytes.error()};
  const std::string& b = *bytes;
  const auto bad = [&](const std::string& why) { return Error{path + ": " + why}; };
  if (b.size() < kHeaderBytes || std::string_view(b).substr(0, kMagic.size()) != kMagic) {
    return bad("not a re-bake file (rebake.bin of a render's output)");
  }
  Reader in(std::string_view(b).substr(kMagic.size()));
  if (const uint32_t version = in.Next<uint32_t>(); version != kVersion) {
    return bad("version " + std::to_string(version) + ", this program reads " +
               std::to_string(kVersion));
  }
  const uint32_t n = in.Next<uint32_t>();
  if ((b.size() - kHeaderBytes) / kPatchBytes != n || (b.size() - kHeaderBytes) % kPatchBytes) {
    return bad("the file is " + std::to_string(b.size()) + " bytes, not what " + std::to_string(n) +
               " patches take");
  }
  const uint8_t flags = in.Next<uint8_t>();
  PreviousSolve solve;
  solve.geometry_hash = in.Text(kHashChars);
  solve.lamps_hash = in.Text(kHashChars);
  if (!IsHex(solve.geometry_hash) || !IsHex(solve.lamps_hash)) return bad("a hash is not hex");
  StartWork work;
  work.sections = in.Next<uint32_t>();
  work.seed = in.Next<uint64_t>();
  work.emitters = in.Next<uint8_t>() != 0;
  work.rays_per_light = in.Next<uint32_t>();
  if (flags & kStartWorkStored) solve.start_work = work;
  PreviousPatchValues& v = solve.values;
  v.punctual_power = in.Next<double>();
  v.emitters_direct = (flags & kEmittersDirect) != 0;
  for (std::vector<Rgb>* field : {&v.radiosity, &v.unshot, &v.emission, &v.reflectance}) {
    field->reserve(n);
  }
  std::vector<Rgb> direct;
  for (uint32_t i = 0; i < n; ++i) {
    v.radiosity.push_back(in.NextRgb());
    v.unshot.push_back(in.NextRgb());
    v.emission.push_back(in.NextRgb());
    v.reflectance.push_back(in.NextRgb());
    direct.push_back(in.NextRgb());
    for (const Rgb& c : {v.radiosity[i], v.unshot[i], v.emission[i], v.reflectance[i], direct[i]}) {
      if (!c.IsFinite()) return bad("patch " + std::to_string(i) + ": a value is not finite");
    }
    const Rgb& rho = v.reflectance[i];
    if (rho.Min() < 0 || rho.Max() >= 1) {
      return bad("patch " + std::to_string(i) + ": reflectance outside [0, 1)");
    }
  }
  if (flags & kDirectStored) v.direct = std::move(direct);
  if (!std::isfinite(v.punctual_power)) return bad("the lamps' power is not finite");
  return solve;
}

}  // namespace radfarm
