#include "mesh/patch_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <map>
#include <sstream>
#include <utility>

#include "base/result.h"
#include "core/thread_pool.h"
#include "mesh/auto_patch_size.h"
#include "mesh/clean_faces.h"
#include "mesh/contact_cut.h"
#include "mesh/hidden_faces.h"
#include "mesh/memory_estimate.h"
#include "mesh/narrow_space.h"
#include "mesh/polygon_split.h"
#include "mesh/surfaces.h"

namespace radfarm {
namespace {

constexpr double kLengthTolerance = 1e-6;  // times the diagonal
constexpr double kAreaTolerance = 1e-12;   // times the diagonal squared
constexpr size_t kListedLines = 10;        // lines named in one warning

// The loader validates its scenes, but InputScene is a plain struct: check what meshing relies on.
Status CheckScene(const InputScene& scene) {
  const size_t objects = std::max<size_t>(scene.objects.size(), 1);
  for (const InputFace& face : scene.faces) {
    const std::string where = scene.path + ":" + std::to_string(face.line) + ": ";
    if (face.object >= objects) {
      return Error{where + "object index " + std::to_string(face.object) + " out of range"};
    }
    if (face.material >= scene.materials.size()) {
      return Error{where + "material index " + std::to_string(face.material) + " out of range"};
    }
    for (uint32_t index : face.indices) {
      if (index >= scene.positions.size()) {
        return Error{where + "vertex index " + std::to_string(index) + " out of range"};
      }
      if (!IsFinite(scene.positions[index])) return Error{where + "non-finite vertex position"};
    }
  }
  return Ok{};
}

Bounds3 FaceBounds(const InputScene& scene) {
  Bounds3 bounds;
  for (const InputFace& face : scene.faces) {
    for (uint32_t index : face.indices) bounds.Extend(scene.positions[index]);
  }
  return bounds;
}

// "scene.obj: dropped 2 zero-area faces (lines 3, 7)".
void WarnDropped(const std::string& path, const std::vector<uint32_t>& lines, const char* one,
                 const char* many, std::vector<std::string>* warnings) {
  if (lines.empty() || warnings == nullptr) return;
  std::ostringstream out;
  out << path << ": dropped " << lines.size() << " " << (lines.size() == 1 ? one : many)
      << (lines.size() == 1 ? " (line " : " (lines ");
  for (size_t i = 0; i < lines.size() && i < kListedLines; ++i) out << (i ? ", " : "") << lines[i];
  if (lines.size() > kListedLines) out << " and " << lines.size() - kListedLines << " more";
  out << ")";
  warnings->push_back(out.str());
}

std::vector<CleanFace> DropHidden(std::vector<CleanFace> faces, double tol,
                                  std::vector<uint32_t>* hidden_lines) {
  const std::vector<bool> hidden = FindHiddenFaces(faces, tol);
  std::vector<CleanFace> kept;
  for (size_t i = 0; i < faces.size(); ++i) {
    if (hidden[i]) {
      hidden_lines->push_back(faces[i].line);
    } else {
      kept.push_back(std::move(faces[i]));
    }
  }
  return kept;
}

// The back of a two-sided face: its patches again, facing the other way, on a surface of their
// own. Two patches rather than one that receives and emits on both sides: an opaque sheet lit on
// one side reflects that light to the same side only, so each side has its own radiosity (one
// patch for both would send half the light a room's wall receives out of the room). The back is
// not cut along footprints or sheets: what stands on the front does not touch it.
void AddBackSide(const SplitPlan& plan, uint32_t surface, uint32_t material,
                 PatchAssembler* assembler) {
  std::vector<PieceCorners> pieces;
  EmitPieces(plan, &pieces);
  for (PieceCorners& piece : pieces) {
    std::reverse(piece.corners.begin(), piece.corners.begin() + piece.count);
    assembler->Add(piece, surface, material);
  }
}

// Surface ids for the backs of two-sided surfaces, numbered after the others in order of first
// use, so the front's vertex averages never mix with the back's.
class BackSurfaces {
 public:
  explicit BackSurfaces(size_t* surface_count) : surface_count_(surface_count) {}
  uint32_t Of(uint32_t front) {
    const auto [it, added] = back_of_.try_emplace(front, static_cast<uint32_t>(*surface_count_));
    if (added) ++*surface_count_;
    return it->second;
  }

