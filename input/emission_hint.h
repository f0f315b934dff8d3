// The hint added to "nothing to light" when an OBJ's materials suggest a light that lost its
// emission on export. Blender writes a material built on an Emission shader node (no Principled
// BSDF) as `Ke 0` with its defaults `Ka 1`, `Kd 0.8`: the light the artist saw is gone from the
// MTL, and the usual clue left is the material's name ("Lamp", "Ceiling light") or an ambient
// colour some exporters put a glow into.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/rgb.h"

namespace radfarm {

// A material faces use, none of which emits.
struct DarkMaterial {
  std::string name;
  Rgb ambient;           // MTL Ka
  std::string mtl_path;  // where it was defined; empty for the default grey
  uint32_t newmtl_line = 0;
  uint32_t ka_line = 0;
};

// Whether a material name reads like a light source: lamp, light, emission, emitter, glow, bulb,
// luminaire, neon (case-insensitive, anywhere in the name; "lightgrey" counts, and costs only an
// unneeded hint).
bool LooksEmissive(const std::string& name);

// "; material 'Lamp' (room.mtl:4) ..." naming the materials whose name looks emissive, or failing
// that those with Ka > 0, and what to do; empty when neither clue is there.
std::string EmissionHint(const std::vector<DarkMaterial>& materials);

}  // namespace radfarm
