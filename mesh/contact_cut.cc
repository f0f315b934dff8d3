#include "mesh/contact_cut.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "mesh/point_grid.h"
#include "mesh/polygon.h"

namespace radfarm {
namespace {

struct Segment {
  Vec3 a, b;
  Vec3 normal;  // of the face standing on the segment
};

// True when p lies inside the polygon (counter-clockwise about n) or within tol of it.
bool InsideOrOn(const std::vector<Vec3>& polygon, const Vec3& n, const Vec3& p, double tol) {
  for (size_t i = 0; i < polygon.size(); ++i) {
    if (DistanceToSegment(p, polygon[i], polygon[(i + 1) % polygon.size()]) <= tol) return true;
  }
  // Crossing number in the plane.
  const std::vector<Point2> q = ProjectToPlane(polygon, polygon[0], n);
  const Point2 x = ProjectToPlane({p}, polygon[0], n)[0];
  bool inside = false;
  for (size_t i = 0, j = q.size() - 1; i < q.size(); j = i++) {
    if ((q[i].y > x.y) != (q[j].y > x.y) &&
        x.x < q[j].x + (x.y - q[j].y) * (q[i].x - q[j].x) / (q[i].y - q[j].y)) {
      inside = !inside;
    }
  }
  return inside;
}

// True when segment ab runs along one edge of the polygon's outline.
bool AlongOutline(const std::vector<Vec3>& polygon, const Vec3& a, const Vec3& b, double tol) {
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Vec3& p = polygon[i];
    const Vec3& q = polygon[(i + 1) % polygon.size()];
    if (DistanceToSegment(a, p, q) <= tol && DistanceToSegment(b, p, q) <= tol) return true;
  }
  return false;
}

// The edge of `g` that lies in the plane (p0, n), when g rises in front of the plane from it.
bool StandingEdge(const CleanFace& g, const Vec3& p0, const Vec3& n, double tol, Segment* edge) {
  const size_t k = g.corners.size();
  int on = 0;
  size_t first = 0;
  for (size_t i = 0; i < k; ++i) {
    const double d = Dot(g.corners[i] - p0, n);
    if (std::fabs(d) <= tol) {
      if (on++ == 0) first = i;
    } else if (d < 0) {
      return false;  // reaches behind the plane
    }
  }
  if (on != 2) return false;
  // The two corners on the plane must be neighbours.
  if (std::fabs(Dot(g.corners[(first + 1) % k] - p0, n)) <= tol) {
    *edge = {g.corners[first], g.corners[(first + 1) % k], g.normal};
    return true;
  }
  if (first == 0 && std::fabs(Dot(g.corners[k - 1] - p0, n)) <= tol) {
    *edge = {g.corners[k - 1], g.corners[0], g.normal};
    return true;
  }
  return false;
}

double Area(const std::vector<Vec3>& polygon, const Vec3& n) {
  return polygon.size() < 3 ? 0.0 : Dot(VectorArea(polygon), n);
}

// How far in front of a face a sheet of area `sheet_area` may hang and still cover it: kSheetGap of
// its size, or up to `reach` (a few patch sizes) while that is at most kSheetGapFar of its size.
double LargestSheetGap(double sheet_area, double reach) {
  const double size = std::sqrt(sheet_area);
  return std::max(kSheetGap * size, std::min(reach, kSheetGapFar * size));
}

// The outline of `g` projected onto the plane (p0, n), when g is a sheet over that plane: parallel
// to it, facing the same way (its back toward the plane), in front of it by more than tol and at
// most LargestSheetGap, its projection inside `outline`.
bool CoveringSheet(const CleanFace& g, const std::vector<Vec3>& outline, const Vec3& p0,
                   const Vec3& n, double tol, double reach, Footprint* footprint) {
  if (Dot(g.normal, n) < 1 - 1e-9) return false;
  const double gap = Dot(g.corners[0] - p0, n);
  if (gap <= tol || gap > LargestSheetGap(g.area, reach)) return false;
  Footprint c;
  for (const Vec3& x : g.corners) {
    const double h = Dot(x - p0, n);
    if (std::fabs(h - gap) > tol) return false;  // not parallel
    c.push_back(x - n * h);
    if (!InsideOrOn(outline, n, c.back(), tol)) return false;
  }
  if (Area(c, n) < 0) std::reverse(c.begin(), c.end());
  RemoveRedundantCorners(tol, &c);
  if (c.size() < 3 || !IsStrictlyConvex(c, n)) return false;
  *footprint = std::move(c);
  return true;
}

// The faces' corners in a spatial hash: the faces that can stand on or cover a face all have their
// corners near it, so each face's tests visit those instead of every other face (a scene of many
// small faces would be quadratic).
class CornerIndex {
 public:
  explicit CornerIndex(const std::vector<CleanFace>& faces) : grid_(CellSize(faces)) {
    for (uint32_t f = 0; f < faces.size(); ++f) {
      for (const Vec3& c : faces[f].corners) {
        grid_.Add(c);
        owner_.push_back(f);
      }
    }
  }