 private:
  size_t* surface_count_;
  std::map<uint32_t, uint32_t> back_of_;
};

// A mesh's patch sizes, weighted by the patches cut to each (see PatchMesh::patch_size()).
struct PatchSizeSummary {
  double median = 0, min = 0, max = 0;
};

PatchSizeSummary SummarizePatchSizes(const std::vector<SplitPlan>& plans,
                                     const std::vector<double>& sizes) {
  // The median by pieces: the size most patches were cut to.
  std::vector<std::pair<double, uint64_t>> by_size;
  uint64_t total = 0;
  for (size_t f = 0; f < plans.size(); ++f) {
    const uint64_t count = std::min(plans[f].PieceCount(), kMaxPatches + 1);
    by_size.emplace_back(sizes[f], count);
    total += count;
  }
  std::sort(by_size.begin(), by_size.end());
  PatchSizeSummary summary;
  summary.min = by_size.front().first;
  summary.max = by_size.back().first;
  uint64_t seen = 0;
  for (const auto& [size, count] : by_size) {
    seen += count;
    summary.median = size;
    if (2 * seen >= total) break;
  }
  return summary;
}

// A face's front pieces in Build's order: its split cut along the footprints on it; the parts under
// each sheet apart (contact_cut.h), one list per sheet; then what is left (open).
struct FacePieces {
  std::vector<PieceCorners> open;
  std::vector<std::vector<PieceCorners>> covered;

