// The atrium: a generated courtyard of the size and kind of the architectural scenes that
// real-time GI is measured on (a 30 x 13 m court open to the sky, 15 m high, two storeys of
// arcades, about 250k triangles and 43 procedural textures), written by our own code so the
// repository ships no third-party data. `rolypoly render --scene atrium` loads it from a cache
// file (src/app/atrium_scene.h); `gen_load_scene OUT.glb --atrium` writes it.
//
// World units are metres: x runs along the court (-15..15), z across it (the arcade facades at
// z = +-6.5, the aisles' back walls at +-10), y up (floor 0, parapet top 15). Light intensities
// are the renderer's (glTF candela or lux / pi, frame_scene.h PunctualLight).
// Deterministic: integer hashing and fixed formulas only, so every run builds the same assets
// and the exported file has the same bytes.
#pragma once

#include "scene/frame_scene.h"

namespace rp::scene {

// Names the generator's output: change it whenever make_atrium's result changes, so a cached
// file of an older atrium is never loaded in its place.
inline constexpr const char* kAtriumVersion = "atrium-1";

struct Atrium {
  SceneAssets assets;
  FrameScene frame;  // camera at eye height looking along the court, the sun and the lamps
};

Atrium make_atrium();

}  // namespace rp::scene