  // The faces other than `self` with a corner within `reach` of `face`'s box grown by how far
  // its corners stray from the plane (p0, its normal), ascending.
  std::vector<uint32_t> Near(const CleanFace& face, const Vec3& p0, double reach,
                             uint32_t self) const {
    Bounds3 box;
    double off_plane = 0;
    for (const Vec3& c : face.corners) {
      box.Extend(c);
      off_plane = std::max(off_plane, std::fabs(Dot(c - p0, face.normal)));
    }
    const double grow = reach + off_plane;
    box.lo = box.lo - Vec3{grow, grow, grow};
    box.hi = box.hi + Vec3{grow, grow, grow};
    std::vector<uint32_t> out;
    // Corner ids run face by face, so their owners come ascending too.
    for (uint32_t id : grid_.InBox(box)) {
      if (owner_[id] != self && (out.empty() || out.back() != owner_[id])) {
        out.push_back(owner_[id]);
      }
    }
    return out;
  }

 private:
  // The median face's box diagonal: a face's query then visits a few cells per face it meets.
  static double CellSize(const std::vector<CleanFace>& faces) {
    std::vector<double> sizes;
    for (const CleanFace& f : faces) {
      Bounds3 b;
      for (const Vec3& c : f.corners) b.Extend(c);
      sizes.push_back(b.Diagonal());
    }
    if (sizes.empty()) return 1;
    std::nth_element(sizes.begin(), sizes.begin() + sizes.size() / 2, sizes.end());
    return sizes[sizes.size() / 2];
  }