  // The lists in Build's order: each sheet's covered pieces, then the open ones.
  std::vector<PieceCorners>& List(size_t i) { return i < covered.size() ? covered[i] : open; }
  size_t ListCount() const { return covered.size() + 1; }
};

void CutFace(const SplitPlan& plan, const CleanFace& face, const std::vector<Footprint>& footprints,
             const std::vector<Footprint>& sheets, double tol, double min_area, FacePieces* out) {
  out->open.clear();
  out->covered.assign(sheets.size(), {});
  EmitPieces(plan, &out->open);
  if (!footprints.empty()) CutFootprints(footprints, face.normal, tol, min_area, &out->open);
  for (size_t i = 0; i < sheets.size(); ++i) {
    CutFootprints({sheets[i]}, face.normal, tol, min_area, &out->open, &out->covered[i]);
  }
}

// Steps 1-4 as far as planning each face's split: the faces left, their sizes and splits, and every
// error and warning Build gives (assembling the patches adds none), so Check needs no more.
struct MeshPlan {
  double tol = 0;
  uint64_t memory_limit = 0;  // bytes: MeshSettings::max_memory, or this machine's
  double min_area = 0;
  std::vector<CleanFace> faces;
  std::vector<double> sizes;
  std::vector<SplitPlan> plans;
  std::vector<std::vector<Footprint>> footprints;  // per face: what stands on it
  std::vector<std::vector<Footprint>> sheets;      // per face: the sheets covering it
  // Per face, per list of FacePieces (each sheet's covered pieces, then the open ones): the pieces
  // a narrow space splits again; empty when none.
  std::vector<std::vector<std::vector<NarrowPiece>>> narrow;
  uint64_t piece_count = 0;
  size_t dropped_degenerate = 0;
  size_t dropped_hidden = 0;
  PatchSizeSummary size;
};

Result<MeshPlan> PlanMesh(const InputScene& scene, const MeshSettings& settings,
                          std::vector<std::string>* warnings, ThreadPool& pool) {
  if (!std::isfinite(settings.patch_size) || settings.patch_size < 0) {
    return Error{scene.path + ": patch size must be a finite number >= 0"};
  }
  RADFARM_RETURN_IF_ERROR(CheckScene(scene));
  const double diagonal = FaceBounds(scene).Diagonal();
  MeshPlan mp;
  mp.tol = kLengthTolerance * diagonal;
  mp.min_area = kAreaTolerance * diagonal * diagonal;
  const double tol = mp.tol;

  CleanFaces clean = CleanInputFaces(scene, tol, mp.min_area);
  std::vector<uint32_t> hidden_lines;
  mp.faces = DropHidden(std::move(clean.faces), tol, &hidden_lines);
  const std::vector<CleanFace>& faces = mp.faces;
  mp.dropped_degenerate = clean.degenerate_lines.size();
  mp.dropped_hidden = hidden_lines.size();
  WarnDropped(scene.path, clean.degenerate_lines, "zero-area face", "zero-area faces", warnings);
  WarnDropped(scene.path, hidden_lines, "face hidden inside a coplanar overlap",
              "faces hidden inside a coplanar overlap", warnings);
  if (faces.empty()) return Error{scene.path + ": no faces left to mesh"};

  const bool automatic = settings.patch_size == 0;
  std::vector<double>& sizes = mp.sizes;
  // One probe of the faces for the automatic size and for narrow spaces.
  const FreePathProbe probe(faces, tol, diagonal);
  sizes = automatic ? AutoPatchSizes(faces, probe, tol, &pool)
                    : std::vector<double>(faces.size(), settings.patch_size);
  const uint64_t memory_limit = mp.memory_limit =
      settings.max_memory > 0 ? settings.max_memory : PhysicalMemoryBytes();
  std::vector<SplitPlan>& plans = mp.plans;
  uint64_t& piece_count = mp.piece_count;
  mp.footprints = FindFootprints(faces, tol);
  std::vector<FacePieces> cuts(pool.size());  // a worker's scratch
  std::vector<uint64_t> face_pieces(faces.size());
  // An automatic mesh too large for the patch limit or the memory is made coarser all over
  // instead of refused: by the square root of the excess, a few times at most.
  for (int attempt = 0;; ++attempt) {
    plans.clear();
    piece_count = 0;
    for (size_t f = 0; f < faces.size(); ++f) {
      const CleanFace& face = faces[f];
      plans.push_back(PlanSplit(face.corners, face.normal, sizes[f], tol));
      const int sides = scene.materials[face.material].two_sided ? 2 : 1;
      piece_count += sides * std::min(plans.back().PieceCount(), kMaxPatches + 1);  // no overflow
    }
    const uint64_t allowed =
        std::min(kMaxPatches, PatchesThatFit(memory_limit).value_or(kMaxPatches));
    mp.size = SummarizePatchSizes(plans, sizes);
    mp.sheets.assign(faces.size(), {});
    mp.narrow.assign(faces.size(), {});
    if (piece_count <= allowed) {
      // Within the limits before the cuts: count what Build makes, narrow spaces split again.
      mp.sheets = FindCoveringSheets(faces, tol, kSheetReachPatches * mp.size.median);
      // Face by face on the pool: each writes only its own entries.
      pool.ParallelFor(faces.size(), [&](unsigned worker, size_t f) {
        const CleanFace& face = faces[f];
        FacePieces& cut = cuts[worker];
        CutFace(plans[f], face, mp.footprints[f], mp.sheets[f], tol, mp.min_area, &cut);
        uint64_t pieces = 0;
        for (size_t i = 0; i < cut.ListCount(); ++i) {
          const std::vector<PieceCorners>& list = cut.List(i);
          std::vector<NarrowPiece> narrow =
              FindNarrowPieces(probe, list, face.normal, sizes[f], tol);
          pieces += list.size() + NarrowExtraPieces(list, face.normal, narrow, tol);
          if (narrow.empty()) continue;
          mp.narrow[f].resize(cut.ListCount());
          mp.narrow[f][i] = std::move(narrow);
        }
        // The back is not cut or split again (AddBackSide).
        if (scene.materials[face.material].two_sided) pieces += plans[f].PieceCount();
        face_pieces[f] = pieces;
      });
      piece_count = 0;
      for (uint64_t pieces : face_pieces) piece_count += pieces;
    }
    if (!automatic || piece_count <= allowed || attempt == 8 || allowed == 0) break;
    const double grow = 1.05 * std::sqrt(double(piece_count) / double(allowed));
    for (double& size : sizes) size *= grow;
  }
  for (size_t f = 0; f < faces.size(); ++f) {
    if (!plans[f].simple && warnings != nullptr) {
      warnings->push_back(scene.path + ":" + std::to_string(faces[f].line) +
                          ": face is self-intersecting; its patches may overlap");
    }
  }
  if (piece_count > kMaxPatches) {
    std::ostringstream out;
    out << scene.path << ": patch size " << mp.size.median << " would make over " << kMaxPatches
        << " patches";
    return Error{out.str()};
  }
  if (memory_limit > 0 && EstimatedSolveBytes(piece_count) > memory_limit) {
    std::ostringstream out;
    out << scene.path << ": " << piece_count << " patches (patch size " << mp.size.median
        << ") need about " << FormatMegabytes(EstimatedSolveBytes(piece_count))
        << " of memory, more than the limit of " << FormatMegabytes(memory_limit)
        << (settings.max_memory > 0 ? " (--max-memory)" : " (this machine's memory)")
        << "; use a larger patch size";
    return Error{out.str()};
  }
  return mp;
}

}  // namespace

Result<MeshCheck> PatchMesh::Check(const InputScene& scene, const MeshSettings& settings,
                                   std::vector<std::string>* warnings) {
  ThreadPool pool(settings.threads);
  Result<MeshPlan> mp = PlanMesh(scene, settings, warnings, pool);
  RADFARM_RETURN_IF_ERROR(mp);
  return MeshCheck{mp->piece_count, mp->size.median, mp->tol, mp->memory_limit};
}

Result<PatchMesh> PatchMesh::Build(const InputScene& scene, const MeshSettings& settings,
                                   std::vector<std::string>* warnings) {
  ThreadPool pool(settings.threads);
  Result<MeshPlan> planned = PlanMesh(scene, settings, warnings, pool);
  RADFARM_RETURN_IF_ERROR(planned);
  const MeshPlan& mp = *planned;
  const double tol = mp.tol;
  const double min_area = mp.min_area;
  const std::vector<CleanFace>& faces = mp.faces;
  const std::vector<SplitPlan>& plans = mp.plans;
  PatchMesh pm;
  pm.dropped_degenerate_ = mp.dropped_degenerate;
  pm.dropped_hidden_ = mp.dropped_hidden;
  pm.patch_size_ = mp.size.median;
  pm.patch_size_min_ = mp.size.min;
  pm.patch_size_max_ = mp.size.max;

  const SurfaceGroups surfaces = GroupSurfaces(faces, tol);
  pm.surface_count_ = surfaces.count;

  pm.materials_ = scene.materials;
  pm.objects_ = ObjectsOrDefault(scene);
  pm.lightmap_triangles_ = LightmapTriangles(scene);
  pm.unmapped_triangles_ = UnmappedTriangles(scene);
  const auto set_object = [&pm](uint32_t surface, uint32_t object) {
    if (pm.surface_object_.size() <= surface) pm.surface_object_.resize(surface + 1);
    pm.surface_object_[surface] = object;
  };
  pm.tol_ = tol;
  pm.memory_limit_ = mp.memory_limit;
  pm.min_area_ = min_area;
  PatchAssembler assembler(tol, min_area, pm.materials_, mp.piece_count);
  BackSurfaces back_surface(&pm.surface_count_);
  FacePieces cut;
  for (size_t f = 0; f < faces.size(); ++f) {
    CutFace(plans[f], faces[f], mp.footprints[f], mp.sheets[f], tol, min_area, &cut);
    for (size_t i = 0; i < mp.narrow[f].size(); ++i) {
      SplitNarrowPieces(mp.narrow[f][i], faces[f].normal, tol, &cut.List(i));
    }
    for (const std::vector<PieceCorners>& covered : cut.covered) {
      // The part under a sheet becomes a surface of its own (contact_cut.h).
      const auto surface = static_cast<uint32_t>(pm.surface_count_++);
      pm.covered_surfaces_.push_back(surface);
      set_object(surface, faces[f].object);
      for (const PieceCorners& piece : covered) assembler.Add(piece, surface, faces[f].material);
    }
    for (const PieceCorners& piece : cut.open) {
      assembler.Add(piece, surfaces.surface[f], faces[f].material);
    }
    set_object(surfaces.surface[f], faces[f].object);
    if (pm.materials_[faces[f].material].two_sided) {
      const uint32_t back = back_surface.Of(surfaces.surface[f]);
      AddBackSide(plans[f], back, faces[f].material, &assembler);
      set_object(back, faces[f].object);
    }
  }
  pm.surface_object_.resize(pm.surface_count_);
  pm.data_ = std::move(assembler).Finish(&pool);
  pm.data_.scene.lights = scene.lights;
  pm.data_.scene.sky = scene.sky;
  return pm;
}

std::vector<PatchMesh::Piece> PatchMesh::PiecesOf(const PatchScene& scene) {
  std::vector<Piece> pieces;
  pieces.reserve(scene.patches.size());
  for (const Patch& p : scene.patches) {
    Piece piece;
    piece.corners.corners = p.corners;
    piece.corners.count = p.corner_count;
    piece.surface = p.surface;
    piece.material = p.material;
    pieces.push_back(piece);
  }
  return pieces;
}

PatchMesh PatchMesh::Rebuilt(const std::vector<Piece>& pieces, ThreadPool* pool) const {
  PatchMesh pm;
  pm.patch_size_ = patch_size_;
  pm.patch_size_min_ = patch_size_min_;
  pm.patch_size_max_ = patch_size_max_;
  pm.dropped_degenerate_ = dropped_degenerate_;
  pm.dropped_hidden_ = dropped_hidden_;
  pm.surface_count_ = surface_count_;
  pm.covered_surfaces_ = covered_surfaces_;
  pm.objects_ = objects_;
  pm.surface_object_ = surface_object_;
  pm.lightmap_triangles_ = lightmap_triangles_;
  pm.unmapped_triangles_ = unmapped_triangles_;
  pm.materials_ = materials_;
  pm.tol_ = tol_;
  pm.memory_limit_ = memory_limit_;
  pm.min_area_ = min_area_;
  PatchAssembler assembler(tol_, min_area_, pm.materials_, pieces.size());
  for (const Piece& piece : pieces) assembler.Add(piece.corners, piece.surface, piece.material);
  pm.data_ = std::move(assembler).Finish(pool);
  pm.data_.scene.lights = data_.scene.lights;
  pm.data_.scene.sky = data_.scene.sky;
  return pm;
}

}  // namespace radfarm