  PointGrid grid_;
  std::vector<uint32_t> owner_;  // per corner id, its face
};

struct Loop {
  std::vector<Vec3> corners;
  std::vector<size_t> segments;  // indices of the segments it was joined from
};

// Closed loops of segments joined end to end (within tol); open chains are dropped.
std::vector<Loop> Loops(const std::vector<Segment>& segments, double tol) {
  std::vector<Loop> loops;
  std::vector<bool> used(segments.size(), false);
  for (size_t s = 0; s < segments.size(); ++s) {
    if (used[s]) continue;
    used[s] = true;
    std::vector<Vec3> loop = {segments[s].a};
    std::vector<size_t> members = {s};
    Vec3 end = segments[s].b;
    bool closed = false;
    for (size_t steps = 0; steps < segments.size(); ++steps) {
      if (Length(end - loop[0]) <= tol) {
        closed = true;
        break;
      }
      bool found = false;
      for (size_t t = 0; t < segments.size() && !found; ++t) {
        if (used[t]) continue;
        if (Length(segments[t].a - end) <= tol) {
          loop.push_back(segments[t].a);
          end = segments[t].b;
          found = used[t] = true;
        } else if (Length(segments[t].b - end) <= tol) {
          loop.push_back(segments[t].b);
          end = segments[t].a;
          found = used[t] = true;
        }
        if (found) members.push_back(t);
      }
      if (!found) break;
    }
    if (closed && loop.size() >= 3) loops.push_back({std::move(loop), std::move(members)});
  }
  return loops;
}

// Whether three or more segment ends meet at one point: solids side by side (a wall's segments and
// the lintels between them) share edges there, and Loops' first-come chaining can then walk from
// one solid's outline into its neighbour's and close no loop, or the wrong one.
bool Branches(const std::vector<Segment>& segments, double tol) {
  std::vector<Vec3> ends;
  for (const Segment& s : segments) ends.insert(ends.end(), {s.a, s.b});
  for (size_t i = 0; i < ends.size(); ++i) {
    int meeting = 0;
    for (const Vec3& e : ends) meeting += Length(e - ends[i]) <= tol;
    if (meeting > 2) return true;
  }
  return false;
}

// The bounded faces of the segments' planar arrangement (in the plane with unit normal n), each
// traced once: from every segment in each direction, taking at every corner the sharpest turn to
// one side walks around the smallest face on that side; a walk that turns the other way overall is
// the outline of the whole arrangement and is dropped.
std::vector<Loop> FaceLoops(const std::vector<Segment>& segments, const Vec3& n, double tol) {
  // Corners: segment ends merged within tol, in order of first appearance.
  std::vector<Vec3> corners;
  auto corner_of = [&](const Vec3& p) {
    for (size_t i = 0; i < corners.size(); ++i) {
      if (Length(corners[i] - p) <= tol) return i;
    }
    corners.push_back(p);
    return corners.size() - 1;
  };
  std::vector<std::pair<size_t, size_t>> ends;  // per segment, its two corners
  for (const Segment& s : segments) {
    const size_t a = corner_of(s.a);
    ends.emplace_back(a, corner_of(s.b));
  }
  std::vector<Loop> loops;
  std::vector<std::vector<size_t>> seen;  // each loop's sorted segments
  for (size_t s = 0; s < segments.size(); ++s) {
    for (const bool reverse : {false, true}) {
      for (const double side : {1.0, -1.0}) {  // sharpest turn left, then right
        size_t from = reverse ? ends[s].second : ends[s].first;
        size_t at = reverse ? ends[s].first : ends[s].second;
        const size_t start = from;
        Loop loop{{corners[from]}, {s}};
        size_t last = s;
        bool closed = false;
        for (size_t steps = 0; steps < segments.size() && !closed; ++steps) {
          if (at == start) {
            closed = true;
            break;
          }
          loop.corners.push_back(corners[at]);
          const Vec3 in = corners[at] - corners[from];
          size_t best = segments.size();
          double best_turn = -INFINITY;
          for (size_t t = 0; t < segments.size(); ++t) {
            if (t == last || (ends[t].first != at && ends[t].second != at)) continue;
            const size_t next = ends[t].first == at ? ends[t].second : ends[t].first;
            const Vec3 out = corners[next] - corners[at];
            const double turn = side * std::atan2(Dot(n, Cross(in, out)), Dot(in, out));
            if (turn > best_turn) {
              best_turn = turn;
              best = t;
            }
          }
          if (best == segments.size()) break;  // an open end
          loop.segments.push_back(best);
          last = best;
          from = at;
          at = ends[best].first == at ? ends[best].second : ends[best].first;
        }
        // Turning left all round goes counter-clockwise about n around a bounded face.
        if (!closed || side * Dot(VectorArea(loop.corners), n) <= 0) continue;
        std::vector<size_t> key = loop.segments;
        std::sort(key.begin(), key.end());
        if (std::find(seen.begin(), seen.end(), key) != seen.end()) continue;
        seen.push_back(std::move(key));
        loops.push_back(std::move(loop));
      }
    }
  }
  return loops;
}

// The part of a convex polygon where Dot(m, x - c) * side >= 0 (Sutherland-Hodgman).
std::vector<Vec3> ClipHalfSpace(const std::vector<Vec3>& polygon, const Vec3& m, const Vec3& c,
                                double side) {
  std::vector<Vec3> out;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Vec3& a = polygon[i];
    const Vec3& b = polygon[(i + 1) % polygon.size()];
    const double da = side * Dot(m, a - c), db = side * Dot(m, b - c);
    if (da >= 0) out.push_back(a);
    if ((da >= 0) != (db >= 0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

void Emit(std::vector<Vec3> part, const Vec3& n, double tol, double min_area,
          std::vector<PieceCorners>* out) {
  RemoveRedundantCorners(tol, &part);
  if (part.size() < 3 || Area(part, n) < min_area) return;
  if (part.size() <= 4) {
    PieceCorners piece;
    std::copy(part.begin(), part.end(), piece.corners.begin());
    piece.count = static_cast<uint8_t>(part.size());
    out->push_back(piece);
    return;
  }
  for (size_t i = 1; i + 1 < part.size(); ++i) {  // convex: a fan
    out->push_back({{part[0], part[i], part[i + 1], {}}, 3});
  }
}

}  // namespace

std::vector<std::vector<Footprint>> FindFootprints(const std::vector<CleanFace>& faces,
                                                   double tol) {
  std::vector<std::vector<Footprint>> out(faces.size());
  const CornerIndex index(faces);
  for (size_t f = 0; f < faces.size(); ++f) {
    const CleanFace& face = faces[f];
    const Vec3 p0 = face.corners[0];
    // A standing edge's ends lie within tol of the face, its plane and its outline.
    std::vector<Segment> segments;
    for (uint32_t g : index.Near(face, p0, tol, static_cast<uint32_t>(f))) {
      Segment edge;
      if (!StandingEdge(faces[g], p0, face.normal, tol, &edge)) continue;
      if (AlongOutline(face.corners, edge.a, edge.b, tol)) continue;
      if (!InsideOrOn(face.corners, face.normal, edge.a, tol) ||
          !InsideOrOn(face.corners, face.normal, edge.b, tol)) {
        continue;
      }
      segments.push_back(edge);
    }
    std::vector<Loop> loops =
        Branches(segments, tol) ? FaceLoops(segments, face.normal, tol) : Loops(segments, tol);
    for (Loop& loop : loops) {
      std::vector<Vec3>& c = loop.corners;
      if (Area(c, face.normal) < 0) std::reverse(c.begin(), c.end());
      RemoveRedundantCorners(tol, &c);
      if (c.size() < 3 || !IsStrictlyConvex(c, face.normal)) continue;
      // A solid's sides face away from its footprint; a room's walls, standing on a larger floor
      // in a closed ring, face into it: the floor inside is the room's, not covered.
      const Vec3 centre = AreaCentroid(c);
      bool outward = true;
      for (size_t s : loop.segments) {
        outward = outward && Dot(segments[s].normal, centre - segments[s].a) < 0;
      }
      if (outward) out[f].push_back(std::move(c));
    }
  }
  return out;
}

std::vector<std::vector<Footprint>> FindCoveringSheets(const std::vector<CleanFace>& faces,
                                                       double tol, double reach) {
  std::vector<std::vector<Footprint>> out(faces.size());
  const CornerIndex index(faces);
  for (size_t f = 0; f < faces.size(); ++f) {
    const CleanFace& face = faces[f];
    // A sheet's outline projects within tol of the face's, so its area is at most the face's
    // grown by tol all round, and its gap at most LargestSheetGap of that area.
    double perimeter = 0;
    for (size_t i = 0; i < face.corners.size(); ++i) {
      perimeter += Length(face.corners[(i + 1) % face.corners.size()] - face.corners[i]);
    }
    const double largest_gap =
        LargestSheetGap(1.001 * (face.area + perimeter * tol + 4 * tol * tol), reach);
    for (uint32_t g :
         index.Near(face, face.corners[0], tol + largest_gap, static_cast<uint32_t>(f))) {
      Footprint sheet;
      if (CoveringSheet(faces[g], face.corners, face.corners[0], face.normal, tol, reach, &sheet)) {
        out[f].push_back(std::move(sheet));
      }
    }
  }
  return out;
}

double CutFootprints(const std::vector<Footprint>& footprints, const Vec3& normal, double tol,
                     double min_area, std::vector<PieceCorners>* pieces,
                     std::vector<PieceCorners>* covered) {
  double dropped = 0;
  for (const Footprint& c : footprints) {
    const size_t k = c.size();
    std::vector<Vec3> inward(k);  // unit normals of the footprint's edges, pointing inside
    for (size_t i = 0; i < k; ++i) inward[i] = Normalize(Cross(normal, c[(i + 1) % k] - c[i]));
    std::vector<PieceCorners> kept;
    for (const PieceCorners& piece : *pieces) {
      const std::vector<Vec3> p(piece.corners.begin(), piece.corners.begin() + piece.count);
      bool outside = false, inside = true;
      for (size_t i = 0; i < k && !outside; ++i) {
        bool all_out = true;
        for (const Vec3& x : p) {
          const double s = Dot(inward[i], x - c[i]);
          all_out = all_out && s <= tol;
          inside = inside && s >= -tol;
        }
        outside = all_out;
      }
      // The piece's own edges may separate it too.
      for (size_t j = 0; j < p.size() && !outside; ++j) {
        const Vec3 m = Cross(normal, p[(j + 1) % p.size()] - p[j]);
        bool all_out = true;
        for (const Vec3& x : c) all_out = all_out && Dot(m, x - p[j]) <= tol * Length(m);
        outside = all_out;
      }
      if (outside) {
        kept.push_back(piece);
        continue;
      }
      if (inside) {
        dropped += Area(p, normal);
        if (covered) covered->push_back(piece);
        continue;
      }
      // Split: the part outside edge 0, then of the rest the part outside edge 1, and so on; what
      // is left at the end lies under the footprint.
      std::vector<Vec3> rest = p;
      for (size_t i = 0; i < k && rest.size() >= 3; ++i) {
        Emit(ClipHalfSpace(rest, inward[i], c[i], -1), normal, tol, min_area, &kept);
        rest = ClipHalfSpace(rest, inward[i], c[i], +1);
      }
      dropped += std::max(0.0, Area(rest, normal));
      if (covered) Emit(rest, normal, tol, min_area, covered);
    }
    *pieces = std::move(kept);
  }
  return dropped;
}

}  // namespace radfarm
